// The texel reads of ao_sample (effect/sao.glsl, sao_ao_main), replayed per work group for the
// memory-traffic model of sao-bench (samples/bench/traffic_*). Every address comes from the same
// functions of sao_math.h that AoSampleInvocation (sao_passes.h) evaluates, in float, so the taps
// are the ones the shader fetches (compile the includer with -ffp-contract=off, as sao_cpu is).
// Reads come per instruction ("step") and lane, the order a SIMT machine issues them: step 0 the
// centre z of every invocation (inside or not), then, for the invocations with geometry, the
// normal (one normals fetch, or the four csz neighbours of eq. 4), then the s taps (with the
// visibility estimator, ESTIMATOR 1: its 2*slices*m slice taps, those that leave the centre texel and
// whose MIP texel does not hold the centre's own z, each its csz texel or, under thickness_model 1,
// its csz_share texel: z and shares in one fetch). The width passes that write csz_share: width_trace.h.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "sao_math.h"
#include "sao_visibility.h"

namespace sao::cpu::trace {

// The textures ao_sample reads, and width_run, which width_resolve reads (width_trace.h).
enum class Surface : std::uint8_t { Csz, Normals, CszShare, WidthRun };

// A trace writes to a sink: `beginStep()` before each step's reads and once after the last,
// `read(lane, surface, level, x, y)` per texel fetch (lane = gl_LocalInvocationIndex; level the
// MIP level, 0 for normals; x, y the texel of that level). samples/bench's GroupReads is one.

// ao_sample of one run: its csz chain, its block (as float, the way the shader sees it), variant.
class AoSampleTrace {
 public:
  // csz: level 0 first, more than params.max_mip levels when zHierarchy (the caller checks).
  AoSampleTrace(const std::vector<detail::Image<float>>& csz, const gen::SaoParams& params, bool zHierarchy,
                bool normalsSupplied, int localX = 8, int localY = 8, bool visibilityEstimator = false)
      : csz_(csz), P_(params), zHierarchy_(zHierarchy), normalsSupplied_(normalsSupplied), localX_(localX),
        localY_(localY), visibility_(visibilityEstimator) {}

  // ao_raw's extent: the viewport over resolution_divisor, rounded up (the dispatch covers it).
  int aoWidth() const { return (P_.ao_size.x + divisor() - 1) / divisor(); }
  int aoHeight() const { return (P_.ao_size.y + divisor() - 1) / divisor(); }
  int groupsX() const { return (aoWidth() + localX_ - 1) / localX_; }
  int groupsY() const { return (aoHeight() + localY_ - 1) / localY_; }
  int lanes() const { return localX_ * localY_; }

  // The reads of work group (gx, gy), appended to `out`.
  template <typename Sink>
  void group(int gx, int gy, Sink& out) const;

 private:
  int divisor() const { return std::max(P_.ao_divisor, 1); }

  struct Lane {  // what one invocation carries from the centre read to its taps
    bool active = false;  // inside the AO buffer and not sky: it reads its normal and taps
    int cx = 0, cy = 0;
    float rPx = 0;
    detail::SpiralDirection<float> direction;  // the next tap's
    std::uint32_t phase = 0;                   // the visibility estimator's slice angles
    float xi = 0;                              // and radial jitter
    float ux = 1, uy = 0;                      // its slice's direction
  };

