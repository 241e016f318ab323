// Image comparison for the tests of every backend: bit-for-bit equality, and the agreement of one
// channel within a tolerance, with failure images to look at when it does not hold.
#pragma once
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>

#include "sao/image.h"

namespace sao::test {

// Bit-for-bit equality (NaN payloads and -0 count as bits).
inline bool sameBits(const FloatImage& a, const FloatImage& b) {
  if (a.extent != b.extent || a.channels != b.channels || a.data.size() != b.data.size()) return false;
  for (std::size_t i = 0; i < a.data.size(); ++i)
    if (std::bit_cast<std::uint32_t>(a.data[i]) != std::bit_cast<std::uint32_t>(b.data[i])) return false;
  return true;
}

// How many values differ in their bits (every value of the larger image when the shapes differ).
inline std::size_t differingValues(const FloatImage& a, const FloatImage& b) {
  if (a.extent != b.extent || a.channels != b.channels || a.data.size() != b.data.size())
    return std::max(a.data.size(), b.data.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i)
    n += std::bit_cast<std::uint32_t>(a.data[i]) != std::bit_cast<std::uint32_t>(b.data[i]);
  return n;
}

struct Agreement {
  double maxAbs = 0;          // largest |actual - expected|
  double p999 = 0;            // 99.9th percentile of |actual - expected|
  double fractionWithin = 0;  // share of pixels within `within`
  std::size_t beyond = 0;     // pixels beyond `never`
  std::size_t nonFinite = 0;  // NaN / Inf in actual
};

// At least 99.9% of the pixels within `within`, none beyond `never`, none non-finite.
bool acceptable(const Agreement& a);

// Compares channel `channel` of two images; a size or channel mismatch fails the running test.
// When the result is not acceptable, writes <failureDir>/<name>_{actual,expected,diff}.png (diff:
// white = `never`) and <name>_{actual,expected}.exr, and says where in `note`.
Agreement compare(const FloatImage& actual, const FloatImage& expected, std::uint32_t channel, double within,
                  double never, const std::string& failureDir, const std::string& name, std::string* note = nullptr);

// compare() with its failure images always in one folder: each backend's test support has one,
// named `compare`, so that its tests call compare(actual, expected, channel, within, never, name).
struct FailureImagesIn {
  std::string failureDir;
  Agreement operator()(const FloatImage& actual, const FloatImage& expected, std::uint32_t channel, double within,
                       double never, const std::string& name, std::string* note = nullptr) const {
    return compare(actual, expected, channel, within, never, failureDir, name, note);
  }
};

}  // namespace sao::test
