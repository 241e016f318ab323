// The passes of sao.glsl in C++, the oracle the GPU backends are compared with: each one runs its
// shader's main over the dispatch, operation for operation, with the library of sao_math.h, in
// parallel over rows (ao_sample over rows of work groups). Every output texel is a pure function
// of its inputs, so results are bit-identical for any thread count. Images come from the
// dispatch's resolved bindings (pass_context.h), as the shader's in_<name> / out_<name>.
// A new pass: its function here, beside its GLSL, and a case in runSaoPass (docs/adding-a-pass.md).
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "pass_context.h"
#include "sao/cpu/parallel.h"
#include "sao/schedule.h"
#include "sao/status.h"
#include "sao_math.h"
#include "sao_visibility.h"

namespace sao::cpu::detail {

inline Status passError(const ScheduledDispatch& d, const std::string& what) {
  return Status::error(StatusCode::InvalidInput,
                       "the CPU pass '" + std::string(gen::pass(d.pass).name) + "' " + what);
}

// A binding the pass reads or writes that its dispatch lacks: the effect and its C++ disagree.
inline Status missingBinding(const ScheduledDispatch& d, gen::ResourceId declared, bool write) {
  return passError(d, std::string("finds no ") + (write ? "write" : "read") + " binding of '" +
                          std::string(gen::kResources[static_cast<std::size_t>(declared)].name) + "'");
}

inline constexpr float kUnorm16Scale = float(1.0 / 65535.0);
inline constexpr float kUnorm24Scale = float(1.0 / 16777215.0);

// texelFetch(in_depth, p, 0).r. Double: the exact value v / (2^n - 1) of a unorm texel (D16,
// D24), the float itself for D32F and LinearZ. Float: what the GPU's texture unit hands the
// shader; for unorm depth we model Mesa's llvmpipe / lavapipe (gallivm), which multiplies by
// the float reciprocal, float(v) * float(1 / (2^n - 1)), instead of rounding v / (2^n - 1)
// correctly: the two differ by one ulp on about half of the D24 texels, and D24 2^24 - 2 reads
// as 1.0 (the clear value, so sky). Other GPUs may round either way.
template <typename T>
T texel(const DepthImage& d, int x, int y, int sample = 0) {
  if constexpr (std::is_same_v<T, float>) {
    const std::uint32_t t = d.raw(std::uint32_t(x), std::uint32_t(y), std::uint32_t(sample));
    switch (d.format) {
      case DepthFormat::D16: return float(t & 0xFFFFu) * kUnorm16Scale;
      case DepthFormat::D24: return float(t & 0xFFFFFFu) * kUnorm24Scale;
      case DepthFormat::D32F:
      case DepthFormat::LinearZ: break;
    }
  }
  return static_cast<T>(d.value(std::uint32_t(x), std::uint32_t(y), std::uint32_t(sample)));
}

// Whether `d` holds w x h texels from (ox, oy) on (the region the host checked; in 64 bits).
inline bool holdsRegion(const DepthImage& d, int ox, int oy, int w, int h) {
  return ox >= 0 && oy >= 0 && std::int64_t(ox) + w <= std::int64_t(d.extent.width) &&
         std::int64_t(oy) + h <= std::int64_t(d.extent.height);
}

// Level m of a z chain (every channel) from level m - 1 by the rotated grid
// (Table 1), level by level: the oracle the GPU's walk up the chain (SAO_CHAIN_FROM_BLOCK in
// effect/sao.glsl) must equal.
template <typename T>
void rotatedGridLevel(const Image<T>& prev, Image<T>& next, unsigned threads) {
  parallelFor(next.h, threads, [&](int y) {
    for (int x = 0; x < next.w; ++x) {
      int sx, sy;
      rotatedGridSource(x, y, prev.w, prev.h, sx, sy);
      for (int c = 0; c < next.ch; ++c) next.at(x, y, c) = prev.at(sx, sy, c);
    }
  });
}

// The levels of a levels=A..B write binding above its first: A + 1 .. A + levelCount - 1, each
// from the one below.
template <typename T>
void chainAbove(PassContext<T>& ctx, const ScheduledBinding& out) {
  for (std::uint32_t m = out.baseLevel + 1; m < out.baseLevel + out.levelCount; ++m)
    rotatedGridLevel(ctx.image(out.resource, m - 1), ctx.image(out.resource, m), ctx.threads);
}

// Passes linear_z (csz from depth, `second` false) and linear_z2 (csz2 from depth2): level 0, one
// invocation per depth texel, then the levels above it (levels=0..B) level by level.
template <typename T>
Status linearZPass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings,
                   bool second) {
  const gen::ResourceId chain = second ? gen::ResourceId::csz2 : gen::ResourceId::csz;
  const DepthImage* depth = second ? ctx.in.depth2 : ctx.in.depth;
  const ScheduledBinding* out = binding(d, bindings, chain, true);
  if (out == nullptr) return missingBinding(d, chain, true);
  Image<T>& csz = ctx.image(*out);
  const int w = csz.w, h = csz.h;
  const int ox = ctx.P.input_offset.x, oy = ctx.P.input_offset.y;  // texel p + input_offset
  if (depth == nullptr || !holdsRegion(*depth, ox, oy, w, h))
    return passError(d, std::string("needs the ") + (second ? "depth2" : "depth") + " input to hold the chain's extent " +
                            std::to_string(w) + "x" + std::to_string(h) + " at offset (" + std::to_string(ox) + ", " +
                            std::to_string(oy) + ")");
  // DEPTH_MULTISAMPLE (the first layer only): sample 0, or the nearest of the samples (sao_nearer_z).
  const bool multisampled = !second && ctx.variant(gen::VariantId::DEPTH_MULTISAMPLE);
  const bool nearest = multisampled && ctx.P.depth_sample_policy == gen::SAO_DEPTH_SAMPLE_NEAREST;
  if (multisampled && std::int64_t(ctx.P.depth_samples) != std::int64_t(depth->samples))
    return passError(d, "reads " + std::to_string(ctx.P.depth_samples) + " samples per texel, but depth has " +
                            std::to_string(depth->samples));
  parallelFor(h, ctx.threads, [&](int y) {
    for (int x = 0; x < w; ++x) {
      T z = zFromDepth(texel<T>(*depth, x + ox, y + oy), ctx.P);
      for (int s = 1; nearest && s < ctx.P.depth_samples; ++s)
        z = nearerZ(z, zFromDepth(texel<T>(*depth, x + ox, y + oy, s), ctx.P));
      csz.at(x, y) = z;
    }
  });
  chainAbove(ctx, *out);
  return Status::success();
}

