// A float setting for a JSON writer: the double of the shortest decimal that reads back as the
// same float (0.02, not 0.019999999552965164, which is what the float holds as a double).
#pragma once
#include <charconv>

namespace sao::samples {

inline double shortestDecimal(float v) {
  char text[32];
  const char* end = std::to_chars(text, text + sizeof text, v).ptr;
  double d = v;  // NaN and infinity read back as themselves
  std::from_chars(text, end, d);
  return d;
}

}  // namespace sao::samples
