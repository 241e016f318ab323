// Private to sao_scenes: a double read from a file as a float, without undefined behaviour.
#pragma once
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <string_view>

namespace sao::scenes::detail {

// Beyond float range becomes +-inf (which validateMesh then reports), NaN stays NaN.
inline float toFloat(double v) {
  constexpr double kMax = std::numeric_limits<float>::max();
  if (std::isnan(v)) return std::numeric_limits<float>::quiet_NaN();
  if (v > kMax) return std::numeric_limits<float>::infinity();
  if (v < -kMax) return -std::numeric_limits<float>::infinity();
  return float(v);
}

// A whole word as a number ("+" allowed in front, "nan" and "inf" too); beyond double range it is
// +-inf or 0, as strtod gives. False if the word is not a number.
inline bool parseNumber(std::string_view word, double& v) {
  if (word.size() > 1 && word[0] == '+' && word[1] != '-') word.remove_prefix(1);
  const auto [p, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
  if (p != word.data() + word.size()) return false;
  if (ec == std::errc::result_out_of_range) {
    const std::string copy(word);
    v = std::strtod(copy.c_str(), nullptr);
    return true;
  }
  return ec == std::errc();
}

}  // namespace sao::scenes::detail
