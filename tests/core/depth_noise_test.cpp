// checkDepthValues names lossy-compression noise (values just outside [0, 1]) as noise, not as
// another depth convention (issue 39: B44's -6e-6 on sky texels was called "linear camera-space z").
#include <gtest/gtest.h>

#include <bit>
#include <string>

#include "sao/image.h"

namespace {

sao::DepthImage withValues(std::initializer_list<float> values) {
  sao::DepthImage d;
  d.extent = {std::uint32_t(values.size()), 1};
  d.format = sao::DepthFormat::D32F;
  for (float v : values) d.texels.push_back(std::bit_cast<std::uint32_t>(v));
  return d;
}

TEST(DepthNoise, TinyNegativeValuesAreNamedNoiseAroundZero) {
  const sao::Status st = sao::checkDepthValues(withValues({0.5f, -6e-6f, 0.0f, -2e-6f}));
  ASSERT_FALSE(st);
  EXPECT_NE(st.message.find("values just below 0 (the lowest -6e-06) are noise around a depth of 0"), std::string::npos)
      << st.message;
  EXPECT_EQ(st.message.find("camera-space"), std::string::npos) << st.message;
}

TEST(DepthNoise, TinyExcessAboveOneIsNamedNoiseAroundOne) {
  const sao::Status st = sao::checkDepthValues(withValues({0.5f, 1.0009765625f, 1.0f}));
  ASSERT_FALSE(st);
  EXPECT_NE(st.message.find("values just above 1 (the highest 1.00098) are noise around a depth of 1"),
            std::string::npos)
      << st.message;
}

TEST(DepthNoise, RealLinearZIsStillNamedLinearZ) {
  const sao::Status st = sao::checkDepthValues(withValues({-0.0005f, -3.0f}));
  ASSERT_FALSE(st);
  EXPECT_NE(st.message.find("look like linear camera-space z"), std::string::npos) << st.message;
}

}  // namespace
