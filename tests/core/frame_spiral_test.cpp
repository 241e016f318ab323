// sao::frameSpiral (sao/spiral.h): frame 0 is the paper's spiral, and any N consecutive frames
// spread the spiral's rotation (golden-ratio steps) and radial offset (van der Corput) evenly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sao/constants.h"
#include "sao/spiral.h"

namespace {

// The largest gap between neighbours of `v` on the unit circle (values in [0, 1)).
double largestGap(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  double gap = 1.0 - v.back() + v.front();
  for (std::size_t i = 1; i < v.size(); ++i) gap = std::max(gap, v[i] - v[i - 1]);
  return gap;
}

TEST(FrameSpiral, FrameZeroIsThePapersSpiral) {
  const sao::FrameSpiral f = sao::frameSpiral(0);
  EXPECT_EQ(f.phase, 0u);
  EXPECT_EQ(f.alphaOffset, 0.5f);
  sao::ParamBlock block{};
  block.frame_phase = 123;
  sao::setFrameIndex(block, 0);
  EXPECT_EQ(block.frame_phase, 0u);
  EXPECT_EQ(block.frame_alpha_offset, 0.5f);
  sao::setFrameIndex(block, 5);
  EXPECT_EQ(block.frame_phase, sao::frameSpiral(5).phase);
  EXPECT_EQ(block.frame_alpha_offset, sao::frameSpiral(5).alphaOffset);
}

TEST(FrameSpiral, AnyConsecutiveFramesCoverRotationAndRadiusEvenly) {
  for (std::uint32_t first : {0u, 1u, 1000u, 4294967000u})
    for (std::uint32_t n : {4u, 8u, 16u, 32u, 64u}) {
      std::vector<double> rotation, offset;
      for (std::uint32_t k = first; k != first + n; ++k) {
        const sao::FrameSpiral f = sao::frameSpiral(k);
        rotation.push_back(double(f.phase) / 4294967296.0);
        ASSERT_GE(f.alphaOffset, 0.0f);
        ASSERT_LT(f.alphaOffset, 1.0f);
        offset.push_back(f.alphaOffset);
      }
      // Independent uniform points leave gaps of about ln(n)/n; golden-ratio steps stay below
      // 1.9/n (the three-gap theorem), van der Corput below 3/n, and exactly 1/n from frame 0
      // for a power of two.
      EXPECT_LT(largestGap(rotation), 1.9 / n) << "frames " << first << " + " << n;
      EXPECT_LT(largestGap(offset), 3.0 / n) << "frames " << first << " + " << n;
      if (first == 0) { EXPECT_NEAR(largestGap(offset), 1.0 / n, 1e-6) << "frames 0 + " << n; }
    }
}

TEST(FrameSpiral, TheRotationIsExactIntegerArithmetic) {
  // k frames on: k times the step, modulo 2^32 (no drift, the same on every backend).
  const std::uint32_t step = sao::frameSpiral(1).phase;
  EXPECT_EQ(step, 2654435769u) << "round(2^32 / golden ratio)";
  for (std::uint32_t k : {2u, 17u, 65535u, 4294967295u}) EXPECT_EQ(sao::frameSpiral(k).phase, k * step);
}

}  // namespace
