// Saving the window's pixels as PNG (stb_image_write from Debian's libstb), by the writers' rule of
// every sample program (sao/samples/output_files.h): a new file renamed into place, no existing
// file replaced without --overwrite, a .png name, never the scene file read.
#pragma once
#include <cstdint>
#include <string>

#include "sao/samples/output_files.h"
#include "sao/status.h"

namespace sao::viewer {

struct PixelLayout {
  bool bottomUp = false;  // row 0 is the bottom of the window (OpenGL's glReadPixels)
  bool bgra = false;      // B, G, R, A byte order (a B8G8R8A8 swapchain)
};

// The rule of this run's screenshots (--overwrite, the inputs), and --screenshot's FILE (empty:
// none): set once from the command line, before the first frame. Returns the checks of FILE
// (InvalidInput: a bad name, exit status 2; IoError: a file in the way, exit status 1), so a
// scripted run is refused before its window opens.
Status setScreenshotRules(const samples::WriteRules& rules, const std::string& screenshotPath);

// `pixels`: width * height texels of 4 bytes, tightly packed. Writes an RGB PNG, top row first.
// Only --screenshot's FILE may replace an existing file (with --overwrite); F12's names are new.
Status writeScreenshot(const std::string& path, int width, int height, const std::uint8_t* pixels, PixelLayout layout);

// "sao-viewer-YYYYMMDD-HHMMSS.png" in the current folder, "-2", "-3", ... added when that exists.
std::string defaultScreenshotName();

}  // namespace sao::viewer