// Pass width (THICKNESS_FROM_WIDTH): each csz texel's shares of thickness along x and y from its
// run on its own level (runShare; binary16-rounded in Float, as sao_width_texel and
// sao_width_level_texel store them, kept in Double; 1 for sky), into width_run's levels.
template <typename T>
Status widthPass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  const ScheduledBinding* in = binding(d, bindings, gen::ResourceId::csz, false);
  const ScheduledBinding* out = binding(d, bindings, gen::ResourceId::width_run, true);
  if (in == nullptr) return missingBinding(d, gen::ResourceId::csz, false);
  if (out == nullptr) return missingBinding(d, gen::ResourceId::width_run, true);
  const Image<T>& z0 = ctx.image(in->resource, 0);
  const Block<T>& P = ctx.P;
  for (std::uint32_t m = out->baseLevel; m < out->baseLevel + out->levelCount; ++m) {
    const Image<T>& zm = ctx.image(in->resource, m);
    Image<T>& share = ctx.image(out->resource, m);
    if (share.w != zm.w || share.h != zm.h || share.ch < 2)
      return passError(d, "width_run's level " + std::to_string(m) + " is not csz's extent with two channels");
    parallelFor(share.h, ctx.threads, [&](int y) {
      for (int x = 0; x < share.w; ++x) {
        const T z = zm.at(x, y);
        T sx = T(1), sy = T(1);
        if (!isSky(z) && P.thickness > T(0)) {
          sx = runShare(zm, int(m), z0.w, z0.h, x, y, z, 1, 0, P);
          sy = runShare(zm, int(m), z0.w, z0.h, x, y, z, 0, 1, P);
          if constexpr (std::is_same_v<T, float>) sx = roundToHalf(sx), sy = roundToHalf(sy);
        }
        share.at(x, y, 0) = sx;
        share.at(x, y, 1) = sy;
      }
    });
  }
  return Status::success();
}

