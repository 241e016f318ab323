#include "screenshot.h"

#include <stb/stb_image_write.h>

#include <ctime>
#include <vector>

namespace sao::viewer {

Status writeScreenshot(const std::string& path, int width, int height, const std::uint8_t* pixels, PixelLayout layout) {
  if (width <= 0 || height <= 0 || !pixels)
    return Status::error(StatusCode::InvalidInput, "no pixels to save for '" + path + "'");
  std::vector<std::uint8_t> rgb(std::size_t(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    const int src = layout.bottomUp ? height - 1 - y : y;
    for (int x = 0; x < width; ++x) {
      const std::uint8_t* p = pixels + (std::size_t(src) * width + x) * 4;
      std::uint8_t* q = rgb.data() + (std::size_t(y) * width + x) * 3;
      q[0] = layout.bgra ? p[2] : p[0];
      q[1] = p[1];
      q[2] = layout.bgra ? p[0] : p[2];
    }
  }
  if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3))
    return Status::error(StatusCode::IoError, "cannot write '" + path + "'");
  return Status::success();
}

std::string defaultScreenshotName() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char name[64];
  std::strftime(name, sizeof name, "sao-viewer-%Y%m%d-%H%M%S.png", &local);
  return name;
}

}  // namespace sao::viewer
