// The error metrics: exact on constructed cases.
#include <gtest/gtest.h>

#include "sao/samples/metrics.h"

namespace {

using namespace sao;

TEST(Metrics, IdenticalImagesAreExact) {
  FloatImage a({32, 16}, 1, 0.0f);
  for (std::size_t i = 0; i < a.data.size(); ++i) a.data[i] = float(i % 7) / 7.0f;
  const std::vector<unsigned char> mask(a.data.size(), 1);
  const auto c = samples::compareToReference(a, a, mask);
  EXPECT_EQ(c.raw.pixels, a.data.size());
  EXPECT_DOUBLE_EQ(c.raw.rmse, 0.0);
  EXPECT_NEAR(c.raw.ssim, 1.0, 1e-12);
  EXPECT_NEAR(c.fittedIntensity, 1.0, 1e-12);
}

TEST(Metrics, HalfTheOcclusionFitsAScaleOfTwo) {
  FloatImage ref({16, 16}, 1, 0.0f), ao({16, 16}, 1, 0.0f);
  for (std::size_t i = 0; i < ref.data.size(); ++i) {
    ref.data[i] = 1.0f - 0.4f * float(i % 5) / 4.0f;
    ao.data[i] = 1.0f - 0.5f * (1.0f - ref.data[i]);
  }
  std::vector<unsigned char> mask(ref.data.size(), 1);
  mask[0] = 0;  // masked pixels are ignored
  ao.data[0] = 1e6f;
  const auto c = samples::compareToReference(ao, ref, mask);
  EXPECT_EQ(c.raw.pixels, ref.data.size() - 1);
  EXPECT_GT(c.raw.meanBias, 0.0) << "too bright";
  EXPECT_NEAR(c.fittedIntensity, 2.0, 1e-5);
  EXPECT_NEAR(c.fitted.rmse, 0.0, 1e-6);
}

TEST(Metrics, FractionOverThreshold) {
  FloatImage ref({10, 1}, 1, 1.0f), ao({10, 1}, 1, 1.0f);
  ao.data[3] = 0.8f;
  ao.data[7] = 0.95f;
  const auto c = samples::compareToReference(ao, ref, std::vector<unsigned char>(10, 1));
  EXPECT_DOUBLE_EQ(c.raw.fractionOver01, 0.1);
  EXPECT_NEAR(c.raw.meanBias, -0.025, 1e-7);
}

// Darkening where the reference sees nothing (issue 40: convex edges at 0.83 where (a) is 1).
TEST(Metrics, DarkeningWhereTheReferenceIsOpen) {
  FloatImage ref({10, 1}, 1, 1.0f), ao({10, 1}, 1, 1.0f);
  ref.data[0] = 0.5f, ao.data[0] = 0.2f;  // occluded in the reference: not an open pixel
  ref.data[1] = 0.999f, ao.data[1] = 0.5f;  // not exactly 1: not open either
  ao.data[2] = 0.83f;
  ao.data[3] = 0.95f;
  const auto c = samples::compareToReference(ao, ref, std::vector<unsigned char>(10, 1));
  EXPECT_EQ(c.raw.openPixels, 8u);
  EXPECT_NEAR(c.raw.openDarkening, (0.17 + 0.05) / 8, 1e-7);
  EXPECT_DOUBLE_EQ(c.raw.openShareUnder09, 1.0 / 8);
  const auto none = samples::compareToReference(ao, ao, std::vector<unsigned char>(10, 0));
  EXPECT_EQ(none.raw.openPixels, 0u);
  EXPECT_TRUE(std::isnan(none.raw.openDarkening));
}

// Undefined metrics are NaN (printed n/a, JSON null), not a flattering 1.
TEST(Metrics, UndefinedMetricsAreNaN) {
  FloatImage white({16, 16}, 1, 1.0f), grey({16, 16}, 1, 0.5f);
  const std::vector<unsigned char> all(white.data.size(), 1);
  // Two constant images: SSIM is 0/0 in its structure term; no occlusion in the AO: no scale fits best.
  const auto same = samples::compareToReference(white, white, all);
  EXPECT_TRUE(std::isnan(same.raw.ssim));
  EXPECT_TRUE(std::isnan(same.fittedIntensity));
  EXPECT_DOUBLE_EQ(same.raw.rmse, 0.0);
  EXPECT_DOUBLE_EQ(same.fitted.rmse, 0.0);
  const auto darker = samples::compareToReference(white, grey, all);
  EXPECT_TRUE(std::isnan(darker.raw.ssim));
  EXPECT_TRUE(std::isnan(darker.fittedIntensity));
  EXPECT_DOUBLE_EQ(darker.raw.meanBias, 0.5);
  // One constant image is enough for a defined SSIM (and occlusion in the AO for a defined scale).
  FloatImage ramp({16, 16}, 1, 0.0f);
  for (std::size_t i = 0; i < ramp.data.size(); ++i) ramp.data[i] = float(i % 16) / 16.0f;
  const auto defined = samples::compareToReference(ramp, grey, all);
  EXPECT_FALSE(std::isnan(defined.raw.ssim));
  EXPECT_FALSE(std::isnan(defined.fittedIntensity));
  // Nothing compared: every metric is undefined.
  const auto none = samples::compareToReference(ramp, grey, std::vector<unsigned char>(ramp.data.size(), 0));
  EXPECT_EQ(none.raw.pixels, 0u);
  for (double v : {none.raw.rmse, none.raw.meanBias, none.raw.ssim, none.raw.fractionOver01, none.fittedIntensity})
    EXPECT_TRUE(std::isnan(v));
  // A mask with no full 8x8 window: SSIM is undefined, the per-pixel metrics are not.
  std::vector<unsigned char> stripes(ramp.data.size(), 0);
  for (std::size_t i = 0; i < stripes.size(); i += 2) stripes[i] = 1;
  const auto sparse = samples::compareToReference(ramp, grey, stripes);
  EXPECT_TRUE(std::isnan(sparse.raw.ssim));
  EXPECT_FALSE(std::isnan(sparse.raw.rmse));
}

}  // namespace