// Pass width_resolve (THICKNESS_FROM_WIDTH): each csz_share texel of each level, its csz z and,
// along x and y apart, the first width_run share under 1 among the texel and the texels above it
// ((x/2, y/2) of the next level, clamped to it, up to the last level; 1 where there is none),
// packed as sao_pack_shares packs them (binary16: in Double too, the storage's own rounding).
template <typename T>
Status widthResolvePass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  const ScheduledBinding* inZ = binding(d, bindings, gen::ResourceId::csz, false);
  const ScheduledBinding* in = binding(d, bindings, gen::ResourceId::width_run, false);
  const ScheduledBinding* out = binding(d, bindings, gen::ResourceId::csz_share, true);
  if (inZ == nullptr) return missingBinding(d, gen::ResourceId::csz, false);
  if (in == nullptr) return missingBinding(d, gen::ResourceId::width_run, false);
  if (out == nullptr) return missingBinding(d, gen::ResourceId::csz_share, true);
  const std::uint32_t levels = out->baseLevel + out->levelCount;
  for (std::uint32_t m = out->baseLevel; m < levels; ++m) {
    const Image<T>& zm = ctx.image(inZ->resource, m);
    const Image<T>& own = ctx.image(in->resource, m);
    Image<T>& packed = ctx.image(out->resource, m);
    if (packed.w != own.w || packed.h != own.h || packed.ch < 2 || zm.w != own.w || zm.h != own.h)
      return passError(d, "csz_share's level " + std::to_string(m) +
                              " is not width_run's and csz's extent with two channels");
    parallelFor(packed.h, ctx.threads, [&](int y) {
      for (int x = 0; x < packed.w; ++x) {
        T share[2];
        for (int c = 0; c < 2; ++c) {
          T s = own.at(x, y, c);
          for (std::uint32_t j = m + 1, qx = x, qy = y; j < levels && s >= T(1); ++j) {
            const Image<T>& run = ctx.image(in->resource, j);
            qx = std::min<std::uint32_t>(qx >> 1, std::uint32_t(run.w - 1));
            qy = std::min<std::uint32_t>(qy >> 1, std::uint32_t(run.h - 1));
            s = run.at(int(qx), int(qy), c);
          }
          share[c] = s;
        }
        packed.at(x, y, 0) = zm.at(x, y);
        packed.at(x, y, 1) = T(packShares(float(share[0]), float(share[1])));
      }
    });
  }
  return Status::success();
}

// Pass ao_sample: the body of sao_ao_main up to the shared-memory exchange, for one invocation.
template <typename T>
class AoSampleInvocation {
 public:
  AoSampleInvocation(const PassContext<T>& ctx, const std::vector<Image<T>>& csz, const std::vector<Image<T>>& csz2,
                     const std::vector<Image<T>>* cszShare, const Image<T>& aoRaw, const Image<T>* history)
      : in_(ctx.in), P_(ctx.P), csz_(csz), csz2_(csz2), cszShare_(cszShare), aoRaw_(aoRaw), history_(history),
        normalsSupplied_(ctx.variant(gen::VariantId::NORMALS_SUPPLIED)),
        twoLayer_(ctx.variant(gen::VariantId::TWO_LAYER)),
        zHierarchy_(ctx.variant(gen::VariantId::Z_HIERARCHY)),
        motionVectors_(ctx.variant(gen::VariantId::MOTION_VECTORS)),
        visibilityEstimator_(ctx.variant(gen::VariantId::ESTIMATOR)),
        bentNormals_(ctx.variant(gen::VariantId::BENT_NORMALS)) {}

