// The error-structure metrics (samples/error_structure.h) on constructed cases with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "sao/samples/error_structure.h"

namespace {

using namespace sao;

TEST(ErrorStructure, ConstantErrorIsAllBlotch) {
  FloatImage ref({64, 48}, 1, 0.7f), ao({64, 48}, 1, 0.65f);
  std::vector<unsigned char> mask(ref.data.size(), 1), band(ref.data.size(), 0);
  for (std::size_t i = 0; i < mask.size(); i += 3) mask[i] = 0, ao.data[i] = 5.0f;  // masked pixels play no part
  const auto s = samples::errorStructure(ao, ref, mask, band);
  EXPECT_NEAR(s.blotchRmse, 0.05, 1e-6) << "the normalised low-pass of a constant is that constant";
  EXPECT_NEAR(s.highFrequencyRmse, 0.0, 1e-6);
  EXPECT_EQ(s.silhouettePixels, 0u);
  EXPECT_TRUE(std::isnan(s.silhouetteRmse));
}

TEST(ErrorStructure, CheckerboardErrorIsAllHighFrequency) {
  FloatImage ref({64, 64}, 1, 0.5f), ao({64, 64}, 1, 0.5f);
  for (std::uint32_t y = 0; y < 64; ++y)
    for (std::uint32_t x = 0; x < 64; ++x) ao.at(x, y) = (x + y) % 2 ? 0.52f : 0.48f;
  const std::vector<unsigned char> mask(ref.data.size(), 1), band(ref.data.size(), 1);
  const auto s = samples::errorStructure(ao, ref, mask, band);
  EXPECT_LT(s.blotchRmse, 0.02 * 0.01) << "a Gaussian of sigma 8 px leaves under 1% of a 2-px pattern";
  EXPECT_NEAR(s.highFrequencyRmse, 0.02, 1e-4);
  EXPECT_EQ(s.silhouettePixels, ref.data.size());
  EXPECT_NEAR(s.silhouetteRmse, 0.02, 1e-6);
}

// Positions (x, y, z, w) of a 20x10 input with a 2-px guard band: geometry at z = -1 on the left,
// z = -2 from input column 10 on (a jump of 100%), sky in the top input row.
FloatImage stepPositions() {
  FloatImage p({20, 10}, 4, 0.0f);
  for (std::uint32_t y = 0; y < 9; ++y)
    for (std::uint32_t x = 0; x < 20; ++x) {
      p.at(x, y, 2) = x < 10 ? -1.0f : -2.0f;
      p.at(x, y, 3) = 1.0f;
    }
  return p;
}

TEST(ErrorStructure, SilhouetteBandLiesWithinThreePixelsOfJumpsAndSky) {
  const FloatImage p = stepPositions();
  const auto band = samples::silhouetteBand(p, 2);
  ASSERT_EQ(band.size(), 16u * 6u);
  // Viewport column x is input column x + 2: the jump lies between viewport columns 7 and 8, the
  // sky above input row 8 (viewport row 6, outside the viewport: row 5 is its last).
  for (std::uint32_t y = 0; y < 6; ++y)
    for (std::uint32_t x = 0; x < 16; ++x) {
      const int toJump = x <= 7 ? 7 - int(x) : int(x) - 8;
      const int toSky = 6 - int(y);  // to input row 8, the geometry next to the sky row 9
      const bool expected = toJump <= 3 || toSky <= 3;
      EXPECT_EQ(band[y * 16 + x] != 0, expected) << x << "," << y;
    }
  // A small relative change (5%) is no discontinuity.
  FloatImage smooth = p;
  for (std::uint32_t y = 0; y < 10; ++y)
    for (std::uint32_t x = 0; x < 20; ++x) smooth.at(x, y, 2) = x < 10 ? -1.0f : -1.05f, smooth.at(x, y, 3) = 1.0f;
  for (unsigned char b : samples::silhouetteBand(smooth, 2)) EXPECT_EQ(b, 0);
}

TEST(ErrorStructure, ErrorMapIsAPng) {
  FloatImage ref({8, 4}, 1, 0.5f), ao({8, 4}, 1, 0.5f);
  ao.at(1, 1) = 0.3f;
  std::vector<unsigned char> mask(ref.data.size(), 1);
  mask[0] = 0;
  const auto path = std::filesystem::temp_directory_path() / "sao_error_map_test.png";
  ASSERT_TRUE(samples::writeErrorMapPng(path.string(), ao, ref, mask).ok());
  std::ifstream f(path, std::ios::binary);
  char sig[8] = {};
  f.read(sig, 8);
  EXPECT_EQ(std::string(sig + 1, 3), "PNG");
  std::filesystem::remove(path);
  EXPECT_EQ(samples::writeErrorMapPng("/nonexistent-dir/x.png", ao, ref, mask).code, StatusCode::IoError);
}

}  // namespace
