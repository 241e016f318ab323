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

}  // namespace