  // A and key for the 2x2 step; with TEMPORAL (history_ set) also this frame's history texel:
  // the accumulated sum, its frames and the packed normal (all 0 for sky and outside); with
  // BENT_NORMALS the pixel's bent normal (0 for sky and outside).
  void operator()(int px, int py, T& A, T& key, T& kept, T& frames, T& normalCode, Vec3<T>& bent) const {
    const Image<T>& z0 = csz_[0];
    const bool inside = px < std::min(P_.ao_size.x, aoRaw_.w) && py < std::min(P_.ao_size.y, aoRaw_.h);
    // The viewport pixel the (reduced) AO pixel stands for: itself at divisor 1.
    const int fx = lowRepresentative(px, P_.ao_divisor, P_.ao_size.x);
    const int fy = lowRepresentative(py, P_.ao_divisor, P_.ao_size.y);
    const int cx = std::clamp(fx + P_.guard.x, 0, z0.w - 1);
    const int cy = std::clamp(fy + P_.guard.y, 0, z0.h - 1);
    const T zc = z0.at(cx, cy);
    A = T(1);
    key = T(0);
    kept = T(0);
    frames = T(0);
    normalCode = T(0);
    bent = Vec3<T>{T(0), T(0), T(0)};
    if (!inside || isSky(zc)) return;

    const Vec3<T> C = position(T(cx) + T(0.5), T(cy) + T(0.5), zc, P_);
    Vec3<T> n;
    if (normalsSupplied_) {
      const FloatImage& ni = *in_.normals;  // texel c + input_offset (inside: checked by the host)
      const auto nx = std::uint32_t(cx + P_.input_offset.x), ny = std::uint32_t(cy + P_.input_offset.y);
      n = suppliedNormal(Vec3<T>{T(quantizeHalf(ni.at(nx, ny, 0))), T(quantizeHalf(ni.at(nx, ny, 1))),
                                 T(quantizeHalf(ni.at(nx, ny, 2)))},
                         P_);
    } else {
      n = reconstructNormal(z0, cx, cy, C, P_);
    }
    const T r_px = screenRadius(zc, P_);
    const std::uint32_t phase = pixelPhase(std::uint32_t(px), std::uint32_t(py)) + P_.frame_phase;
    const int s = std::clamp(P_.samples, 1, gen::SAO_MAX_SAMPLES);
    T sum = T(0);
    SpiralDirection<T> u = SpiralDirection<T>::start(phase, P_);
    // ESTIMATOR 1: the occlusion 1 - V of the visibility estimator (sao_visibility.h) is the sum.
    if (visibilityEstimator_) {
      Vec3<T> moment{};
      sum = visibilityOcclusion(csz_, csz2_, cszShare_, twoLayer_, zHierarchy_, cx, cy, C, n, r_px, phase,
                                radialJitter(std::uint32_t(px), std::uint32_t(py), P_), s, P_,
                                bentNormals_ ? &moment : nullptr);
      if (bentNormals_) bent = bentNormal(moment, n);
    }
    for (int i = 0; i < s && !visibilityEstimator_; ++i) {
      T h;
      int tx, ty;
      spiralTap(cx, cy, i, r_px, P_, u, tx, ty, h);
      const int m = zHierarchy_ ? mipLevel(h, P_.log_q, P_.max_mip) : 0;
      const int mx = mipTexel(tx, m, z0.w), my = mipTexel(ty, m, z0.h);
      const T qx = T(tx) + T(0.5), qy = T(ty) + T(0.5);
      T o = tapObscurance(C, n, qx, qy, csz_[std::size_t(m)].at(mx, my), P_);
      if (twoLayer_) o = glslMax(o, tapObscurance(C, n, qx, qy, csz2_[std::size_t(m)].at(mx, my), P_));
      sum += o;
    }
    if (history_) {
      // Where this surface was in the previous frame: through the cameras, or by the motion input.
      const Vec3<T> Q = toPrevious(C, P_);
      T px, py;
      if (motionVectors_) {
        const FloatImage& mv = *in_.motion;  // texel c + input_offset (inside: checked by the host)
        const auto mx = std::uint32_t(cx + P_.input_offset.x), my = std::uint32_t(cy + P_.input_offset.y);
        px = (T(cx) + T(0.5)) + T(quantizeHalf(mv.at(mx, my, 0)));  // rg16f, as the texture holds it
        py = (T(cy) + T(0.5)) + T(quantizeHalf(mv.at(mx, my, 1)));
      } else {
        previousPixel(Q, P_, px, py);
      }
      temporalAccumulate(*history_, px, py, Q.z, rotateToPrevious(n, P_), normalsSupplied_, sum, P_, kept, frames);
      sum = kept;
      normalCode = packNormal(n);
    }
    A = fade(visibility(sum, P_), zc, P_);
    key = zc;
  }

