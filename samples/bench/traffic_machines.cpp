#include "traffic_machines.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <thread>

namespace sao::bench {

namespace {

// One cache of /sys/devices/system/cpu/cpu0/cache/indexN; false when the folder is not there.
struct SysCache {
  int level = 0;
  std::string type, sharedWith;
  std::uint64_t bytes = 0;
  std::uint32_t ways = 0, line = 0;
};

std::string readLine(const std::string& path) {
  std::ifstream f(path);
  std::string s;
  std::getline(f, s);
  return s;
}

bool readSysCache(int index, SysCache& c) {
  const std::string dir = "/sys/devices/system/cpu/cpu0/cache/index" + std::to_string(index) + "/";
  const std::string size = readLine(dir + "size");  // "48K"
  if (size.empty()) return false;
  c.level = std::atoi(readLine(dir + "level").c_str());
  c.type = readLine(dir + "type");
  c.bytes = std::strtoull(size.c_str(), nullptr, 10) * (size.back() == 'K' ? 1024 : size.back() == 'M' ? 1 << 20 : 1);
  c.ways = std::uint32_t(std::atoi(readLine(dir + "ways_of_associativity").c_str()));
  c.line = std::uint32_t(std::atoi(readLine(dir + "coherency_line_size").c_str()));
  c.sharedWith = readLine(dir + "shared_cpu_list");
  return true;
}

// Ways that split the lines into whole sets, else 8 (the model needs whole sets).
CacheConfig cache(std::uint64_t bytes, std::uint32_t line, std::uint32_t ways) {
  CacheConfig c{bytes, line == 0 ? 64 : line, ways};
  const std::uint64_t lines = c.bytes / c.lineBytes;
  if (c.ways == 0 || lines % c.ways != 0) c.ways = 8;
  return c;
}

}  // namespace

Machine paperLikeMachine(std::uint64_t l1Bytes) {
  Machine m;
  m.name = "paper-like GTX 680";
  if (l1Bytes != 16 * 1024) m.name += " with " + std::to_string(l1Bytes >> 10) + " KB L1";
  m.sms = 8;
  m.groupsInFlight = 16;
  m.warpLanes = 32;
  m.warpsInterleave = true;
  m.l1 = {l1Bytes, 128, 0};
  m.l2 = {512 * 1024, 128, 16};
  m.l2Shared = true;
  m.layout = TexelLayout::Tiled;
  return m;
}

Machine thisCpuMachine(std::string& source) {
  Machine m;
  m.name = "this CPU (llvmpipe-like)";
  m.sms = std::max(1u, std::thread::hardware_concurrency());
  m.groupsInFlight = 1;
  m.warpLanes = 8;  // llvmpipe's 256-bit vectors of 32-bit lanes
  m.warpsInterleave = false;
  m.layout = TexelLayout::Linear;
  m.l1 = cache(48 * 1024, 64, 12);  // fallbacks: a Zen 4/5 core
  m.l2 = cache(1024 * 1024, 64, 8);
  m.l2Shared = false;
  bool l1 = false, l2 = false;
  SysCache c;
  for (int i = 0; i < 8 && readSysCache(i, c); ++i) {
    const bool shared = c.sharedWith.find_first_of(",-") != std::string::npos;
    if (c.level == 1 && c.type != "Instruction") m.l1 = cache(c.bytes, c.line, c.ways), l1 = true;
    if (c.level == 2) m.l2 = cache(c.bytes, c.line, c.ways), m.l2Shared = shared, l2 = true;
  }
  if (l1 && l2) {
    source = "/sys/devices/system/cpu/cpu0/cache";
    return m;
  }
  const long l1Size = sysconf(_SC_LEVEL1_DCACHE_SIZE), l2Size = sysconf(_SC_LEVEL2_CACHE_SIZE);
  if (l1Size > 0 && l2Size > 0) {
    m.l1 = cache(std::uint64_t(l1Size), std::uint32_t(std::max(0L, sysconf(_SC_LEVEL1_DCACHE_LINESIZE))),
                 std::uint32_t(std::max(0L, sysconf(_SC_LEVEL1_DCACHE_ASSOC))));
    m.l2 = cache(std::uint64_t(l2Size), std::uint32_t(std::max(0L, sysconf(_SC_LEVEL2_CACHE_LINESIZE))),
                 std::uint32_t(std::max(0L, sysconf(_SC_LEVEL2_CACHE_ASSOC))));
    source = "sysconf (glibc's cpuid; L2 taken as private per core)";
  } else {
    source = "assumed (48 KB L1d 12-way, 1 MB private L2 8-way, 64 B lines): no /sys cache folder, no sysconf";
  }
  return m;
}

std::string describe(const Machine& m) {
  auto kb = [](std::uint64_t b) { return b >= (1u << 20) && b % (1u << 20) == 0 ? std::to_string(b >> 20) + " MB"
                                                                                 : std::to_string(b >> 10) + " KB"; };
  auto ways = [](const CacheConfig& c) { return c.ways == 0 ? std::string("fully assoc.") : std::to_string(c.ways) + "-way"; };
  const Tile t = tileOf(m.l1.lineBytes, 4, m.layout);
  return std::to_string(m.sms) + " SM x " + std::to_string(m.groupsInFlight) + " groups, " + kb(m.l1.bytes) + " L1 (" +
         ways(m.l1) + ") per SM, " + kb(m.l2.bytes) + " L2 (" + ways(m.l2) + (m.l2Shared ? ") shared" : ") per SM") +
         ", " + std::to_string(m.l1.lineBytes) + " B lines, r32f " + std::to_string(t.w) + "x" + std::to_string(t.h) +
         " texels per line, " + std::to_string(m.warpLanes) + "-lane warps" +
         (m.warpsInterleave ? " interleaved" : " run one after another");
}

}  // namespace sao::bench
