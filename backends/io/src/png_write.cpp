// writeAoPng: the 8-bit grey PNG of the ambient-obscurance result, through stb. See sao/io.h for
// the row order.
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "io_checks.h"
#include "sao/io.h"

namespace sao {
namespace {

using namespace io::detail;

Status writePng(const std::string& path, const FloatImage& ao, std::uint32_t channel) {
  if (Status s = checkWritable(path); !s) return s;
  if (Status s = checkExtent(path, ao.extent); !s) return s;
  if (channel >= ao.channels)
    return fail(StatusCode::InvalidInput, path,
                "channel " + std::to_string(channel) + " asked of an image with " + std::to_string(ao.channels) +
                    " channels");
  const std::size_t w = ao.extent.width, h = ao.extent.height;
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
  return guarded(path, "write the PNG", [&] { return writePng(path, ao, channel); });
}

}  // namespace sao
