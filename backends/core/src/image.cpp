#include "sao/image.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace sao {

const char* toString(DepthFormat format) {
  switch (format) {
    case DepthFormat::D16: return "D16";
    case DepthFormat::D24: return "D24";
    case DepthFormat::D32F: return "D32F";
    case DepthFormat::LinearZ: return "R32F linear z";
  }
  return "?";
}

std::uint32_t encodeDepth(DepthFormat format, double d) {
  switch (format) {
    case DepthFormat::D16: return static_cast<std::uint32_t>(std::lround(std::clamp(d, 0.0, 1.0) * 65535.0));
    case DepthFormat::D24: return static_cast<std::uint32_t>(std::lround(std::clamp(d, 0.0, 1.0) * 16777215.0));
    case DepthFormat::D32F:
    case DepthFormat::LinearZ: return std::bit_cast<std::uint32_t>(static_cast<float>(d));
  }
  return 0;
}

double decodeDepth(DepthFormat format, std::uint32_t t) {
  switch (format) {
    case DepthFormat::D16: return double(t & 0xffffu) / 65535.0;
    case DepthFormat::D24: return double(t & 0xffffffu) / 16777215.0;
    case DepthFormat::D32F:
    case DepthFormat::LinearZ: return double(std::bit_cast<float>(t));
  }
  return 0;
}

double DepthImage::value(std::uint32_t x, std::uint32_t y) const {
  return decodeDepth(format, texels[std::size_t(y) * extent.width + x]);
}

}  // namespace sao
