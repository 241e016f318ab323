// The blur's depth edge against the centre's plane (blur_edge_slope; effect/include/sao_blur.glsl
// sao_blur_slope, effect/cpu/sao_math.h blurSlope and bilateralBlur): on a slanted surface a tap
// is weighed by its distance from the centre's plane, so the edge no longer cuts a slant it would
// cut with the plain depth difference, while a step still cuts; the slope is the flatter one-sided
// difference and none at a ridge, a valley or next to sky.
#include <algorithm>
#include <cmath>

#include "sao/constants.h"
#include "sao/settings.h"
#include "../../effect/cpu/sao_math.h"
#include "test_support.h"

namespace sao::test {
namespace {

using cpu::detail::bilateralBlur;
using cpu::detail::blurSlope;
using cpu::detail::Image;

cpu::detail::Block<double> blockFor(bool slope, float sharpness) {
  Settings s;
  s.blur_radius = 2;
  s.blur_edge_sharpness = sharpness;
  s.blur_edge_slope = slope;
  s.half_intermediates = true;  // the key in metres: the sharpness applies per metre as given
  ParamBlock p{};
  const Status st = computeConstants(s, testCamera(), DepthEncoding::Hardware, p);
  EXPECT_TRUE(st.ok()) << st.message;
  return cpu::detail::Block<double>(p);
}

// A row of (A, key): A alternating 0 and 1, key linear in x (a slanted surface, 2 cm a pixel
// nearer to the right) with a step 1 m nearer still from x = stepAt on (the slope's own sign, so
// that the minmod next to it takes the slant's).
Image<double> slantedRow(int w, int stepAt) {
  Image<double> img(w, 1, 2);
  for (int x = 0; x < w; ++x) {
    img.at(x, 0, 0) = double(x % 2);
    img.at(x, 0, 1) = -5.0 + 0.02 * x + (x >= stepAt ? 1.0 : 0.0);
  }
  return img;
}

TEST(BlurSlope, MinmodOfTheOneSidedDifferences) {
  EXPECT_DOUBLE_EQ(blurSlope(-5.0, -4.9, -4.7), -4.9 - -5.0);  // the flatter side (left)
  EXPECT_DOUBLE_EQ(blurSlope(-5.2, -4.9, -4.8), -4.8 - -4.9);  // the flatter side (right)
  EXPECT_EQ(blurSlope(-5.0, -4.9, -5.0), 0.0);                 // a ridge
  EXPECT_EQ(blurSlope(-4.8, -4.9, -4.8), 0.0);                 // a valley
  EXPECT_EQ(blurSlope(0.0, -4.9, -4.8), 0.0);                  // sky (key +0) on one side
  EXPECT_EQ(blurSlope(-5.0, -4.9, 0.0), 0.0);
}

TEST(BlurSlope, ASlantBlursAsAFlatSurfaceAndAStepStillCuts) {
  const Image<double> row = slantedRow(16, 10);
  double a = 0, key = 0;
  // Plain depth difference at 100/m: taps 2 and 4 cm away weigh 0 on the slant: A stays the centre's.
  const auto plain = blockFor(false, 100.0f);
  bilateralBlur(row, 4, 0, 1, 0, plain, a, key);
  EXPECT_EQ(a, 0.0);
  EXPECT_EQ(key, row.at(4, 0, 1));
  // Against the centre's plane every tap of the slant weighs its Gaussian weight, as on a flat
  // surface with no depth edge at all.
  const auto slope = blockFor(true, 100.0f);
  const auto none = blockFor(false, 0.0f);
  double aSlope = 0, aNone = 0;
  bilateralBlur(row, 4, 0, 1, 0, slope, aSlope, key);
  bilateralBlur(row, 4, 0, 1, 0, none, aNone, key);
  EXPECT_GT(aSlope, 0.0);
  EXPECT_NEAR(aSlope, aNone, 1e-12);
  // Next to the step (x = 9: the slope is the slant's, taps 10 and 11 lie 1 m off the plane) those
  // taps weigh 0 and A is the Gaussian mean of x = 7, 8, 9.
  bilateralBlur(row, 9, 0, 1, 0, slope, aSlope, key);
  const double w1 = slope.blur_weights_1_4[0], w2 = slope.blur_weights_1_4[1];
  EXPECT_NEAR(aSlope, (w2 * row.at(7, 0, 0) + w1 * row.at(8, 0, 0) + row.at(9, 0, 0)) / (w2 + w1 + 1.0), 1e-12);
  // At the image's edge the slope is unknown (a neighbour off the image): 0, the plain difference.
  bilateralBlur(row, 0, 0, 1, 0, slope, aSlope, key);
  bilateralBlur(row, 0, 0, 1, 0, plain, a, key);
  EXPECT_EQ(aSlope, a);
}

TEST(BlurSlope, OffChangesNoBit) {
  // blur_edge_slope false gives the plain depth difference exactly (g = 0: k0 + t * 0 = k0).
  const Image<double> row = slantedRow(16, 10);
  const auto plain = blockFor(false, 10.0f);
  for (int x = 0; x < 16; ++x) {
    double a = 0, key = 0;
    bilateralBlur(row, x, 0, 1, 0, plain, a, key);
    double sum = 0, wsum = 0;
    for (int t = -2; t <= 2; ++t) {
      const int q = x + t;
      if (q < 0 || q >= 16) continue;
      const double g = t == 0 ? 1.0 : plain.blur_weights_1_4[std::abs(t) - 1];
      const double w = g * std::max(0.0, 1.0 - plain.blur_edge_sharpness * std::abs(row.at(q, 0, 1) - row.at(x, 0, 1)));
      sum += w * row.at(q, 0, 0);
      wsum += w;
    }
    EXPECT_EQ(a, sum / wsum) << "x = " << x;
  }
}

}  // namespace
}  // namespace sao::test
