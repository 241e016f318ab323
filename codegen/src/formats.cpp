#include "formats.h"

#include <array>

namespace sao::codegen {
namespace {

// The numbers are the API's enumerants (GL 4.3 core; Vulkan 1.1), checked against the real headers
// by the GL and Vulkan tests (gl.Formats.*, vk.Formats.*). The ES columns: GLSL ES 3.10's image
// format qualifiers (section 4.4.7) and its rule that only r32f images may be both read and written.
constexpr std::array<FormatFacts, 9> kFormats = {{
    {"r32f", "R32F", 1, 4, 0x822E, 100, true, false, true, true},
    {"rg32f", "RG32F", 2, 8, 0x8230, 103, true, false, false, false},
    {"r16f", "R16F", 1, 2, 0x822D, 76, true, false, false, false},
    {"rg16f", "RG16F", 2, 4, 0x822F, 83, true, false, false, false},
    {"rgba16f", "RGBA16F", 4, 8, 0x881A, 97, true, false, true, false},
    {"r8", "R8", 1, 1, 0x8229, 9, true, true, false, false},
    {"rgba8", "RGBA8", 4, 4, 0x8058, 37, true, true, true, false},
    {"depth", "Depth", 1, 4, 0x8CAC, 126, false, false, false, false},
    {"rgba32f", "RGBA32F", 4, 16, 0x8814, 109, true, false, true, false},
}};

}  // namespace

std::span<const FormatFacts> formats() { return kFormats; }

std::optional<FormatFacts> findFormat(std::string_view name) {
  for (const FormatFacts& f : kFormats)
    if (f.name == name) return f;
  return std::nullopt;
}

}  // namespace sao::codegen
