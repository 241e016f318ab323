// The depth-value contract of sao/image.h, shared by the cpu, gl and vulkan tests: hardware depth
// that is NaN, +-Inf, below 0 or above 1 is sky exactly like the clear value, -0.0 is 0, and
// linear z that is NaN, +-Inf, +-0 or positive is sky. Each test renders a crease, plants the
// values on a grid of texels and checks that csz holds +0.0 there and that the AO is bit for bit
// the AO of the same depth with the clear value planted instead.
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "analytic_scenes.h"
#include "image_compare.h"
#include "sao/camera.h"
#include "sao/cpu/reference.h"
#include "sao/image.h"

namespace sao::test {

inline std::vector<float> badHardwareDepthValues() {
  return {std::bit_cast<float>(0x7FC00000u),  // quiet NaN
          std::bit_cast<float>(0x7F800123u),  // NaN with a payload
          std::bit_cast<float>(0xFFC00000u),  // negative NaN
          std::numeric_limits<float>::infinity(),
          -std::numeric_limits<float>::infinity(),
          -0.5f,
          1.5f,
          -std::numeric_limits<float>::denorm_min(),
          -std::numeric_limits<float>::max(),
          std::numeric_limits<float>::max(),
          1.0f + std::numeric_limits<float>::epsilon()};
}

// Every value linear z treats as sky (+0.0 itself is the renderer's own sky marker).
inline std::vector<float> skyLinearZValues() {
  return {std::bit_cast<float>(0x7FC00000u), std::bit_cast<float>(0x7F800123u), std::bit_cast<float>(0xFFC00000u),
          std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(), -0.0f, 0.5f,
          std::numeric_limits<float>::max()};
}

inline std::string valueName(float v) {
  const std::uint32_t b = std::bit_cast<std::uint32_t>(v);
  char text[48];
  std::snprintf(text, sizeof text, "%.9g (0x%08X)", double(v), b);
  return text;
}

// The grid of planted texels (every 5th in x and y, inside the guard band too).
inline std::vector<std::size_t> plantedTexels(Extent e) {
  std::vector<std::size_t> at;
  for (std::uint32_t y = 1; y < e.height; y += 5)
    for (std::uint32_t x = 2; x < e.width; x += 5) at.push_back(std::size_t(y) * e.width + x);
  return at;
}

// `depth` with `value` written at every planted texel.
inline DepthImage planted(DepthImage depth, float value) {
  for (std::size_t i : plantedTexels(depth.extent)) depth.texels[i] = std::bit_cast<std::uint32_t>(value);
  return depth;
}

// The crease the tests plant into: occluded enough that a wrong sky texel changes the AO around it.
inline DepthImage contractDepth(const Camera& camera, DepthFormat format) {
  return renderDepth(creaseScene(2.0), camera, format);
}

// How many planted texels of csz level 0 are not +0.0 (bit for bit).
inline std::size_t plantedNotSky(const FloatImage& csz0) {
  std::size_t n = 0;
  for (std::size_t i : plantedTexels(csz0.extent)) n += std::bit_cast<std::uint32_t>(csz0.data[i]) != 0u;
  return n;
}

// The camera every backend's contract test renders with: 64x40, a guard band of 4.
inline Camera contractCamera(bool reversedZ) {
  Camera c = perspectiveCamera(1.0, 64, 40, 0.1, reversedZ ? INFINITY : 100.0, ClipDepth::ZeroToOne, reversedZ);
  c.guardBand = 4;
  return c;
}

// csz level 0 of the CPU reference (float), the GPU backends' oracle.
inline FloatImage cpuCsz0(const Camera& camera, const DepthImage& depth) {
  cpu::Inputs in;
  in.depth = &depth;
  cpu::Result r;
  EXPECT_TRUE(cpu::run(Settings{}, camera, in, {cpu::Precision::Float, 2}, r).ok());
  return r.csz.empty() ? FloatImage{} : r.csz[0];
}

// The GPU backends' checks, for `render(camera, depth)` returning an object with csz0 and ao.
// -0.0 in D32F gives the bits +0.0 gives, in csz and AO, and the CPU reference's csz.
template <class Render>
void expectMinusZeroIsZero(Render&& render) {
  for (bool reversedZ : {false, true}) {
    SCOPED_TRACE(reversedZ ? "reversed-Z (-0.0 is the sky)" : "standard (-0.0 is the near plane)");
    const Camera camera = contractCamera(reversedZ);
    const DepthImage depth = contractDepth(camera, DepthFormat::D32F);
    const auto plus = render(camera, planted(depth, 0.0f));
    const auto minus = render(camera, planted(depth, -0.0f));
    ASSERT_FALSE(minus.ao.data.empty());
    EXPECT_TRUE(sameBits(minus.csz0, plus.csz0));
    EXPECT_TRUE(sameBits(minus.ao, plus.ao));
    EXPECT_TRUE(sameBits(minus.csz0, cpuCsz0(camera, planted(depth, -0.0f))));
  }
}

// Every sky value of R32F linear z gives csz +0.0, the AO of +0.0, and the CPU reference's csz.
template <class Render>
void expectLinearZSkyValuesAreSky(Render&& render) {
  const Camera camera = contractCamera(true);
  const DepthImage depth = contractDepth(camera, DepthFormat::LinearZ);
  const auto sky = render(camera, planted(depth, 0.0f));
  ASSERT_FALSE(sky.ao.data.empty());
  for (float v : skyLinearZValues()) {
    SCOPED_TRACE("z = " + valueName(v));
    const DepthImage bad = planted(depth, v);
    const auto r = render(camera, bad);
    EXPECT_EQ(plantedNotSky(r.csz0), 0u);
    EXPECT_TRUE(sameBits(r.ao, sky.ao));
    EXPECT_TRUE(sameBits(r.csz0, cpuCsz0(camera, bad)));
  }
}

}  // namespace sao::test
