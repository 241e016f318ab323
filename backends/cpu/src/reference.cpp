// sao::cpu::run — validation, then the planned passes of effect/sao.glsl in order, each a
// parallel loop over rows of its dispatch. The per-texel math lives in kernels.h.
#include "sao/cpu/reference.h"

#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <new>
#include <string>
#include <thread>
#include <type_traits>

#include "kernels.h"
#include "sao/schedule.h"
#include "sao/cpu/parallel.h"

namespace sao::cpu {

using namespace detail;

namespace {

std::string extentText(Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

Status invalid(std::string message) { return Status::error(StatusCode::InvalidInput, std::move(message)); }

bool knownFormat(DepthFormat f) {
  switch (f) {
    case DepthFormat::D16:
    case DepthFormat::D24:
    case DepthFormat::D32F:
    case DepthFormat::LinearZ: return true;
  }
  return false;
}

std::string expectedText(const Camera& camera, Extent expected) {
  return extentText(expected) + " (viewport " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
         " + 2 * guard band " + std::to_string(camera.guardBand) + ")";
}

Status checkDepth(const char* name, const DepthImage& d, const Camera& camera, Extent expected) {
  if (d.extent.width == 0 || d.extent.height == 0)
    return invalid(std::string(name) + " is empty (" + extentText(d.extent) + "); expected " +
                   expectedText(camera, expected));
  if (d.extent != expected)
    return invalid(std::string(name) + " is " + extentText(d.extent) + ", but the plan expects " +
                   expectedText(camera, expected));
  const std::size_t texels = std::size_t(d.extent.width) * d.extent.height;
  if (d.texels.size() != texels)
    return invalid(std::string(name) + " holds " + std::to_string(d.texels.size()) + " texels, but its extent " +
                   extentText(d.extent) + " needs " + std::to_string(texels));
  return Status::success();
}

Status checkNormals(const FloatImage& n, const Camera& camera, Extent expected) {
  if (n.channels != 4)
    return Status::error(StatusCode::UnsupportedFormat,
                         "normals have " + std::to_string(n.channels) +
                             " channels; 4 are expected (rgba16f, camera-space normal in .xyz)");
  if (n.extent.width == 0 || n.extent.height == 0)
    return invalid("normals are empty (" + extentText(n.extent) + "); expected " + expectedText(camera, expected));
  if (n.extent != expected)
    return invalid("normals are " + extentText(n.extent) + ", but the plan expects " + expectedText(camera, expected));
  const std::size_t values = std::size_t(n.extent.width) * n.extent.height * 4;
  if (n.data.size() != values)
    return invalid("normals hold " + std::to_string(n.data.size()) + " floats, but their extent " +
                   extentText(n.extent) + " with 4 channels needs " + std::to_string(values));
  return Status::success();
}

std::size_t variantIndex(gen::VariantId id) { return static_cast<std::size_t>(id); }

template <typename T>
FloatImage toFloatImage(const Image<T>& src) {
  FloatImage out(Extent{std::uint32_t(src.w), std::uint32_t(src.h)}, std::uint32_t(src.ch));
  for (std::size_t i = 0; i < src.v.size(); ++i) out.data[i] = static_cast<float>(src.v[i]);
  return out;
}

// ------------------------------------------------------------------------------------------------
// The passes, in T.

template <typename T>
class Pipeline {
 public:
  Pipeline(const Inputs& in, const Plan& plan, const gen::SaoParams& params, unsigned threads)
      : in_(in), plan_(plan), P_(params), threads_(threads) {
    normalsSupplied_ = plan.variants[variantIndex(gen::VariantId::NORMALS_SUPPLIED)] != 0;
    twoLayer_ = plan.variants[variantIndex(gen::VariantId::TWO_LAYER)] != 0;
    zHierarchy_ = plan.variants[variantIndex(gen::VariantId::Z_HIERARCHY)] != 0;
  }

  // Runs the schedule's dispatches in order (sao/schedule.h); images are plain arrays, so its
  // hazards need nothing here.
  Status execute(Result& out, bool measureTime) {
    if (measureTime) out.timings.method = TimingMethod::CpuClock;
    const Schedule schedule = makeSchedule(plan_);
    auto start = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < schedule.dispatches.size(); ++i) {
      const ScheduledDispatch& d = schedule.dispatches[i];
      if (Status st = run(d, schedule.bindingsOf(d)); !st) return st;
      const bool lastOfPass = i + 1 == schedule.dispatches.size() || schedule.dispatches[i + 1].passIndex != d.passIndex;
      if (measureTime && lastOfPass) {
        const auto now = std::chrono::steady_clock::now();
        const std::chrono::duration<double, std::milli> ms = now - start;
        out.timings.passes.push_back({std::string(gen::pass(d.pass).name), ms.count()});
        start = now;
      }
    }
    for (const auto& level : csz_) out.csz.push_back(toFloatImage(level));
    for (const auto& level : csz2_) out.csz2.push_back(toFloatImage(level));
    out.aoRaw = toFloatImage(aoRaw_);
    if (haveBlurH_) out.aoBlurH = toFloatImage(aoBlurH_);
    out.ao = toFloatImage(ao_);
    return Status::success();
  }

 private:
  Status run(const ScheduledDispatch& d, std::span<const ScheduledBinding> bindings) {
    switch (d.pass) {
      case gen::PassId::linear_z: linearZ(); break;
      case gen::PassId::mips: mips(static_cast<int>(d.level)); break;
      case gen::PassId::ao_sample: return aoSample();
      case gen::PassId::blur_h:
        blur(readImage(bindings), aoBlurH_, 1, 0, false);
        haveBlurH_ = true;
        break;
      case gen::PassId::blur_v: blur(readImage(bindings), ao_, 0, 1, true); break;
      default:
        return invalid("the plan holds pass '" + std::string(gen::pass(d.pass).name) +
                       "', which the CPU reference does not implement");
    }
    return Status::success();
  }

  // The (A, key) image a blur dispatch reads: its sampled binding, aliases already resolved.
  const Image<T>& readImage(std::span<const ScheduledBinding> bindings) const {
    for (const ScheduledBinding& b : bindings)
      if (!b.write) return b.resource == gen::ResourceId::ao_raw ? aoRaw_ : aoBlurH_;
    return aoRaw_;
  }

  // Pass linear_z: one invocation per depth texel.
  void linearZ() {
    const int w = int(plan_.inputExtent.width), h = int(plan_.inputExtent.height);
    csz_.assign(1, Image<T>(w, h, 1));
    if (twoLayer_) csz2_.assign(1, Image<T>(w, h, 1));
    parallelFor(h, threads_, [&](int y) {
      for (int x = 0; x < w; ++x) {
        csz_[0].at(x, y) = zFromDepth(texel(*in_.depth, x, y), P_);
        if (twoLayer_) csz2_[0].at(x, y) = zFromDepth(texel(*in_.depth2, x, y), P_);
      }
    });
  }

  // texelFetch(in_depth, p, 0).r. Double: the exact value v / (2^n - 1) of a unorm texel (D16,
  // D24), the float itself for D32F and LinearZ. Float: what the GPU's texture unit hands the
  // shader; for unorm depth we model Mesa's llvmpipe / lavapipe (gallivm), which multiplies by
  // the float reciprocal, float(v) * float(1 / (2^n - 1)), instead of rounding v / (2^n - 1)
  // correctly: the two differ by one ulp on about half of the D24 texels, and D24 2^24 - 2 reads
  // as 1.0 (the clear value, so sky). Other GPUs may round either way.
  static T texel(const DepthImage& d, int x, int y) {
    if constexpr (std::is_same_v<T, float>) {
      const std::uint32_t t = d.texels[std::size_t(y) * d.extent.width + std::size_t(x)];
      switch (d.format) {
        case DepthFormat::D16: return float(t & 0xFFFFu) * kUnorm16Scale;
        case DepthFormat::D24: return float(t & 0xFFFFFFu) * kUnorm24Scale;
        case DepthFormat::D32F:
        case DepthFormat::LinearZ: break;
      }
    }
    return static_cast<T>(d.value(std::uint32_t(x), std::uint32_t(y)));
  }
  static constexpr float kUnorm16Scale = float(1.0 / 65535.0);
  static constexpr float kUnorm24Scale = float(1.0 / 16777215.0);

  // Pass mips, level m from level m - 1.
  void mips(int m) {
    const std::size_t level = std::size_t(m);
    const int w = std::max(csz_[0].w >> m, 1), h = std::max(csz_[0].h >> m, 1);
    csz_.resize(level + 1);  // levels are produced in order 1, 2, ...
    csz_[level] = Image<T>(w, h, 1);
    if (twoLayer_) {
      csz2_.resize(level + 1);
      csz2_[level] = Image<T>(w, h, 1);
    }
    const Image<T>& prev = csz_[level - 1];  // in_csz: a view of level m - 1, read at lod 0
    parallelFor(h, threads_, [&](int y) {
      for (int x = 0; x < w; ++x) {
        int sx, sy;
        rotatedGridSource(x, y, prev.w, prev.h, sx, sy);
        csz_[level].at(x, y) = prev.at(sx, sy);
        if (twoLayer_) csz2_[level].at(x, y) = csz2_[level - 1].at(sx, sy);
      }
    });
  }

  // Pass ao_sample: the body of sao_ao_main up to the shared-memory exchange, for one invocation.
  void sampleInvocation(int px, int py, T& A, T& key) const {
    const Image<T>& z0 = csz_[0];
    const bool inside = px < std::min(P_.ao_size.x, aoRaw_.w) && py < std::min(P_.ao_size.y, aoRaw_.h);
    const int cx = std::clamp(px + P_.guard.x, 0, z0.w - 1);
    const int cy = std::clamp(py + P_.guard.y, 0, z0.h - 1);
    const T zc = z0.at(cx, cy);
    A = T(1);
    key = T(0);
    if (!inside || isSky(zc)) return;

    const Vec3<T> C = position(T(cx) + T(0.5), T(cy) + T(0.5), zc, P_);
    Vec3<T> n;
    if (normalsSupplied_) {
      const FloatImage& ni = *in_.normals;
      n = decodeNormal(Vec3<T>{T(quantizeHalf(ni.at(std::uint32_t(cx), std::uint32_t(cy), 0))),
                               T(quantizeHalf(ni.at(std::uint32_t(cx), std::uint32_t(cy), 1))),
                               T(quantizeHalf(ni.at(std::uint32_t(cx), std::uint32_t(cy), 2)))});
    } else {
      n = reconstructNormal(z0, cx, cy, C, P_);
    }
    const T r_px = screenRadius(zc, P_);
    const std::uint32_t phase = pixelPhase(std::uint32_t(px), std::uint32_t(py));
    const int s = std::clamp(P_.samples, 1, gen::SAO_MAX_SAMPLES);
    T sum = T(0);
    for (int i = 0; i < s; ++i) {
      T h;
      int tx, ty;
      spiralTap(cx, cy, i, s, phase, r_px, P_, tx, ty, h);
      const int m = zHierarchy_ ? mipLevel(h, P_.log_q, P_.max_mip) : 0;
      const int mx = mipTexel(tx, m, z0.w), my = mipTexel(ty, m, z0.h);
      const T qx = T(tx) + T(0.5), qy = T(ty) + T(0.5);
      T o = tapObscurance(C, n, qx, qy, csz_[std::size_t(m)].at(mx, my), P_);
      if (twoLayer_) o = glslMax(o, tapObscurance(C, n, qx, qy, csz2_[std::size_t(m)].at(mx, my), P_));
      sum += o;
    }
    A = visibility(sum, P_);
    key = zc;
  }

  // Pass ao_sample over work groups: each group computes its invocations' (A, key) into
  // "shared memory", then the two reconstruction steps separated as the barriers separate them.
  // Invocations outside the AO buffer take part with A = 1, key = +0.0 (sky) and store nothing.
  Status aoSample() {
    const gen::PassInfo& info = gen::pass(gen::PassId::ao_sample);
    const int LX = int(info.localX), LY = int(info.localY);
    if (LX <= 0 || LY <= 0 || (LX & 1) || (LY & 1))
      return invalid("ao_sample's local size " + std::to_string(LX) + "x" + std::to_string(LY) +
                     " is not even; the 2x2 reconstruction needs whole quads in a work group");
    if (P_.max_mip < 0 || std::size_t(P_.max_mip) >= csz_.size() || (twoLayer_ && csz2_.size() != csz_.size()))
      return invalid("max_mip " + std::to_string(P_.max_mip) + " does not match the " +
                     std::to_string(csz_.size()) + " csz levels computed");
    const int W = int(plan_.aoExtent.width), H = int(plan_.aoExtent.height);
    aoRaw_ = Image<T>(W, H, 2);
    const int groupsX = (W + LX - 1) / LX, groupsY = (H + LY - 1) / LY;
    const T threshold = P_.quad_edge_threshold;
    parallelFor(groupsY, threads_, [&](int gy) {
      std::vector<T> quadA(std::size_t(LX) * LY), quadH(quadA.size()), quadZ(quadA.size());
      for (int gx = 0; gx < groupsX; ++gx) {
        // Up to the first barrier: every invocation's A and key.
        for (int ly = 0; ly < LY; ++ly)
          for (int lx = 0; lx < LX; ++lx) {
            const std::size_t li = std::size_t(ly) * LX + lx;
            sampleInvocation(gx * LX + lx, gy * LY + ly, quadA[li], quadZ[li]);
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
            if (px < std::min(P_.ao_size.x, W) && py < std::min(P_.ao_size.y, H)) {
              aoRaw_.at(px, py, 0) = av;
              aoRaw_.at(px, py, 1) = quadZ[li];
            }
          }
      }
    });
    return Status::success();
  }

  // Passes blur_h (final = false: writes (A, key)) and blur_v (final = true: writes A, rounded to
  // binary16 in Float precision as sao_round_to_half does, unrounded in Double).
  void blur(const Image<T>& src, Image<T>& dst, int dx, int dy, bool final) {
    const int W = src.w, H = src.h;
    dst = Image<T>(W, H, final ? 1 : 2);
    parallelFor(H, threads_, [&](int y) {
      for (int x = 0; x < W; ++x) {
        T a, key;
        bilateralBlur(src, x, y, dx, dy, P_, a, key);
        if (final) {
          if constexpr (std::is_same_v<T, float>) a = roundToHalf(a);
          dst.at(x, y, 0) = a;
        } else {
          dst.at(x, y, 0) = a;
          dst.at(x, y, 1) = key;
        }
      }
    });
  }

  const Inputs& in_;
  const Plan& plan_;
  const Block<T> P_;
  const unsigned threads_;
  bool normalsSupplied_ = false, twoLayer_ = false, zHierarchy_ = false;
  std::vector<Image<T>> csz_, csz2_;
  Image<T> aoRaw_, aoBlurH_, ao_;
  bool haveBlurH_ = false;
};

Status validateAndPlan(const Settings& settings, const Camera& camera, const Inputs& in, Result& r) {
  if (in.depth == nullptr) return invalid("no depth input: Inputs::depth is null");
  if (!knownFormat(in.depth->format))
    return Status::error(StatusCode::UnsupportedFormat,
                         "depth has an unknown format (" + std::to_string(int(in.depth->format)) + ")");
  const DepthEncoding encoding =
      in.depth->format == DepthFormat::LinearZ ? DepthEncoding::LinearZ : DepthEncoding::Hardware;
  const PlanInputs planInputs{encoding, in.normals != nullptr, in.depth2 != nullptr, false};
  if (Status st = plan(settings, camera, planInputs, r.plan); !st) return st;
  const Extent expected = r.plan.inputExtent;
  if (Status st = checkDepth("depth", *in.depth, camera, expected); !st) return st;
  if (in.depth2 != nullptr) {
    if (in.depth2->format != in.depth->format)
      return invalid(std::string("depth2 is ") + toString(in.depth2->format) + " but depth is " +
                     toString(in.depth->format) + "; both layers must have the same format and convention");
    if (Status st = checkDepth("depth2", *in.depth2, camera, expected); !st) return st;
  }
  if (in.normals != nullptr)
    if (Status st = checkNormals(*in.normals, camera, expected); !st) return st;
  if (Status st = computeConstants(settings, camera, encoding, r.params); !st) return st;
  // The block and the plan come from the same core functions; check that they agree anyway.
  if (std::uint32_t(r.params.max_mip) + 1 != r.plan.cszLevels)
    return invalid("max_mip " + std::to_string(r.params.max_mip) + " disagrees with the plan's " +
                   std::to_string(r.plan.cszLevels) + " csz levels");
  if (std::uint32_t(r.params.ao_size.x) != r.plan.aoExtent.width ||
      std::uint32_t(r.params.ao_size.y) != r.plan.aoExtent.height)
    return invalid("the block's ao_size disagrees with the plan's AO extent " + extentText(r.plan.aoExtent));
  return Status::success();
}

}  // namespace

const char* toString(Precision precision) {
  switch (precision) {
    case Precision::Double: return "double";
    case Precision::Float: return "float";
  }
  return "?";
}

Status run(const Settings& settings, const Camera& camera, const Inputs& inputs, const Options& options,
           Result& out) {
  out = Result{};
  Result r;
  if (Status st = validateAndPlan(settings, camera, inputs, r); !st) return st;
  const unsigned threads = threadCount(options.threads);
  try {
    Status st;
    const bool timed = options.measureTime;
    switch (options.precision) {
      case Precision::Float: st = Pipeline<float>(inputs, r.plan, r.params, threads).execute(r, timed); break;
      case Precision::Double: st = Pipeline<double>(inputs, r.plan, r.params, threads).execute(r, timed); break;
      default: return invalid("unknown precision " + std::to_string(int(options.precision)));
    }
    if (!st) return st;
  } catch (const std::bad_alloc&) {
    return Status::error(StatusCode::InvalidExtent, "out of memory running the CPU reference on a " +
                                                        extentText(r.plan.inputExtent) + " input");
  }
  out = std::move(r);
  return Status::success();
}

float roundToHalfAsShader(float x) { return roundToHalf(x); }

}  // namespace sao::cpu
