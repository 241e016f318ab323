// Bit-for-bit image equality for the tests of every backend (NaN payloads and -0 count as bits).
#pragma once
#include <bit>
#include <cstdint>

#include "sao/image.h"

namespace sao::test {

inline bool sameBits(const FloatImage& a, const FloatImage& b) {
  if (a.extent != b.extent || a.channels != b.channels || a.data.size() != b.data.size()) return false;
  for (std::size_t i = 0; i < a.data.size(); ++i)
    if (std::bit_cast<std::uint32_t>(a.data[i]) != std::bit_cast<std::uint32_t>(b.data[i])) return false;
  return true;
}

}  // namespace sao::test
