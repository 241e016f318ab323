// The texel reads of the two width passes (thickness_model 1; effect/sao.glsl, sao_width_main and
// sao_width_resolve_main), replayed per work group for sao-bench's memory-traffic model, as
// tap_trace.h does for ao_sample. Reads come per instruction ("step") and lane, lanes in order:
//  - width: six textureGathers of csz level 0 an invocation (the tile's 48x16 rows and 16x48
//    columns, four texels each, clamped), then SAO_LEVELS_PASS's texels above level 0, each its
//    centre and its walks (runShare's: a read per step until the run breaks, leaves the level or
//    reaches SAO_WIDTH_REACH), x then y, the + side then the - side;
//  - width_resolve: SAO_LEVELS_PASS's texels of every level, each its csz texel, its width_run
//    texel and its ancestors' while a share is still 1.
// Whether a walk goes on and whether a share is 1 depend on the data: the trace evaluates them with
// the CPU reference's own functions in float (runShare, roundToHalf), so the reads are the shader's.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "sao_math.h"
#include "sao_visibility.h"
#include "tap_trace.h"

namespace sao::cpu::trace {

class WidthTrace {
 public:
  // csz: level 0 first, at least params.max_mip + 1 levels (the caller checks). The width_run
  // shares the resolve depends on are computed here, once.
  WidthTrace(const std::vector<detail::Image<float>>& csz, const gen::SaoParams& params) : csz_(csz), P_(params) {
    for (int m = 0; m <= P_.max_mip; ++m) {
      const detail::Image<float>& zm = csz_[std::size_t(m)];
      detail::Image<float>& share = runs_.emplace_back(zm.w, zm.h, 2);
      for (int y = 0; y < zm.h; ++y)
        for (int x = 0; x < zm.w; ++x) {
          const float z = zm.at(x, y);
          float sx = 1.0f, sy = 1.0f;
          if (!detail::isSky(z) && P_.thickness > 0.0f) {
            sx = detail::roundToHalf(detail::runShare(zm, m, csz_[0].w, csz_[0].h, x, y, z, 1, 0, P_));
            sy = detail::roundToHalf(detail::runShare(zm, m, csz_[0].w, csz_[0].h, x, y, z, 0, 1, P_));
          }
          share.at(x, y, 0) = sx;
          share.at(x, y, 1) = sy;
        }
    }
  }

  // Both passes' dispatch: one invocation of 8x8 per 2x2 level-0 texels.
  int groupsX() const { return (csz_[0].w + 15) / 16; }
  int groupsY() const { return (csz_[0].h + 15) / 16; }
  static constexpr int kLanes = 64;

  // The reads of work group (gx, gy) of the width pass / of width_resolve, appended to `out`.
  template <typename Sink>
  void widthGroup(int gx, int gy, Sink& out) const;
  template <typename Sink>
  void resolveGroup(int gx, int gy, Sink& out) const;

 private:
  struct Read {
    int level, x, y;
    Surface surface;
  };
  struct Size {
    int w, h;
  };
  // One lane's reads of one texel by step (the steps fixed per kind of texel, so lanes line up):
  // at most one read a step.
  using Steps = std::vector<std::vector<Read>>;

  // SAO_LEVELS_PASS's texels of levels >= 2 for group (gx, gy): per chunk of 64 slots, its level
  // and the texel index of its lane 0 (lane l takes first + l, if inside the level).
  struct Chunk {
    int level;
    int first;  // the chunk's first texel index on that level
  };
  std::vector<Chunk> upperChunks(int gx, int gy) const;
  Size levelSize(int m) const { return {csz_[std::size_t(m)].w, csz_[std::size_t(m)].h}; }

  // sao_width_level_texel's reads of texel (x, y) of level m >= 1: step 0 its centre, then 4
  // walks of SAO_WIDTH_REACH steps (x +, x -, y +, y -).
  void walkReads(int m, int x, int y, Steps& steps) const;
  // sao_width_resolved_texel's reads: step 0 its csz texel, step 1 its own width_run texel, step
  // 1 + j its ancestor j levels up.
  void resolveReads(int m, int x, int y, Steps& steps) const;

  template <typename Sink>
  static void emit(const std::vector<Steps>& perLane, Sink& out);
  // SAO_LEVELS_PASS's texels above level 0 in group (gx, gy), their reads by readsOf.
  using ReadsOf = void (WidthTrace::*)(int m, int x, int y, Steps& steps) const;
  template <typename Sink>
  void levelsAbove0(int gx, int gy, ReadsOf readsOf, Sink& out) const;

