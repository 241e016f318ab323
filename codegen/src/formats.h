// Every image format the annotated source may name, with its facts: one table, from which the
// parser's list, the generated gen::Format enum and gen::kFormatInfo (channels, bytes, the GL
// internal format and the VkFormat) are made. The enum's order is the table's (values stay stable:
// a new format goes last).
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

namespace sao::codegen {

struct FormatFacts {
  std::string_view name;      // as directives and GLSL image qualifiers spell it: r32f, rgba8, depth
  std::string_view enumName;  // gen::Format's enumerator
  std::uint32_t channels;
  std::uint32_t bytesPerTexel;
  std::uint32_t glInternalFormat;  // GL_R32F ... (GL_DEPTH_COMPONENT32F for depth)
  std::uint32_t vkFormat;          // VK_FORMAT_R32_SFLOAT ... (VK_FORMAT_D32_SFLOAT for depth)
  bool colour;                     // an image a pass may store to (every format but depth)
  bool unorm;                      // 8-bit unsigned normalised
  // OpenGL ES 3.1 (GLSL ES 3.10, 4.4.7): a compute shader may store to it (esStorage); it may also
  // load from it through the same image, not readonly or writeonly (esReadWrite: r32f only).
  bool esStorage;
  bool esReadWrite;
};

std::span<const FormatFacts> formats();
std::optional<FormatFacts> findFormat(std::string_view name);

}  // namespace sao::codegen
