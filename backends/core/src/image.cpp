#include "sao/image.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

// Imath's half conversions, header only: without the lookup table half -> float is bit
// arithmetic, so sao::core (and the gl and vulkan components that link it) references no Imath
// symbol and its package needs no Imath. The C functions (static inline), not Imath::half, whose
// inline members would differ from those of a program built with the table (an ODR clash).
#define IMATH_HALF_NO_LOOKUP_TABLE
#include <Imath/half.h>

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

double DepthImage::value(std::uint32_t x, std::uint32_t y, std::uint32_t sample) const {
  return decodeDepth(format, raw(x, y, sample));
}

// Imath's float -> binary16 rounds to nearest even, overflows to +-Inf and keeps subnormals, as a
// GPU's rgba16f does. NaN is handled here: Imath keeps (part of) its payload, and the contract in
// sao/image.h is a quiet NaN.
float quantizeHalf(float x) {
  if (std::isnan(x)) return x;
  return imath_half_to_float(imath_float_to_half(x));
}

std::uint16_t halfBits(float x) {
  if (std::isnan(x)) return std::uint16_t(((std::bit_cast<std::uint32_t>(x) >> 16) & 0x8000u) | 0x7E00u);
  return imath_float_to_half(x);
}

float halfToFloat(std::uint16_t bits) { return imath_half_to_float(bits); }

}  // namespace sao