  const std::vector<detail::Image<float>>& csz_;
  const detail::Block<float> P_;
  const bool zHierarchy_, normalsSupplied_;
  const int localX_, localY_;
  const bool visibility_;
};

template <typename Sink>
void AoSampleTrace::group(int gx, int gy, Sink& out) const {
  using namespace sao::cpu::detail;
  const Image<float>& z0 = csz_[0];
  const Block<float>& P = P_;
  std::vector<Lane> lane(static_cast<std::size_t>(lanes()));

  // Step 0: zc = texelFetch(in_csz, c, 0), by every invocation.
  out.beginStep();
  for (int li = 0; li < lanes(); ++li) {
    const int px = gx * localX_ + li % localX_, py = gy * localY_ + li / localX_;
    const bool inside = px < std::min(P.ao_size.x, aoWidth()) && py < std::min(P.ao_size.y, aoHeight());
    Lane& l = lane[std::size_t(li)];
    // The viewport pixel the (reduced) AO pixel stands for: itself at divisor 1.
    l.cx = std::clamp(lowRepresentative(px, P.ao_divisor, P.ao_size.x) + P.guard.x, 0, z0.w - 1);
    l.cy = std::clamp(lowRepresentative(py, P.ao_divisor, P.ao_size.y) + P.guard.y, 0, z0.h - 1);
    out.read(li, Surface::Csz, 0, l.cx, l.cy);
    const float zc = z0.at(l.cx, l.cy);
    l.active = inside && !isSky(zc);
    if (l.active) {
      l.rPx = screenRadius(zc, P);
      l.phase = pixelPhase(std::uint32_t(px), std::uint32_t(py)) + P.frame_phase;
      l.direction = SpiralDirection<float>::start(l.phase, P);
      l.xi = radialJitter(std::uint32_t(px), std::uint32_t(py), P);
    }
  }

  // The normal: one fetch of the normals input, or eq. 4's four neighbours (clamped addresses,
  // fetched even at the border, as sao_reconstruct_normal does).
  if (normalsSupplied_) {
    out.beginStep();
    for (int li = 0; li < lanes(); ++li)
      if (const Lane& l = lane[std::size_t(li)]; l.active)
        out.read(li, Surface::Normals, 0, l.cx + P.input_offset.x, l.cy + P.input_offset.y);
  } else {
    const int lastX = z0.w - 1, lastY = z0.h - 1;
    for (int k = 0; k < 4; ++k) {  // zl, zr, zd, zu
      out.beginStep();
      for (int li = 0; li < lanes(); ++li) {
        const Lane& l = lane[std::size_t(li)];
        if (!l.active) continue;
        const int x = k == 0 ? std::max(l.cx - 1, 0) : k == 1 ? std::min(l.cx + 1, lastX) : l.cx;
        const int y = k == 2 ? std::max(l.cy - 1, 0) : k == 3 ? std::min(l.cy + 1, lastY) : l.cy;
        out.read(li, Surface::Csz, 0, x, y);
      }
    }
  }

  const int s = std::clamp(P.samples, 1, gen::SAO_MAX_SAMPLES);
  if (visibility_) {
    // sao_visibility_occlusion's taps: slice k's +u then -u side, m steps each, at h_j = r'((j + xi)/m)^2;
    // a tap on the centre texel is not fetched.
    const int ns = std::clamp(P.slices, 1, gen::SAO_MAX_SLICES);
    const int m = std::max(1, s / (2 * ns));
    const float invM = 1.0f / float(m);
    for (int i = 0; i < ns * 2 * m; ++i) {
      const int k = i / (2 * m), r = i - k * (2 * m);
      const bool negative = r >= m;
      const int j = negative ? r - m : r;
      out.beginStep();
      for (int li = 0; li < lanes(); ++li) {
        Lane& l = lane[std::size_t(li)];
        if (!l.active) continue;
        if (r == 0) turnDirection<float>(l.phase + std::uint32_t(k) * P.slice_turn, l.ux, l.uy);
        const float t = (float(j) + l.xi) * invM;
        const float h = l.rPx * (t * t);
        const int tx = l.cx + static_cast<int>(h * (negative ? -l.ux : l.ux));
        const int ty = l.cy + static_cast<int>(h * (negative ? -l.uy : l.uy));
        if (tx == l.cx && ty == l.cy) continue;
        const int lvl = zHierarchy_ ? mipLevel(h, P.log_q, P.max_mip) : 0;
        const int mx = mipTexel(tx, lvl, z0.w), my = mipTexel(ty, lvl, z0.h);
        int sx = mx, sy = my;
        mipSource(sx, sy, lvl, z0.w, z0.h);
        if (sx == l.cx && sy == l.cy) continue;  // a coarse texel holding the centre's z: not read
        // thickness_model 1: the tap's csz_share texel, its z beside its shares.
        out.read(li, P.thickness_min > 0.0f ? Surface::CszShare : Surface::Csz, lvl, mx, my);
      }
    }
    out.beginStep();  // closes the last step
    return;
  }
  // The s spiral taps (eq. 6-10).
  for (int i = 0; i < s; ++i) {
    out.beginStep();
    for (int li = 0; li < lanes(); ++li) {
      Lane& l = lane[std::size_t(li)];
      if (!l.active) continue;
      float h;
      int tx, ty;
      spiralTap(l.cx, l.cy, i, l.rPx, P, l.direction, tx, ty, h);
      const int m = zHierarchy_ ? mipLevel(h, P.log_q, P.max_mip) : 0;
      out.read(li, Surface::Csz, m, mipTexel(tx, m, z0.w), mipTexel(ty, m, z0.h));
    }
  }
  out.beginStep();  // closes the last step
}

}  // namespace sao::cpu::trace
