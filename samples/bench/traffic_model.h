// A memory-traffic model of a texture read stream: per-SM L1 caches and an L2 (shared or per SM),
// LRU, with texels laid out in cache-line tiles. sao-bench's traffic section feeds it the exact
// reads of ao_sample (effect/cpu/tap_trace.h) to count the bytes each variant pulls from L2 and
// from memory per pixel: the paper's argument for the z hierarchy, checkable without a GPU.
// Only reads are modelled (ao_sample's writes are the same for every variant).
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sao/status.h"

namespace sao::bench {

// One texel fetch of one invocation (lane = gl_LocalInvocationIndex in its work group).
struct TexelRead {
  std::uint16_t lane;
  std::uint8_t surface, level;
  std::int32_t x, y;
};

// One work group's reads per instruction: step s holds reads [stepBegin[s], stepBegin[s + 1]).
// It is the sink sao::cpu::trace::AoSampleTrace::group writes to.
struct GroupReads {
  std::vector<TexelRead> reads;
  std::vector<std::uint32_t> stepBegin;

  void clear() { reads.clear(), stepBegin.clear(); }
  void beginStep() { stepBegin.push_back(std::uint32_t(reads.size())); }
  template <typename Surface>
  void read(int lane, Surface surface, int level, int x, int y) {
    reads.push_back({std::uint16_t(lane), std::uint8_t(surface), std::uint8_t(level), x, y});
  }
  std::size_t steps() const { return stepBegin.empty() ? 0 : stepBegin.size() - 1; }
};

struct CacheConfig {
  std::uint64_t bytes = 0;
  std::uint32_t lineBytes = 128;
  std::uint32_t ways = 0;  // 0: fully associative
};

// A set-associative LRU cache of line numbers; a miss fills the line.
class LruCache {
 public:
  explicit LruCache(const CacheConfig& c);  // c valid (validate() below)
  bool access(std::uint64_t line);          // true: hit
  std::uint64_t sets() const { return sets_; }
  std::uint32_t ways() const { return ways_; }

 private:
  std::uint32_t ways_;
  std::uint64_t sets_;
  std::vector<std::uint64_t> tags_;  // per set, most recently used first
  std::vector<std::uint32_t> held_;  // lines held per set
};

// How texels fill a cache line: Tiled, a 2D tile (as wide as high or twice as wide: 128-byte lines
// of r32f hold 8x4 texels); Linear, a run of one row (llvmpipe's layout).
enum class TexelLayout { Tiled, Linear };
struct Tile {
  std::uint32_t w = 1, h = 1;
};
Tile tileOf(std::uint32_t lineBytes, std::uint32_t texelBytes, TexelLayout layout);

struct LevelExtent {
  std::uint32_t w = 0, h = 0;
};
// A texture: bytes per texel and its MIP levels' extents, level 0 first.
struct SurfaceShape {
  std::uint32_t texelBytes = 4;
  std::vector<LevelExtent> levels;
};

// Texel -> cache-line number. Each level is its own run of whole lines, levels and surfaces one
// after another, the way a driver allocates them.
class AddressMap {
 public:
  AddressMap(TexelLayout layout, std::uint32_t lineBytes, const std::vector<SurfaceShape>& surfaces);
  std::uint64_t line(const TexelRead& r) const {
    const Level& l = levels_[r.surface][r.level];
    return l.base + std::uint64_t(std::uint32_t(r.y) / l.tile.h) * l.tilesX + std::uint32_t(r.x) / l.tile.w;
  }

 private:
  struct Level {
    std::uint64_t base;
    std::uint64_t tilesX;
    Tile tile;
  };
  std::vector<std::vector<Level>> levels_;
};

struct Machine {
  std::string name;
  std::uint32_t sms = 1;             // SMs (cores); work group g runs on SM g % sms
  std::uint32_t groupsInFlight = 1;  // work groups resident on an SM at once
  std::uint32_t warpLanes = 32;      // invocations that issue a step together
  bool warpsInterleave = true;       // true: an SM's resident warps take turns per step (a GPU);
                                     // false: each warp runs all its steps (llvmpipe's coroutines)
  CacheConfig l1, l2;
  bool l2Shared = true;  // false: one L2 per SM (a CPU core's private L2)
  TexelLayout layout = TexelLayout::Tiled;
};

// Why a machine cannot be modelled (sizes not a whole number of sets, lines not a power of two,
// different line sizes in L1 and L2, ...); success otherwise.
Status validate(const Machine& m);

struct Traffic {
  std::uint64_t reads = 0, l1Misses = 0, l2Misses = 0;
  std::uint32_t lineBytes = 0;
  std::uint64_t l2Bytes() const { return l1Misses * lineBytes; }      // L1 fills
  std::uint64_t memoryBytes() const { return l2Misses * lineBytes; }  // L2 fills
};

// Replays work groups, in dispatch order, through a machine's caches. Every groupsInFlight x sms
// consecutive groups form a wave that runs together: the SMs take turns issuing one warp step.
class TrafficModel {
 public:
  TrafficModel(const Machine& m, const std::vector<SurfaceShape>& surfaces);  // m valid
  void add(const GroupReads& group);  // the next group of the dispatch
  void finish();                      // runs the last, partial wave
  const Traffic& traffic() const { return traffic_; }

 private:
  void runWave();
  void issue(std::uint32_t sm, const GroupReads& g, std::uint32_t warp, std::size_t step);

  Machine machine_;
  AddressMap map_;
  std::vector<LruCache> l1_, l2_;
  std::vector<GroupReads> wave_;
  std::size_t waveUsed_ = 0;
  Traffic traffic_;
};

}  // namespace sao::bench