  const std::vector<detail::Image<float>>& csz_;
  const detail::Block<float> P_;
  std::vector<detail::Image<float>> runs_;  // width_run, levels 0 .. max_mip
};

inline std::vector<WidthTrace::Chunk> WidthTrace::upperChunks(int gx, int gy) const {
  std::vector<Chunk> chunks;
  const int groups = groupsX() * groupsY();
  auto slots = [](int texels) { return (texels + kLanes - 1) / kLanes * kLanes; };  // sao_level_slots
  int m = 2, first = 0;
  for (int s = (gy * groupsX() + gx) * kLanes; m <= P_.max_mip; s += groups * kLanes) {
    while (m <= P_.max_mip && s >= first + slots(levelSize(m).w * levelSize(m).h)) {
      first += slots(levelSize(m).w * levelSize(m).h);
      ++m;
    }
    if (m <= P_.max_mip) chunks.push_back({m, s - first});
  }
  return chunks;
}

inline void WidthTrace::walkReads(int m, int x, int y, Steps& steps) const {
  const detail::Image<float>& zm = csz_[std::size_t(m)];
  steps.assign(1 + 4 * gen::SAO_WIDTH_REACH, {});
  steps[0].push_back({m, x, y, Surface::Csz});
  const float z = zm.at(x, y);
  if (detail::isSky(z) || !(P_.thickness > 0.0f)) return;
  for (int axis = 0; axis < 2; ++axis) {  // the reference's own walk, its fetches recorded
    auto record = [&](int side, int k, int cx, int cy) {
      steps[std::size_t(1 + (axis * 2 + side) * gen::SAO_WIDTH_REACH + k - 1)].push_back({m, cx, cy, Surface::Csz});
    };
    detail::runShare(zm, m, csz_[0].w, csz_[0].h, x, y, z, int(axis == 0), int(axis == 1), P_, record);
  }
}

inline void WidthTrace::resolveReads(int m, int x, int y, Steps& steps) const {
  steps.assign(std::size_t(2 + P_.max_mip - m), {});
  steps[0].push_back({m, x, y, Surface::Csz});
  steps[1].push_back({m, x, y, Surface::WidthRun});
  float sx = runs_[std::size_t(m)].at(x, y, 0), sy = runs_[std::size_t(m)].at(x, y, 1);
  for (int j = m + 1, qx = x, qy = y; j <= P_.max_mip && (sx >= 1.0f || sy >= 1.0f); ++j) {
    const detail::Image<float>& run = runs_[std::size_t(j)];
    qx = std::min(qx >> 1, run.w - 1), qy = std::min(qy >> 1, run.h - 1);
    steps[std::size_t(1 + j - m)].push_back({j, qx, qy, Surface::WidthRun});
    sx = sx >= 1.0f ? run.at(qx, qy, 0) : sx;
    sy = sy >= 1.0f ? run.at(qx, qy, 1) : sy;
  }
}

template <typename Sink>
void WidthTrace::emit(const std::vector<Steps>& perLane, Sink& out) {
  std::size_t steps = 0;
  for (const Steps& s : perLane) steps = std::max(steps, s.size());
  for (std::size_t k = 0; k < steps; ++k) {
    out.beginStep();
    for (std::size_t li = 0; li < perLane.size(); ++li)
      if (k < perLane[li].size())
        for (const Read& r : perLane[li][k]) out.read(int(li), r.surface, r.level, r.x, r.y);
  }
}

template <typename Sink>
void WidthTrace::widthGroup(int gx, int gy, Sink& out) const {
  const detail::Image<float>& z0 = csz_[0];
  const int ox = 16 * gx, oy = 16 * gy;
  // Six gathers an invocation: for k = 0..2, quad li + 64 k of the rows (24x8 quads of the 48x16
  // band texels from (ox - 16, oy)), then of the columns (8x24 from (ox, oy - 16)); each the 2x2
  // texels from the quad's lower-left corner, clamped to the image (clamp-to-edge).
  for (int k = 0; k < 3; ++k)
    for (int kind = 0; kind < 2; ++kind) {
      out.beginStep();
      for (int li = 0; li < kLanes; ++li) {
        const int q = li + 64 * k;
        const int qi = 2 * (kind == 0 ? q % 24 : q / 8), qb = 2 * (kind == 0 ? q / 24 : q % 8);
        const int cx = kind == 0 ? ox + qi - 16 : ox + qb, cy = kind == 0 ? oy + qb : oy + qi - 16;
        for (int t = 0; t < 4; ++t)
          out.read(li, Surface::Csz, 0, std::clamp(cx + (t & 1), 0, z0.w - 1), std::clamp(cy + (t >> 1), 0, z0.h - 1));
      }
    }
  // Level 0 is written from shared memory.
  levelsAbove0(gx, gy, &WidthTrace::walkReads, out);
  out.beginStep();  // closes the last step
}

template <typename Sink>
void WidthTrace::resolveGroup(int gx, int gy, Sink& out) const {
  const detail::Image<float>& z0 = csz_[0];
  std::vector<Steps> perLane(kLanes);
  // Level 0: invocation b's four texels 2b + (k & 1, k >> 1), one after the other.
  for (int k = 0; k < 4; ++k) {
    for (int li = 0; li < kLanes; ++li) {
      perLane[std::size_t(li)].clear();
      const int x = 2 * (8 * gx + li % 8) + (k & 1), y = 2 * (8 * gy + li / 8) + (k >> 1);
      if (x < z0.w && y < z0.h) resolveReads(0, x, y, perLane[std::size_t(li)]);
    }
    emit(perLane, out);
  }
  levelsAbove0(gx, gy, &WidthTrace::resolveReads, out);
  out.beginStep();  // closes the last step
}

template <typename Sink>
void WidthTrace::levelsAbove0(int gx, int gy, ReadsOf readsOf, Sink& out) const {
  const detail::Image<float>& z0 = csz_[0];
  std::vector<Steps> perLane(kLanes);
  if (P_.max_mip >= 1) {  // level 1: invocation b's texel b
    const Size s1 = levelSize(1);
    for (int li = 0; li < kLanes; ++li) {
      const int bx = 8 * gx + li % 8, by = 8 * gy + li / 8;
      if (2 * bx < z0.w && 2 * by < z0.h && bx < s1.w && by < s1.h) (this->*readsOf)(1, bx, by, perLane[std::size_t(li)]);
    }
    emit(perLane, out);
  }
  for (const Chunk& c : upperChunks(gx, gy)) {  // levels 2+: a level a chunk of 64 slots
    const Size sz = levelSize(c.level);
    for (int li = 0; li < kLanes; ++li) {
      perLane[std::size_t(li)].clear();
      const int i = c.first + li;
      if (i < sz.w * sz.h) (this->*readsOf)(c.level, i % sz.w, i / sz.w, perLane[std::size_t(li)]);
    }
    emit(perLane, out);
  }
}

}  // namespace sao::cpu::trace
