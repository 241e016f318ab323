// checkDepthValues (sao/image.h): depth from a file is refused when its texels are not what its
// format holds, naming the count, the first bad texel and the likely cause; -0.0 is 0.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "sao/image.h"

namespace {

sao::DepthImage filled(sao::DepthFormat format, float value, std::uint32_t w = 8, std::uint32_t h = 4) {
  sao::DepthImage d;
  d.extent = {w, h};
  d.format = format;
  d.texels.assign(std::size_t(w) * h, std::bit_cast<std::uint32_t>(value));
  return d;
}

void put(sao::DepthImage& d, std::uint32_t x, std::uint32_t y, float v) {
  d.texels[std::size_t(y) * d.extent.width + x] = std::bit_cast<std::uint32_t>(v);
}

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

TEST(DepthValues, HardwareDepthInZeroOneIsAcceptedWithMinusZero) {
  sao::DepthImage d = filled(sao::DepthFormat::D32F, 0.5f);
  put(d, 0, 0, 0.0f);
  put(d, 1, 0, -0.0f);  // a sky written as -0.0 with reversed-Z: it is 0
  put(d, 2, 0, 1.0f);
  put(d, 3, 0, std::numeric_limits<float>::denorm_min());
  EXPECT_TRUE(sao::checkDepthValues(d).ok()) << sao::checkDepthValues(d).message;
}

TEST(DepthValues, NaNInfinitiesAndOutOfRangeAreCountedAndTheFirstNamed) {
  sao::DepthImage d = filled(sao::DepthFormat::D32F, 0.5f);
  put(d, 5, 1, kNaN);
  put(d, 6, 1, kNaN);
  put(d, 7, 1, kInf);
  put(d, 0, 2, -kInf);
  put(d, 1, 2, -0.25f);
  put(d, 2, 2, -std::numeric_limits<float>::denorm_min());  // below 0, unlike -0.0
  put(d, 3, 2, 1.5f);
  const sao::Status st = sao::checkDepthValues(d);
  EXPECT_EQ(st.code, sao::StatusCode::InvalidInput);
  EXPECT_EQ(st.message,
            "7 of 32 texels are not D32F depth (2 NaN, 1 +inf, 1 -inf, 2 below 0, 1 above 1); the first is (5, 1) = "
            "nan: hardware depth lies in [0, 1] and holds no NaN or infinity; write the sky as the clear value (1, or "
            "0 with reversed-Z)");
}

TEST(DepthValues, LinearDistanceInMetresIsRecognised) {
  sao::DepthImage d = filled(sao::DepthFormat::D32F, 0.0f);
  for (std::uint32_t x = 0; x < 8; ++x) put(d, x, 3, 2.5f + float(x));
  const sao::Status st = sao::checkDepthValues(d);
  EXPECT_EQ(st.message,
            "8 of 32 texels are not D32F depth (8 above 1); the first is (0, 3) = 2.5: values above 1 look like linear "
            "depth (a distance in view units, e.g. metres), not hardware depth in [0, 1]: store it as LinearZ "
            "(camera-space z, negative in front of the camera; sao.depthFormat \"LinearZ\", see sao/io.h)");
}

TEST(DepthValues, LinearCameraSpaceZIsRecognised) {
  const sao::Status st = sao::checkDepthValues(filled(sao::DepthFormat::D32F, -3.0f));
  EXPECT_NE(st.message.find("32 of 32 texels are not D32F depth (32 below 0); the first is (0, 0) = -3: values below "
                            "0 look like linear camera-space z"),
            std::string::npos)
      << st.message;
}

TEST(DepthValues, IntegerTexelsAboveTheirRangeAreRefused) {
  sao::DepthImage d16;
  d16.extent = {2, 1};
  d16.format = sao::DepthFormat::D16;
  d16.texels = {65535u, 65536u};
  EXPECT_EQ(sao::checkDepthValues(d16).message,
            "1 of 2 texels are above 65535, the largest D16 texel; the first is (1, 0) = 65536");
  sao::DepthImage d24 = d16;
  d24.format = sao::DepthFormat::D24;
  EXPECT_TRUE(sao::checkDepthValues(d24).ok());
  d24.texels = {1u << 24, 0};
  EXPECT_EQ(sao::checkDepthValues(d24).message,
            "1 of 2 texels are above 16777215, the largest D24 texel; the first is (0, 0) = 16777216");
}

TEST(DepthValues, LinearZRefusesOnlyNaN) {
  sao::DepthImage z = filled(sao::DepthFormat::LinearZ, -2.0f);
  for (float sky : {0.0f, -0.0f, 7.0f, kInf, -kInf}) {
    put(z, 0, 0, sky);
    EXPECT_TRUE(sao::checkDepthValues(z).ok()) << sky;
  }
  put(z, 4, 2, kNaN);
  EXPECT_EQ(sao::checkDepthValues(z).message,
            "1 of 32 texels are not R32F linear z depth (1 NaN); the first is (4, 2) = nan: linear z holds no NaN; "
            "write the sky as +0 or +inf");
}

TEST(DepthValues, TexelsThatDoNotMatchTheExtentAreRefused) {
  sao::DepthImage d = filled(sao::DepthFormat::D32F, 0.5f);
  d.texels.pop_back();
  EXPECT_EQ(sao::checkDepthValues(d).message, "depth image holds 31 texels, its extent 8x4 needs 32");
}

}  // namespace
