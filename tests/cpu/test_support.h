// Small helpers shared by the CPU reference tests.
#pragma once
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "image_compare.h"
#include "analytic_scenes.h"
#include "sao/cpu/reference.h"

namespace sao::test {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The test camera: 60 degree vertical field of view, near 0.1, 160x90 unless told otherwise.
inline Camera testCamera(std::uint32_t guard = 8, double farDistance = 1000.0,
                         ClipDepth clip = ClipDepth::NegativeOneToOne, bool reversedZ = false,
                         std::uint32_t width = 160, std::uint32_t height = 90) {
  Camera c = perspectiveCamera(std::numbers::pi / 3.0, width, height, 0.1, farDistance, clip, reversedZ);
  c.guardBand = guard;
  return c;
}

inline cpu::Result runOrFail(const Settings& settings, const Camera& camera, const cpu::Inputs& inputs,
                             cpu::Precision precision, unsigned threads = 2) {
  cpu::Result r;
  const Status st = cpu::run(settings, camera, inputs, cpu::Options{precision, threads}, r);
  EXPECT_TRUE(st.ok()) << st.message;
  return r;
}


inline bool allFinite(const FloatImage& img) {
  for (float v : img.data)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace sao::test