 private:
  const Inputs& in_;
  const Block<T>& P_;
  const std::vector<Image<T>>& csz_;
  const std::vector<Image<T>>& csz2_;
  const std::vector<Image<T>>* cszShare_;  // THICKNESS_FROM_WIDTH: csz_share (z, packed shares), else null
  const Image<T>& aoRaw_;
  const Image<T>* history_;  // the previous frame's (TEMPORAL), else null
  const bool normalsSupplied_, twoLayer_, zHierarchy_, motionVectors_, visibilityEstimator_, bentNormals_;
};

// The output texel at (x, y) as sao_output_texel stores it: into the channels output_mask selects,
// A quantised as the output's format holds it (Float: binary16 or 1/255 steps; Double: unrounded),
// or with output_blend multiply the channel's value times A (outputMultiply); the other channels
// keep what the image holds (the caller's contents, Inputs::output). A goes through the
// multi-bounce fit first (SAO_BOUNCED; A itself with albedo 0).
template <typename T>
bool outputIsUnorm8(const PassContext<T>& ctx) {
  const std::int32_t v = ctx.plan.variants[static_cast<std::size_t>(gen::VariantId::OUTPUT_FORMAT)];
  const gen::Format f = gen::kResources[static_cast<std::size_t>(gen::ResourceId::ao)].formats[std::size_t(v)];
  return f == gen::Format::R8 || f == gen::Format::RGBA8;
}

// A (after the multi-bounce fit) as the replace blend stores it: Float rounded as the format holds
// it, Double unrounded but for the shader's channel clamp (the fit reaches 1.0001 at A = 1 for
// albedo > 0.8).
template <typename T>
T replacedA(const PassContext<T>& ctx, T a, bool unorm8) {
  if constexpr (std::is_same_v<T, float>)
    return unorm8 ? roundToUnorm8(a) : roundToHalf(a);
  else
    return ctx.P.multi_bounce != 0 ? std::clamp(a, T(0), T(1)) : a;
}

template <typename T>
void storeOutput(const PassContext<T>& ctx, Image<T>& dst, int x, int y, T a) {
  a = multiBounce(a, ctx.P);
  const bool unorm8 = outputIsUnorm8(ctx);
  if (ctx.P.output_blend == gen::SAO_OUTPUT_BLEND_MULTIPLY) {
    for (int c = 0; c < dst.ch; ++c)
      if ((ctx.P.output_mask >> c) & 1) dst.at(x, y, c) = outputMultiply(dst.at(x, y, c), a, unorm8);
    return;
  }
  a = replacedA(ctx, a, unorm8);
  for (int c = 0; c < dst.ch; ++c)
    if ((ctx.P.output_mask >> c) & 1) dst.at(x, y, c) = a;
}

// The bent normal output's texel (BENT_NORMALS, sao_output_bent_texel): b in R, G, B (rgba8:
// 0.5 + 0.5 b), A (through the multi-bounce fit) in A; every channel, replace (plan() refuses other
// masks and blends). Float rounds each as the format holds it, Double keeps them unrounded.
template <typename T>
void storeBentOutput(const PassContext<T>& ctx, Image<T>& dst, int x, int y, Vec3<T> b, T a) {
  const bool unorm8 = outputIsUnorm8(ctx);
  T c[3] = {b.x, b.y, b.z};
  for (T& e : c) {
    if (unorm8) e = T(0.5) + T(0.5) * e;
    if constexpr (std::is_same_v<T, float>) e = unorm8 ? roundToUnorm8(e) : roundToHalfSigned(e);
  }
  dst.at(x, y, 0) = c[0];
  dst.at(x, y, 1) = c[1];
  dst.at(x, y, 2) = c[2];
  dst.at(x, y, 3) = replacedA(ctx, multiBounce(a, ctx.P), unorm8);
}

// An (A, key) intermediate's texel (ao_raw, ao_low): with HALF_INTERMEDIATES as the rg16f
// image holds it (sao_half_texel: rounded in Float, kept in Double).
template <typename T>
void storeAKey(const PassContext<T>& ctx, Image<T>& img, int x, int y, T a, T key) {
  if (ctx.variant(gen::VariantId::HALF_INTERMEDIATES)) halfTexel(a, key);
  img.at(x, y, 0) = a;
  img.at(x, y, 1) = key;
}

