#include "sao/samples/shading.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>

namespace sao::samples {

FloatImage shadeEnvironment(const FloatImage& normals, const FloatImage& positions, const FloatImage* ao,
                            std::uint32_t g) {
  const Extent e{normals.extent.width - 2 * g, normals.extent.height - 2 * g};
  FloatImage out(e, 3, 0.0f);
  const float sky[3] = {0.55f, 0.7f, 1.0f}, ground[3] = {0.25f, 0.2f, 0.15f}, albedo = 0.75f;
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x) {
      if (positions.at(x + g, y + g, 3) == 0.0f) {
        for (int c = 0; c < 3; ++c) out.at(x, y, c) = sky[c];
        continue;
      }
      // Irradiance of a sky/ground hemisphere light for a normal with camera-space up component.
      const float up = normals.at(x + g, y + g, 1);
      const float t = 0.5f + 0.5f * up;
      const float a = ao ? std::clamp(ao->at(x, y), 0.0f, 1.0f) : 1.0f;
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = albedo * (t * sky[c] + (1 - t) * ground[c]) * a;
    }
  return out;
}

namespace {

// 8-bit RGB PNG of the first three channels, each through `encode` (a value in [0, 1] out), row
// height-1 first.
template <class Encode>
Status writePng(const std::string& path, const FloatImage& image, Encode encode) {
  const Extent e = image.extent;
  std::vector<unsigned char> px(std::size_t(e.width) * e.height * 3);
  for (std::uint32_t y = 0; y < e.height; ++y)
    for (std::uint32_t x = 0; x < e.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const float s = std::clamp(encode(image.at(x, e.height - 1 - y, c)), 0.0f, 1.0f);
        px[(std::size_t(y) * e.width + x) * 3 + c] = static_cast<unsigned char>(std::lround(s * 255.0f));
      }
  if (!stbi_write_png(path.c_str(), int(e.width), int(e.height), 3, px.data(), int(e.width) * 3))
    return Status::error(StatusCode::IoError, "cannot write '" + path + "'");
  return Status::success();
}

}  // namespace

Status writeRgbPng(const std::string& path, const FloatImage& rgb) {
  return writePng(path, rgb, [](float linear) {
    const float v = std::clamp(linear, 0.0f, 1.0f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  });
}

Status writeNormalPng(const std::string& path, const FloatImage& normals) {
  return writePng(path, normals, [](float v) { return 0.5f + 0.5f * v; });
}

}  // namespace sao::samples
