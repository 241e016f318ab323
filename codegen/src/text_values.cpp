#include "text_values.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <regex>

namespace sao::codegen {

bool isIdentifier(const std::string& s) {
  static const std::regex re("^[A-Za-z_][A-Za-z0-9_]*$");
  return std::regex_match(s, re);
}

bool parseNumber(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}

bool parseInt(const std::string& s, int& out) {
  static const std::regex re("^[+-]?[0-9]+$");
  if (!std::regex_match(s, re) || s.size() > 11) return false;
  // from_chars, not stoi: a value beyond int (e.g. 2540685460) is an error, not an exception
  // (found by fuzz_codegen_parser).
  const char* first = s.data() + (s[0] == '+' ? 1 : 0);
  int v = 0;
  const auto [end, ec] = std::from_chars(first, s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return false;
  out = v;
  return true;
}

std::vector<std::string> splitList(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == sep) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

}  // namespace sao::codegen
