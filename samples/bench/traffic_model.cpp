#include "traffic_model.h"

#include <algorithm>
#include <bit>
#include <cstring>

namespace sao::bench {

namespace {

std::uint64_t lines(const CacheConfig& c) { return c.lineBytes == 0 ? 0 : c.bytes / c.lineBytes; }

Status bad(const Machine& m, const std::string& what) {
  return Status::error(StatusCode::InvalidInput, "traffic model '" + m.name + "': " + what);
}

Status validateCache(const Machine& m, const char* name, const CacheConfig& c) {
  const std::string n = name;
  if (c.lineBytes == 0 || !std::has_single_bit(c.lineBytes))
    return bad(m, n + " line of " + std::to_string(c.lineBytes) + " bytes: needs a power of two");
  if (c.bytes == 0 || c.bytes % c.lineBytes != 0)
    return bad(m, n + " of " + std::to_string(c.bytes) + " bytes: needs a non-zero multiple of its line");
  if (c.ways != 0 && lines(c) % c.ways != 0)
    return bad(m, n + ": " + std::to_string(lines(c)) + " lines do not make whole sets of " + std::to_string(c.ways));
  if (c.ways == 0 && lines(c) > 4096)
    return bad(m, n + ": fully associative with " + std::to_string(lines(c)) + " lines (at most 4096; give ways)");
  return Status::success();
}

}  // namespace

LruCache::LruCache(const CacheConfig& c)
    : ways_(c.ways == 0 ? std::uint32_t(lines(c)) : c.ways), sets_(lines(c) / ways_),
      tags_(std::size_t(sets_) * ways_), held_(std::size_t(sets_), 0) {}

bool LruCache::access(std::uint64_t line) {
  const std::size_t set = std::size_t(line % sets_);
  std::uint64_t* t = tags_.data() + set * ways_;
  std::uint32_t& held = held_[set];
  for (std::uint32_t i = 0; i < held; ++i)
    if (t[i] == line) {
      std::memmove(t + 1, t, i * sizeof *t);  // move to the front
      t[0] = line;
      return true;
    }
  const std::uint32_t keep = std::min(held, ways_ - 1);  // the last one is evicted when full
  std::memmove(t + 1, t, keep * sizeof *t);
  t[0] = line;
  held = keep + 1;
  return false;
}

Tile tileOf(std::uint32_t lineBytes, std::uint32_t texelBytes, TexelLayout layout) {
  const std::uint32_t n = texelBytes == 0 ? 1 : std::max(1u, lineBytes / texelBytes);
  if (layout == TexelLayout::Linear) return {n, 1};
  const int log2n = std::bit_width(n) - 1;
  const std::uint32_t w = 1u << ((log2n + 1) / 2);  // the wider side when n is an odd power of two
  return {w, n / w};
}

AddressMap::AddressMap(TexelLayout layout, std::uint32_t lineBytes, const std::vector<SurfaceShape>& surfaces) {
  std::uint64_t next = 0;
  for (const SurfaceShape& s : surfaces) {
    std::vector<Level>& levels = levels_.emplace_back();
    const Tile tile = tileOf(lineBytes, s.texelBytes, layout);
    for (const LevelExtent& e : s.levels) {
      const std::uint64_t tilesX = (e.w + tile.w - 1) / tile.w, tilesY = (e.h + tile.h - 1) / tile.h;
      levels.push_back({next, tilesX, tile});
      next += tilesX * tilesY;
    }
  }
}

Status validate(const Machine& m) {
  if (m.sms == 0 || m.groupsInFlight == 0 || m.warpLanes == 0)
    return bad(m, "needs at least one SM, one work group in flight and one lane per warp");
  if (Status s = validateCache(m, "L1", m.l1); !s) return s;
  if (Status s = validateCache(m, "L2", m.l2); !s) return s;
  if (m.l1.lineBytes != m.l2.lineBytes)
    return bad(m, "L1 and L2 lines differ (" + std::to_string(m.l1.lineBytes) + " and " +
                      std::to_string(m.l2.lineBytes) + " bytes); the model needs one line size");
  return Status::success();
}

TrafficModel::TrafficModel(const Machine& m, const std::vector<SurfaceShape>& surfaces)
    : machine_(m), map_(m.layout, m.l1.lineBytes, surfaces), l1_(m.sms, LruCache(m.l1)),
      l2_(m.l2Shared ? 1 : m.sms, LruCache(m.l2)), wave_(std::size_t(m.sms) * m.groupsInFlight) {
  traffic_.lineBytes = m.l1.lineBytes;
}

void TrafficModel::add(const GroupReads& group) {
  wave_[waveUsed_++] = group;
  if (waveUsed_ == wave_.size()) runWave();
}

void TrafficModel::finish() {
  if (waveUsed_ > 0) runWave();
}

// The reads of one warp in one step go through the SM's L1, its misses through the L2.
void TrafficModel::issue(std::uint32_t sm, const GroupReads& g, std::uint32_t warp, std::size_t step) {
  const std::uint32_t lo = warp * machine_.warpLanes, hi = lo + machine_.warpLanes;
  const TexelRead* first = g.reads.data() + g.stepBegin[step];
  const TexelRead* last = g.reads.data() + g.stepBegin[step + 1];
  first = std::partition_point(first, last, [lo](const TexelRead& r) { return r.lane < lo; });
  LruCache& l2 = l2_[machine_.l2Shared ? 0 : sm];
  for (const TexelRead* r = first; r != last && r->lane < hi; ++r) {
    const std::uint64_t line = map_.line(*r);
    ++traffic_.reads;
    if (l1_[sm].access(line)) continue;
    ++traffic_.l1Misses;
    if (!l2.access(line)) ++traffic_.l2Misses;
  }
}

void TrafficModel::runWave() {
  struct Slot {
    std::uint32_t group, warp;
    std::size_t step;
  };
  // Each SM's order of (group, warp, step); then the SMs take turns, one slot each.
  std::vector<std::vector<Slot>> order(machine_.sms);
  for (std::uint32_t sm = 0; sm < machine_.sms; ++sm) {
    std::vector<std::uint32_t> groups;
    for (std::uint32_t g = sm; g < waveUsed_; g += machine_.sms) groups.push_back(g);
    std::size_t steps = 0;
    std::vector<std::uint32_t> warps;
    for (std::uint32_t g : groups) {
      const GroupReads& r = wave_[g];
      steps = std::max(steps, r.steps());
      std::uint32_t maxLane = 0;
      for (const TexelRead& t : r.reads) maxLane = std::max<std::uint32_t>(maxLane, t.lane);
      warps.push_back(r.reads.empty() ? 0 : maxLane / machine_.warpLanes + 1);
    }
    std::vector<Slot>& o = order[sm];
    if (machine_.warpsInterleave) {
      for (std::size_t s = 0; s < steps; ++s)
        for (std::size_t i = 0; i < groups.size(); ++i)
          for (std::uint32_t w = 0; w < warps[i]; ++w)
            if (s < wave_[groups[i]].steps()) o.push_back({groups[i], w, s});
    } else {
      for (std::size_t i = 0; i < groups.size(); ++i)
        for (std::uint32_t w = 0; w < warps[i]; ++w)
          for (std::size_t s = 0; s < wave_[groups[i]].steps(); ++s) o.push_back({groups[i], w, s});
    }
  }
  std::size_t longest = 0;
  for (const auto& o : order) longest = std::max(longest, o.size());
  for (std::size_t k = 0; k < longest; ++k)
    for (std::uint32_t sm = 0; sm < machine_.sms; ++sm)
      if (k < order[sm].size()) issue(sm, wave_[order[sm][k].group], order[sm][k].warp, order[sm][k].step);
  waveUsed_ = 0;
}

}  // namespace sao::bench