// Passes ao_sample and ao_sample_output over work groups: each group computes its invocations'
// (A, key) into "shared memory", then the two reconstruction steps separated as the barriers
// separate them. Invocations outside the AO buffer take part with A = 1, key = +0.0 (sky) and store
// nothing. ao_sample stores (A, key) into ao_raw, ao_sample_output A into the output (storeOutput).
template <typename T>
Status aoSamplePass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  const bool twoLayer = ctx.variant(gen::VariantId::TWO_LAYER);
  const bool direct = d.pass == gen::PassId::ao_sample_output;
  const gen::ResourceId target = direct ? gen::ResourceId::ao : gen::ResourceId::ao_raw;
  const ScheduledBinding* in = binding(d, bindings, gen::ResourceId::csz, false);
  const ScheduledBinding* in2 = twoLayer ? binding(d, bindings, gen::ResourceId::csz2, false) : nullptr;
  const ScheduledBinding* out = binding(d, bindings, target, true);
  if (in == nullptr) return missingBinding(d, gen::ResourceId::csz, false);
  if (twoLayer && in2 == nullptr) return missingBinding(d, gen::ResourceId::csz2, false);
  if (out == nullptr) return missingBinding(d, target, true);
  // THICKNESS_FROM_WIDTH: the width pass's chain, read by the visibility estimator's taps.
  const bool fromWidth = ctx.variant(gen::VariantId::THICKNESS_FROM_WIDTH) && ctx.variant(gen::VariantId::ESTIMATOR);
  const ScheduledBinding* inWidth = fromWidth ? binding(d, bindings, gen::ResourceId::csz_share, false) : nullptr;
  if (fromWidth && inWidth == nullptr) return missingBinding(d, gen::ResourceId::csz_share, false);
  if (ctx.variant(gen::VariantId::NORMALS_SUPPLIED) && ctx.in.normals == nullptr)
    return passError(d, "reads normals, but none were supplied");
  if (ctx.variant(gen::VariantId::MOTION_VECTORS) && ctx.in.motion == nullptr)
    return passError(d, "reads motion vectors, but none were supplied");
  const std::vector<Image<T>>& csz = ctx.levels(in->resource);  // the whole chain
  const std::vector<Image<T>>& csz2 = ctx.levels(twoLayer ? in2->resource : gen::ResourceId::csz2);
  const std::vector<Image<T>>* cszShare = fromWidth ? &ctx.levels(inWidth->resource) : nullptr;
  Image<T>& dst = ctx.image(*out);
  const auto& P = ctx.P;

  const gen::PassInfo& info = gen::pass(d.pass);
  const int LX = int(info.localX), LY = int(info.localY);
  if (LX <= 0 || LY <= 0 || (LX & 1) || (LY & 1))
    return Status::error(StatusCode::InvalidInput,
                         "ao_sample's local size " + std::to_string(LX) + "x" + std::to_string(LY) +
                             " is not even; the 2x2 reconstruction needs whole quads in a work group");
  if (P.max_mip < 0 || std::size_t(P.max_mip) >= csz.size() || (twoLayer && csz2.size() != csz.size()) ||
      (cszShare && cszShare->size() != csz.size()))
    return Status::error(StatusCode::InvalidInput, "max_mip " + std::to_string(P.max_mip) + " does not match the " +
                                                       std::to_string(csz.size()) + " csz levels computed");
  if (!direct && dst.ch != 2) return passError(d, "needs a 2-channel ao_raw");
  const bool bentNormals = direct && ctx.variant(gen::VariantId::BENT_NORMALS);
  if (bentNormals && dst.ch != 4) return passError(d, "writes bent normals, which need a 4-channel output");
  // TEMPORAL: the previous frame's history in, this frame's out (sao_temporal.glsl).
  const bool temporal = ctx.variant(gen::VariantId::TEMPORAL);
  const ScheduledBinding* historyIn = temporal ? binding(d, bindings, gen::ResourceId::history, false) : nullptr;
  const ScheduledBinding* historyOut = temporal ? binding(d, bindings, gen::ResourceId::history, true) : nullptr;
  if (temporal && historyIn == nullptr) return missingBinding(d, gen::ResourceId::history, false);
  if (temporal && historyOut == nullptr) return missingBinding(d, gen::ResourceId::history, true);
  const Image<T>* previous = temporal ? &ctx.image(*historyIn) : nullptr;
  Image<T>* history = temporal ? &ctx.image(*historyOut) : nullptr;
  if (temporal && (previous->ch != 4 || history->ch != 4 || previous->w != dst.w || previous->h != dst.h ||
                   history->w != dst.w || history->h != dst.h))
    return passError(d, "needs 4-channel history images of the AO extent");
  const int W = dst.w, H = dst.h;
  const int groupsX = int(d.groupsX), groupsY = int(d.groupsY);
  const T threshold = P.quad_edge_threshold;
  const AoSampleInvocation<T> sampleInvocation(ctx, csz, csz2, cszShare, dst, previous);
  parallelFor(groupsY, ctx.threads, [&](int gy) {
    std::vector<T> quadA(std::size_t(LX) * LY), quadH(quadA.size()), quadZ(quadA.size()), kept(quadA.size()),
        frames(quadA.size()), normalCode(quadA.size());
    std::vector<Vec3<T>> bent(quadA.size());
    for (int gx = 0; gx < groupsX; ++gx) {
      // Up to the first barrier: every invocation's A and key.
      for (int ly = 0; ly < LY; ++ly)
        for (int lx = 0; lx < LX; ++lx) {
          const std::size_t li = std::size_t(ly) * LX + lx;
          sampleInvocation(gx * LX + lx, gy * LY + ly, quadA[li], quadZ[li], kept[li], frames[li], normalCode[li],
                           bent[li]);
        }
      // Between the barriers: the step along x.
      for (int ly = 0; ly < LY; ++ly)
        for (int lx = 0; lx < LX; ++lx) {
          const std::size_t li = std::size_t(ly) * LX + lx;
          const std::size_t nx = std::size_t(ly) * LX + (lx ^ 1);
          quadH[li] = quadMix(quadA[li], quadZ[li], quadA[nx], quadZ[nx], threshold);
        }
      // After the second barrier: the step along y, stored by inside invocations.
      for (int ly = 0; ly < LY; ++ly)
        for (int lx = 0; lx < LX; ++lx) {
          const std::size_t li = std::size_t(ly) * LX + lx;
          const std::size_t ny = std::size_t(ly ^ 1) * LX + lx;
          const T av = quadMix(quadH[li], quadZ[li], quadH[ny], quadZ[ny], threshold);
          const int px = gx * LX + lx, py = gy * LY + ly;
          if (px < std::min(P.ao_size.x, W) && py < std::min(P.ao_size.y, H)) {
            if (bentNormals)
              storeBentOutput(ctx, dst, px, py, bent[li], av);
            else if (direct)
              storeOutput(ctx, dst, px, py, av);
            else
              storeAKey(ctx, dst, px, py, av, quadZ[li] * P.key_scale);
            if (history) {
              history->at(px, py, 0) = kept[li];
              history->at(px, py, 1) = quadZ[li];
              history->at(px, py, 2) = frames[li];
              history->at(px, py, 3) = normalCode[li];
            }
          }
        }
    }
  });
  return Status::success();
}

