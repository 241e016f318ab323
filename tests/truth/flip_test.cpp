// FLIP on grey AO images (samples/flip.h) against its closed forms: uniform images have no
// features and a filter-invariant colour term, so their FLIP is the remapped |dL*|^0.7 alone.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sao/samples/flip.h"

namespace {

using namespace sao;

// CIELAB L* of an sRGB grey, written out here from the standard formulas (not the library's code).
double lStarOfSrgbGrey(double v) {
  const double y = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  return y > 216.0 / 24389.0 ? 116 * std::cbrt(y) - 16 : 24389.0 / 27.0 * y;
}

// FLIP's remap of a colour difference d = HyAB^0.7 against cmax (p_c = 0.4, p_t = 0.95).
double remap(double d, double cmax) {
  const double knee = 0.4 * cmax;
  return d < knee ? d * 0.95 / knee : 0.95 + (d - knee) / (cmax - knee) * 0.05;
}

FloatImage randomImage(Extent e, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  FloatImage img(e, 1);
  for (float& v : img.data) v = u(rng);
  return img;
}

TEST(Flip, MaxColorDistanceIsGreenToBlue) {
  // Published CIELAB (D65) of sRGB green and blue, Hunt-adjusted (a*, b* times L*/100).
  const double gl = 87.7347, ga = -86.1827, gb = 83.1793, bl = 32.3026, ba = 79.1967, bb = -107.8601;
  const double hyab = std::fabs(gl - bl) + std::hypot(ga * gl / 100 - ba * bl / 100, gb * gl / 100 - bb * bl / 100);
  EXPECT_NEAR(samples::flipMaxColorDistance(), std::pow(hyab, 0.7), 2e-3);
}

TEST(Flip, IdenticalImagesScoreZeroEverywhere) {
  const FloatImage a = randomImage({37, 23}, 1);
  const FloatImage map = samples::flipErrorMap(a, a);
  for (float v : map.data) ASSERT_EQ(v, 0.0f);
}

TEST(Flip, IsSymmetric) {
  const FloatImage a = randomImage({40, 30}, 2), b = randomImage({40, 30}, 3);
  const FloatImage ab = samples::flipErrorMap(a, b), ba = samples::flipErrorMap(b, a);
  for (std::size_t i = 0; i < ab.data.size(); ++i) {
    ASSERT_NEAR(ab.data[i], ba.data[i], 1e-6f) << i;
    ASSERT_GE(ab.data[i], 0.0f);
    ASSERT_LE(ab.data[i], 1.0f);
  }
}

TEST(Flip, UniformGreysMatchTheClosedForm) {
  const double cmax = samples::flipMaxColorDistance();
  double previous = 0;
  for (double v : {0.51, 0.55, 0.6, 0.8, 1.0}) {
    const FloatImage ref({24, 16}, 1, 0.5f), test({24, 16}, 1, float(v));
    const double expected = remap(std::pow(std::fabs(lStarOfSrgbGrey(v) - lStarOfSrgbGrey(0.5)), 0.7), cmax);
    const FloatImage map = samples::flipErrorMap(test, ref);
    for (float f : map.data) ASSERT_NEAR(f, expected, 1e-5) << "grey " << v;
    EXPECT_GT(expected, previous) << "a larger grey difference is a larger FLIP";
    previous = expected;
  }
  const FloatImage black({8, 8}, 1, 0.0f), white({8, 8}, 1, 1.0f);
  const float bw = samples::flipErrorMap(black, white).data[0];
  EXPECT_NEAR(bw, remap(std::pow(100.0, 0.7), cmax), 1e-5);
  EXPECT_GT(bw, 0.95f) << "black against white is past the knee";
}

// A one-pixel line the CSF filter nearly removes from the colour term is still seen through the
// feature term (points): FLIP on the line is well above the remapped colour term of its filtered
// difference, and falls off away from it.
TEST(Flip, AThinLineIsSeenByTheFeatureTerm) {
  const Extent e{48, 48};
  FloatImage ref(e, 1, 0.5f), line(e, 1, 0.5f);
  for (std::uint32_t y = 0; y < e.height; ++y) line.at(24, y) = 0.6f;
  const FloatImage map = samples::flipErrorMap(line, ref);
  const double uniform = samples::flipErrorMap(FloatImage(e, 1, 0.6f), ref).at(24, 24);
  EXPECT_GT(map.at(24, 24), 0.0f);
  EXPECT_LT(map.at(24, 24), uniform) << "a line is less visible than a whole field of the same difference";
  EXPECT_GT(map.at(24, 24), 2 * map.at(34, 24)) << "the error is at the line";
}

TEST(Flip, MaskSelectsPixelsAndSkyAddsNothing) {
  const Extent e{32, 32};
  FloatImage ref(e, 1, 0.6f), test(e, 1, 0.6f);
  std::vector<unsigned char> mask(ref.data.size(), 1);
  for (std::uint32_t y = 0; y < 8; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      mask[y * e.width + x] = 0;   // "sky": the two images differ wildly there
      test.at(x, y) = float(x % 2);
    }
  EXPECT_EQ(samples::meanFlip(test, ref, mask), 0.0) << "sky is set to 1 in both images before the filters";
  EXPECT_TRUE(std::isnan(samples::meanFlip(test, ref, std::vector<unsigned char>(ref.data.size(), 0))));
}

TEST(Flip, RefusesMismatchedImages) {
  EXPECT_THROW(samples::flipErrorMap(FloatImage({4, 4}, 1), FloatImage({4, 5}, 1)), std::invalid_argument);
  EXPECT_THROW(samples::flipErrorMap(FloatImage({4, 4}, 2), FloatImage({4, 4}, 2)), std::invalid_argument);
  EXPECT_THROW(samples::flipErrorMap(FloatImage({4, 4}, 1), FloatImage({4, 4}, 1), 0.0), std::invalid_argument);
}

}  // namespace
