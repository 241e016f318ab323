#include "screenshot.h"

#include <stb/stb_image_write.h>

#include <ctime>
#include <filesystem>
#include <memory>
#include <vector>

namespace sao::viewer {
namespace {

// The run's rule: program, --overwrite for --screenshot's FILE, the inputs.
samples::WriteRules g_rules{"sao-viewer", false, {}};
std::string g_screenshotPath;  // --screenshot FILE

}  // namespace

Status setScreenshotRules(const samples::WriteRules& rules, const std::string& screenshotPath) {
  g_rules = rules;
  g_screenshotPath = screenshotPath;
  if (screenshotPath.empty()) return Status::success();
  return samples::OutputFile::check(screenshotPath, "--screenshot", samples::kPngFormat, rules);
}

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
  const bool named = !g_screenshotPath.empty() && path == g_screenshotPath;
  samples::WriteRules rules = g_rules;
  rules.overwrite = named && g_rules.overwrite;  // F12's names never replace a file
  std::unique_ptr<samples::OutputFile> file;
  if (Status s = samples::OutputFile::stage(path, named ? "--screenshot" : "the screenshot", samples::kPngFormat,
                                            rules, file);
      !s)
    return s;
  if (!stbi_write_png(file->stagedPath().c_str(), width, height, 3, rgb.data(), width * 3))
    return Status::error(StatusCode::IoError, "cannot write '" + path + "'");
  return file->commit();
}

std::string defaultScreenshotName() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char stamp[64];
  std::strftime(stamp, sizeof stamp, "sao-viewer-%Y%m%d-%H%M%S", &local);
  std::string name = std::string(stamp) + ".png";
  std::error_code ec;
  for (int n = 2; std::filesystem::exists(std::filesystem::symlink_status(name, ec)); ++n)
    name = std::string(stamp) + "-" + std::to_string(n) + ".png";
  return name;
}

}  // namespace sao::viewer