// Pass blur: the bilateral blur along x into a float image (the shader's shared-memory rows, never
// rounded), then along y from it into ao_low through storeAKey (rg16f with HALF_INTERMEDIATES).
template <typename T>
Status blurPass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  const ScheduledBinding* in = binding(d, bindings, gen::ResourceId::ao_raw, false);
  const ScheduledBinding* out = binding(d, bindings, gen::ResourceId::ao_low, true);
  if (in == nullptr) return missingBinding(d, gen::ResourceId::ao_raw, false);
  if (out == nullptr) return missingBinding(d, gen::ResourceId::ao_low, true);
  const Image<T>& src = ctx.image(*in);
  Image<T>& dst = ctx.image(*out);
  if (src.ch != 2 || dst.ch != 2 || dst.w != src.w || dst.h != src.h)
    return passError(d, "needs (A, key) images of one extent");
  const int W = src.w, H = src.h;
  Image<T> rows(W, H, 2);
  parallelFor(H, ctx.threads, [&](int y) {
    for (int x = 0; x < W; ++x) bilateralBlur(src, x, y, 1, 0, ctx.P, rows.at(x, y, 0), rows.at(x, y, 1));
  });
  parallelFor(H, ctx.threads, [&](int y) {
    for (int x = 0; x < W; ++x) {
      T a, key;
      bilateralBlur(rows, x, y, 0, 1, ctx.P, a, key);
      storeAKey(ctx, dst, x, y, a, key);
    }
  });
  return Status::success();
}

