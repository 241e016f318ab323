#include "sao/image.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

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

float quantizeHalf(float x) {
  if (!std::isfinite(x) || x == 0.0f) return x;
  const float a = std::fabs(x);
  int e = 0;
  (void)std::frexp(a, &e);              // a = f * 2^e, f in [0.5, 1)
  const int q = std::max(e - 11, -24);  // log2 of the binary16 spacing at a
  const float t = std::ldexp(a, -q);    // exact: a power-of-two scaling
  float r = std::floor(t);
  const float frac = t - r;             // exact
  if (frac > 0.5f || (frac == 0.5f && std::fmod(r, 2.0f) != 0.0f)) r += 1.0f;
  float v = std::ldexp(r, q);
  if (v > 65504.0f) v = std::numeric_limits<float>::infinity();
  return std::copysign(v, x);
}

std::uint16_t halfBits(float x) {
  const std::uint16_t sign = std::uint16_t((std::bit_cast<std::uint32_t>(x) >> 16) & 0x8000u);
  if (std::isnan(x)) return std::uint16_t(sign | 0x7E00u);
  const float a = std::fabs(quantizeHalf(x));
  if (std::isinf(a)) return std::uint16_t(sign | 0x7C00u);
  if (a < 0x1p-14f) return std::uint16_t(sign | std::uint16_t(a * 0x1p24f));  // subnormal: a / 2^-24, exact
  int e = 0;
  const float f = std::frexp(a, &e);  // a = f * 2^e = (2f) * 2^(e-1), f in [0.5, 1)
  const auto mantissa = std::uint32_t(f * 2048.0f) - 1024u;  // exact: a has at most 11 significant bits
  return std::uint16_t(sign | (std::uint32_t(e - 1 + 15) << 10) | mantissa);
}

float halfToFloat(std::uint16_t h) {
  const std::uint32_t sign = (h & 0x8000u) << 16;
  std::uint32_t exp = (h >> 10) & 0x1f, mant = h & 0x3ffu;
  std::uint32_t bits;
  if (exp == 0) {
    if (mant == 0) bits = sign;
    else {  // subnormal: normalise
      int e = -1;
      do {
        ++e;
        mant <<= 1;
      } while (!(mant & 0x400u));
      bits = sign | std::uint32_t(127 - 15 - e) << 23 | (mant & 0x3ffu) << 13;
    }
  } else if (exp == 31) {
    bits = sign | 0x7f800000u | mant << 13;
  } else {
    bits = sign | (exp + 112) << 23 | mant << 13;
  }
  return std::bit_cast<float>(bits);
}

}  // namespace sao
