// 8-bit grey PNG of the ambient-obscurance result. See sao/io.h for the row order.
#include <stb/stb_image_write.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "sao/io.h"

namespace sao {
namespace {

Status fail(StatusCode code, const std::string& path, const std::string& problem) {
  return Status::error(code, path + ": " + problem);
}

Status writePng(const std::string& path, const FloatImage& ao, std::uint32_t channel) {
  if (path.empty()) return Status::error(StatusCode::IoError, "empty path");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return fail(StatusCode::IoError, path, "is a directory, cannot write a file there");
  const Extent e = ao.extent;
  if (e.width == 0 || e.height == 0)
    return fail(StatusCode::InvalidExtent, path,
                "image is " + std::to_string(e.width) + "x" + std::to_string(e.height) + "; both sides must be > 0");
  if (e.width > kMaxImageSide || e.height > kMaxImageSide)
    return fail(StatusCode::InvalidExtent, path,
                "image is " + std::to_string(e.width) + "x" + std::to_string(e.height) + "; the largest side is " +
                    std::to_string(kMaxImageSide));
  if (channel >= ao.channels)
    return fail(StatusCode::InvalidInput, path,
                "channel " + std::to_string(channel) + " asked of an image with " + std::to_string(ao.channels) +
                    " channels");
  const std::size_t w = e.width, h = e.height;
  if (ao.data.size() != w * h * ao.channels)
    return fail(StatusCode::InvalidInput, path,
                "image has " + std::to_string(ao.data.size()) + " floats, its extent and channels need " +
                    std::to_string(w * h * ao.channels));

  // Image row 0 is the bottom of the screen; the PNG's first row is the top.
  std::vector<unsigned char> pixels(w * h);
  for (std::size_t y = 0; y < h; ++y)
    for (std::size_t x = 0; x < w; ++x) {
      const float v = ao.at(std::uint32_t(x), std::uint32_t(y), channel);
      if (std::isnan(v))
        return fail(StatusCode::InvalidInput, path,
                    "pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") channel " + std::to_string(channel) +
                        " is NaN (row 0 = bottom); refusing to write it");
      pixels[(h - 1 - y) * w + x] =
          static_cast<unsigned char>(std::lround(double(std::clamp(v, 0.0f, 1.0f)) * 255.0));
    }

  if (!stbi_write_png(path.c_str(), int(w), int(h), 1, pixels.data(), int(w)))
    return fail(StatusCode::IoError, path, "cannot write the PNG (cannot create the file, or the disk is full)");
  return Status::success();
}

}  // namespace

Status writeAoPng(const std::string& path, const FloatImage& ao, std::uint32_t channel) {
  try {
    return writePng(path, ao, channel);
  } catch (const std::exception& ex) {
    return fail(StatusCode::IoError, path, std::string("cannot write the PNG: ") + ex.what());
  } catch (...) {
    return fail(StatusCode::IoError, path, "cannot write the PNG: unknown error");
  }
}

}  // namespace sao
