// Saving the window's pixels as PNG (stb_image_write from Debian's libstb).
#pragma once
#include <cstdint>
#include <string>

#include "sao/status.h"

namespace sao::viewer {

struct PixelLayout {
  bool bottomUp = false;  // row 0 is the bottom of the window (OpenGL's glReadPixels)
  bool bgra = false;      // B, G, R, A byte order (a B8G8R8A8 swapchain)
};

// `pixels`: width * height texels of 4 bytes, tightly packed. Writes an RGB PNG, top row first.
Status writeScreenshot(const std::string& path, int width, int height, const std::uint8_t* pixels, PixelLayout layout);

// "sao-viewer-YYYYMMDD-HHMMSS.png" in the current folder.
std::string defaultScreenshotName();

}  // namespace sao::viewer
