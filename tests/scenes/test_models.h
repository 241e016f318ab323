// The models the scene tests read: Debian's assimp-testmodels, a unit cube, and a scratch folder
// per test to write files into.
#pragma once
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

#include "temp_dir.h"

namespace sao::scenes::test {

using sao::test::TempDir;

// Where Debian's assimp-testmodels package puts its files.
inline const std::filesystem::path kAssimpModels = SAO_ASSIMP_MODELS;

// A unit cube as an OBJ (8 vertices, 6 quads, so 12 triangles once triangulated).
inline constexpr std::string_view kCubeObj =
    "# unit cube\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

// A test input on one printable line, for the names of parameterised cases (gtest would print a
// case struct's bytes, pointers included, and the ctest names would change with every build).
inline std::string escapedText(std::string_view text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    if (c == '\n') out += "\\n";
    else if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') out += char(c);
    else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", unsigned(c));
      out += hex;
    }
  }
  return out + "\"";
}

}  // namespace sao::scenes::test
