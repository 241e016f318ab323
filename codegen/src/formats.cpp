#include "formats.h"

#include <array>

namespace sao::codegen {
namespace {

// The numbers are the API's enumerants (GL 4.3 core; Vulkan 1.1), checked against the real headers
// by the GL and Vulkan tests (gl.Formats.*, vk.Formats.*).
constexpr std::array<FormatFacts, 9> kFormats = {{
    {"r32f", "R32F", 1, 4, 0x822E, 100, true, false},
    {"rg32f", "RG32F", 2, 8, 0x8230, 103, true, false},
    {"r16f", "R16F", 1, 2, 0x822D, 76, true, false},
    {"rg16f", "RG16F", 2, 4, 0x822F, 83, true, false},
    {"rgba16f", "RGBA16F", 4, 8, 0x881A, 97, true, false},
    {"r8", "R8", 1, 1, 0x8229, 9, true, true},
    {"rgba8", "RGBA8", 4, 4, 0x8058, 37, true, true},
    {"depth", "Depth", 1, 4, 0x8CAC, 126, false, false},
    {"rgba32f", "RGBA32F", 4, 16, 0x8814, 109, true, false},
}};

}  // namespace

std::span<const FormatFacts> formats() { return kFormats; }

std::optional<FormatFacts> findFormat(std::string_view name) {
  for (const FormatFacts& f : kFormats)
    if (f.name == name) return f;
  return std::nullopt;
}

}  // namespace sao::codegen
