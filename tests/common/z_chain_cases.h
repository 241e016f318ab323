// The z chain's test inputs, shared by the GL and Vulkan tests that compare every csz level with the
// CPU reference's level-by-level chain bit for bit: depth whose texels all differ (a texel copied
// from the wrong place shows), and extents whose chains end at every kind of level count.
#pragma once
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "sao/camera.h"
#include "sao/cpu/reference.h"
#include "sao/image.h"

namespace sao::test {

// D32F depth in [0.5, 0.99) with a different value in every texel, and every 37th texel 1.0 (sky with
// standard depth): `seed` gives a second layer other values.
inline DepthImage distinctDepth(Extent e, std::uint32_t seed) {
  DepthImage d;
  d.extent = e;
  d.format = DepthFormat::D32F;
  d.texels.resize(std::size_t(e.width) * e.height);
  for (std::size_t i = 0; i < d.texels.size(); ++i) {
    // An odd multiplier permutes the residues mod 2^20: distinct for the first 2^20 texels.
    const std::uint32_t k = std::uint32_t((i + seed * 7919u) * 2654435761u) & 0xFFFFFu;
    const float v = i % 37 == 36 ? 1.0f : 0.5f + 0.49f * float(k) / float(1u << 20);
    d.texels[i] = std::bit_cast<std::uint32_t>(v);
  }
  return d;
}

struct ZChainCase {
  std::string name;
  std::uint32_t width, height, guard;
  double radius;  // m: a larger radius keeps more levels (the plan allocates what taps reach)
};

// Chains of 8 levels, of fewer (array slots past the chain's end), odd extents, 1-texel-wide levels.
inline std::vector<ZChainCase> zChainCases() {
  return {{"640x360", 640, 360, 0, 1.0},   {"257x129_guard3", 257, 129, 3, 2.0}, {"100x60_guard4", 100, 60, 4, 1.0},
          {"1029x5", 1029, 5, 0, 4.0},     {"3x200", 3, 200, 0, 4.0},            {"37x23", 37, 23, 0, 0.3},
          {"1x1", 1, 1, 0, 1.0}};
}

// One case's inputs (the settings with its radius, two layers of distinct depth of the input extent)
// and the CPU reference's run on them, the level-by-level chain a backend must equal.
struct ZChainReference {
  Settings settings;
  DepthImage depth, depth2;
  cpu::Result cpu;
  Status status;
};

inline ZChainReference zChainReference(const ZChainCase& c, const Camera& camera, bool twoLayer) {
  ZChainReference r;
  r.settings.radius = float(c.radius);
  const Extent input{c.width + 2 * c.guard, c.height + 2 * c.guard};
  r.depth = distinctDepth(input, 1);
  r.depth2 = distinctDepth(input, 2);
  cpu::Inputs in;
  in.depth = &r.depth;
  in.depth2 = twoLayer ? &r.depth2 : nullptr;
  r.status = cpu::run(r.settings, camera, in, cpu::Options{cpu::Precision::Float, 2}, r.cpu);
  return r;
}

// thickness_model 1's width_run and csz_share chains (the width passes): depth of rectangular
// blocks of constant z whose widths and heights cycle through 1 .. 40 texels (runs that end inside a
// 16x16 work-group tile, across its edges and beyond the pass's reach of 16), every 11th block sky,
// and every 5th block along x at its left neighbour's depth (a run that goes on across a block's edge).
inline DepthImage blockDepth(Extent e) {
  static constexpr std::uint32_t kSides[] = {1, 2, 3, 5, 8, 13, 16, 17, 21, 31, 32, 33, 40};
  auto blocks = [](std::uint32_t n) {
    std::vector<std::uint32_t> index(n);
    std::uint32_t b = 0, left = kSides[0];
    for (std::uint32_t i = 0; i < n; ++i) {
      if (left == 0) left = kSides[++b % std::size(kSides)];
      index[i] = b;
      --left;
    }
    return index;
  };
  const std::vector<std::uint32_t> bx = blocks(e.width), by = blocks(e.height);
  auto value = [](std::uint32_t x, std::uint32_t y) { return 0.55f + 0.03f * float((x * 7 + y * 3) % 13); };
  DepthImage d;
  d.extent = e;
  d.format = DepthFormat::D32F;
  d.texels.resize(std::size_t(e.width) * e.height);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      const std::uint32_t i = bx[x], j = by[y];
      const float v = (i * 3 + j) % 11 == 10 ? 1.0f : value(i % 5 == 4 && i > 0 ? i - 1 : i, j);
      d.texels[std::size_t(y) * e.width + x] = std::bit_cast<std::uint32_t>(v);
    }
  return d;
}

// The CPU reference's run of the visibility estimator with thickness_model 1 on blockDepth: its
// width_run and csz_share chains (cpu::Result::images) are what a backend's width passes must
// equal bit for bit.
inline ZChainReference widthShareReference(const ZChainCase& c, const Camera& camera) {
  ZChainReference r;
  r.settings.radius = float(c.radius);
  r.settings.estimator = 1;
  r.settings.thickness_model = 1;
  r.depth = blockDepth({c.width + 2 * c.guard, c.height + 2 * c.guard});
  cpu::Inputs in;
  in.depth = &r.depth;
  r.status = cpu::run(r.settings, camera, in, cpu::Options{cpu::Precision::Float, 2}, r.cpu);
  return r;
}

}  // namespace sao::test
