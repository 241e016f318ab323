// writeAoPng: 8-bit grey values, screen orientation (image row 0 = bottom, the PNG's first row is
// the top), clamping, NaN refused, errors.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>

#include "sao/io.h"
#include "temp_dir.h"

namespace sao {
namespace {

namespace fs = std::filesystem;
class AoPng : public test::TempDirTest {};

struct Png {
  int width = 0, height = 0, channelsInFile = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> pixels{nullptr, stbi_image_free};
  int at(int x, int y) const { return pixels.get()[std::size_t(y) * width + x]; }  // y = 0: first (top) PNG row
};

Png load(const std::string& path) {
  Png p;
  p.pixels.reset(stbi_load(path.c_str(), &p.width, &p.height, &p.channelsInFile, 1));
  return p;
}

TEST_F(AoPng, ValuesAndOrientation) {
  const std::uint32_t w = 5, h = 3;
  FloatImage ao({w, h}, 1);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) ao.at(x, y) = float(y * w + x) / float(w * h - 1);
  const std::string path = file("ao.png");
  const Status s = writeAoPng(path, ao);
  ASSERT_TRUE(s) << s.message;

  const Png png = load(path);
  ASSERT_NE(png.pixels, nullptr) << stbi_failure_reason();
  EXPECT_EQ(png.width, int(w));
  EXPECT_EQ(png.height, int(h));
  EXPECT_EQ(png.channelsInFile, 1) << "an 8-bit grey PNG";
  // The top-left screen pixel is image pixel (0, h-1), the PNG's first pixel.
  EXPECT_EQ(png.at(0, 0), int(std::lround(ao.at(0, h - 1) * 255.0)));
  EXPECT_EQ(png.at(0, 0), 182);  // 10/14 * 255 = 182.14
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x)
      EXPECT_EQ(png.at(int(x), int(h - 1 - y)), int(std::lround(double(ao.at(x, y)) * 255.0))) << x << "," << y;
  EXPECT_EQ(png.at(0, int(h - 1)), 0) << "image pixel (0, 0), bottom left, is the darkest";
  EXPECT_EQ(png.at(int(w - 1), 0), 255) << "image pixel (w-1, h-1), top right, is the brightest";
}

TEST_F(AoPng, ClampsAndRoundsAndPicksTheChannel) {
  FloatImage ao({4, 2}, 2, 0.25f);
  const float inf = std::numeric_limits<float>::infinity();
  const float values[] = {-0.5f, 1.7f, inf, -inf, 0.5f, 1.0f / 255.0f * 0.49f, 254.6f / 255.0f, 1.0f};
  const int expected[] = {0, 255, 255, 0, 128, 0, 255, 255};
  for (std::uint32_t i = 0; i < 8; ++i) ao.at(i % 4, i / 4, 1) = values[i];
  const std::string path = file("clamp.png");
  ASSERT_TRUE(writeAoPng(path, ao, 1));
  const Png png = load(path);
  ASSERT_NE(png.pixels, nullptr);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(png.at(i % 4, 1 - i / 4), expected[i]) << "value " << values[i];

  ASSERT_TRUE(writeAoPng(path, ao, 0));
  const Png first = load(path);
  ASSERT_NE(first.pixels, nullptr);
  EXPECT_EQ(first.at(0, 0), 64);  // 0.25 * 255 = 63.75
}

TEST_F(AoPng, NaNIsRefused) {
  FloatImage ao({6, 4}, 1, 0.5f);
  ao.at(4, 2) = std::numeric_limits<float>::quiet_NaN();
  ao.at(1, 3) = std::numeric_limits<float>::quiet_NaN();
  const std::string path = file("nan.png");
  const Status s = writeAoPng(path, ao);
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_NE(s.message.find(path), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("pixel (4, 2) channel 0 is NaN"), std::string::npos) << s.message;
  EXPECT_FALSE(fs::exists(path)) << "nothing is written";
}

TEST_F(AoPng, Errors) {
  const FloatImage ao({3, 3}, 1, 0.5f);
  const std::string path = file("e.png");
  Status s = writeAoPng(path, ao, 1);
  EXPECT_EQ(s.code, StatusCode::InvalidInput);
  EXPECT_NE(s.message.find("channel 1 asked of an image with 1 channels"), std::string::npos) << s.message;
  EXPECT_EQ(writeAoPng(path, FloatImage{}).code, StatusCode::InvalidExtent);
  FloatImage shortImage = ao;
  shortImage.data.pop_back();
  EXPECT_EQ(writeAoPng(path, shortImage).code, StatusCode::InvalidInput);
  EXPECT_FALSE(fs::exists(path));

  s = writeAoPng(tmp_.path().string(), ao);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_NE(s.message.find("is a directory"), std::string::npos) << s.message;
  const std::string nowhere = file("missing/dir/e.png");
  s = writeAoPng(nowhere, ao);
  EXPECT_EQ(s.code, StatusCode::IoError);
  EXPECT_NE(s.message.find(nowhere), std::string::npos) << s.message;
}

}  // namespace
}  // namespace sao