// Pass output (full resolution with a blur): each pixel's A of ao_low into the output through
// storeOutput.
template <typename T>
Status outputPass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  const ScheduledBinding* in = binding(d, bindings, gen::ResourceId::ao_low, false);
  const ScheduledBinding* out = binding(d, bindings, gen::ResourceId::ao, true);
  if (in == nullptr) return missingBinding(d, gen::ResourceId::ao_low, false);
  if (out == nullptr) return missingBinding(d, gen::ResourceId::ao, true);
  const Image<T>& src = ctx.image(*in);
  Image<T>& dst = ctx.image(*out);
  if (src.ch != 2 || src.w != dst.w || src.h != dst.h) return passError(d, "needs an (A, key) image of the output's extent");
  parallelFor(dst.h, ctx.threads, [&](int y) {
    for (int x = 0; x < dst.w; ++x) storeOutput(ctx, dst, x, y, src.at(x, y, 0));
  });
  return Status::success();
}

// Pass upsample: the reduced (A, key) image to the viewport-sized output, guided by csz level 0;
// stored through storeOutput (rounded as the output's format holds it in Float, unrounded in Double).
template <typename T>
Status upsamplePass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  const ScheduledBinding* in = binding(d, bindings, gen::ResourceId::ao_low, false);
  const ScheduledBinding* z = binding(d, bindings, gen::ResourceId::csz, false);
  const ScheduledBinding* out = binding(d, bindings, gen::ResourceId::ao, true);
  if (in == nullptr) return missingBinding(d, gen::ResourceId::ao_low, false);
  if (z == nullptr) return missingBinding(d, gen::ResourceId::csz, false);
  if (out == nullptr) return missingBinding(d, gen::ResourceId::ao, true);
  const Image<T>& low = ctx.image(*in);
  const Image<T>& z0 = ctx.image(z->resource, 0);
  Image<T>& dst = ctx.image(*out);
  const auto& P = ctx.P;
  const int div = P.ao_divisor;
  if (low.ch != 2 || div < 1 || (div & (div - 1)) != 0 || P.ao_size.x != dst.w || P.ao_size.y != dst.h ||
      low.w != (dst.w + div - 1) / div || low.h != (dst.h + div - 1) / div || dst.w + P.guard.x > z0.w ||
      dst.h + P.guard.y > z0.h)
    return passError(d, "needs a power-of-two ao_divisor, an (A, key) image of the output's extent over it "
                        "and the viewport's csz");
  parallelFor(dst.h, ctx.threads, [&](int y) {
    for (int x = 0; x < dst.w; ++x) {
      storeOutput(ctx, dst, x, y,
                  upsample(low, x, y, z0.at(x + P.guard.x, y + P.guard.y), div, dst.w, dst.h, P.key_to_view));
    }
  });
  return Status::success();
}

}  // namespace sao::cpu::detail

namespace sao::cpu {

// One dispatch of a pass of sao.glsl. An effect that adds passes switches on its own first and
// falls back to this (tests/walkthrough/cpu_passes.h); a pass nobody implements is refused.
template <typename T>
Status runSaoPass(PassContext<T>& ctx, const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
  switch (d.pass) {
    case gen::PassId::linear_z: return detail::linearZPass(ctx, d, bindings, false);
    case gen::PassId::linear_z2: return detail::linearZPass(ctx, d, bindings, true);
    case gen::PassId::width: return detail::widthPass(ctx, d, bindings);
    case gen::PassId::width_resolve: return detail::widthResolvePass(ctx, d, bindings);
    case gen::PassId::ao_sample:
    case gen::PassId::ao_sample_output: return detail::aoSamplePass(ctx, d, bindings);
    case gen::PassId::blur: return detail::blurPass(ctx, d, bindings);
    case gen::PassId::output: return detail::outputPass(ctx, d, bindings);
    case gen::PassId::upsample: return detail::upsamplePass(ctx, d, bindings);
    default:
      return Status::error(StatusCode::InvalidInput, "the plan holds pass '" + std::string(gen::pass(d.pass).name) +
                                                         "', which the CPU reference does not implement");
  }
}

}  // namespace sao::cpu
