#include "std140.h"

#include <charconv>
#include <regex>

namespace sao::codegen {
namespace {

struct TypeLayout {
  int size;
  int align;
  bool arrayable;  // std140 array stride equals the C++ element size
};

bool layoutOf(const std::string& type, TypeLayout& out) {
  if (type == "float" || type == "int" || type == "uint") out = {4, 4, false};
  else if (type == "vec2" || type == "ivec2" || type == "uvec2") out = {8, 8, false};
  else if (type == "vec4" || type == "ivec4" || type == "uvec4") out = {16, 16, true};
  else if (type == "mat4") out = {64, 16, true};
  else return false;
  return true;
}

std::string unsafeReason(const std::string& type) {
  if (type == "vec3" || type == "ivec3" || type == "uvec3" || type == "bvec3")
    return "std140 gives a " + type + " 16-byte alignment but 12 bytes of size, so the next member can "
           "pack into its last 4 bytes; use a 4-component vector";
  if (type == "mat3" || type == "mat2" || type == "mat2x3" || type == "mat3x2")
    return "std140 pads every column of a " + type + " to 16 bytes; use mat4 or vec4 columns";
  if (type == "bool" || type == "bvec2" || type == "bvec4")
    return "a GLSL bool is 4 bytes in std140 but 1 in C++; use int";
  if (type.rfind("d", 0) == 0 || type == "double") return "64-bit types are not available in GLSL 4.30 compute on every driver";
  return "";
}

std::string stripComment(const std::string& s) {
  const auto p = s.find("//");
  return p == std::string::npos ? s : s.substr(0, p);
}

bool blank(const std::string& s) { return s.find_first_not_of(" \t") == std::string::npos; }

}  // namespace

ParamBlock parseParamBlock(const std::string& name, const SourceLoc& directiveLoc,
                           const std::vector<SourceLine>& lines, size_t first, Diagnostics& diags) {
  ParamBlock block;
  block.loc = directiveLoc;
  block.name = name;
  size_t i = first;
  while (i < lines.size() && blank(stripComment(lines[i].text))) ++i;
  const std::regex headerRe("^\\s*layout\\s*\\(\\s*std140\\s*,\\s*binding\\s*=\\s*0\\s*\\)\\s*uniform\\s+" + name +
                            "\\s*(\\{)?\\s*$");
  std::smatch m;
  std::string header = i < lines.size() ? stripComment(lines[i].text) : std::string();
  if (i >= lines.size() || !std::regex_match(header, m, headerRe)) {
    diags.error(i < lines.size() ? lines[i].loc : directiveLoc,
                "parameter block '" + name + "' must follow as 'layout(std140, binding = 0) uniform " + name + " {'");
    return block;
  }
  bool open = m[1].matched;
  ++i;
  if (!open) {
    while (i < lines.size() && blank(stripComment(lines[i].text))) ++i;
    if (i < lines.size() && std::regex_match(stripComment(lines[i].text), std::regex("^\\s*\\{\\s*$"))) {
      open = true;
      ++i;
    }
  }
  if (!open) {
    diags.error(directiveLoc, "parameter block '" + name + "' has no opening '{'");
    return block;
  }
  static const std::regex memberRe(R"(^\s*(\w+)\s+(\w+)\s*(\[\s*(\d+)\s*\])?\s*;\s*$)");
  static const std::regex closeRe(R"(^\s*\}\s*;\s*$)");
  int offset = 0;
  for (; i < lines.size(); ++i) {
    const std::string text = stripComment(lines[i].text);
    if (blank(text)) continue;
    if (text.find_first_not_of(" \t") != std::string::npos && text[text.find_first_not_of(" \t")] == '#') break;
    if (std::regex_match(text, closeRe)) {
      block.size = (offset + 15) / 16 * 16;
      if (block.members.empty()) diags.error(directiveLoc, "parameter block '" + name + "' has no members");
      return block;
    }
    if (text.find('}') != std::string::npos) {
      diags.error(lines[i].loc, "parameter block '" + name + "' must end with '};' on a line of its own (no instance name)");
      return block;
    }
    if (!std::regex_match(text, m, memberRe)) {
      diags.error(lines[i].loc, "cannot read block member: expected 'type name;' or 'type name[N];', one per line");
      continue;
    }
    BlockMember member;
    member.loc = lines[i].loc;
    member.glslType = m[1].str();
    member.name = m[2].str();
    // At most the 16 KiB every GL implementation gives a uniform block (GL_MAX_UNIFORM_BLOCK_SIZE),
    // checked before any arithmetic: a huge N must be an error, not an exception or an overflow.
    constexpr long long kMaxBlockBytes = 16384;
    if (m[4].matched) {
      long long n = 0;
      const std::string digits = m[4].str();
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
      if (ec != std::errc() || end != digits.data() + digits.size() || n > kMaxBlockBytes / 16) {
        diags.error(lines[i].loc, "array size of block member '" + member.name + "' is " + digits + "; the block must fit " +
                                      std::to_string(kMaxBlockBytes) + " bytes (at most " +
                                      std::to_string(kMaxBlockBytes / 16) + " elements)");
        continue;
      }
      member.arraySize = int(n);
    }
    const std::string why = unsafeReason(member.glslType);
    TypeLayout layout{};
    if (!why.empty()) {
      diags.error(member.loc, "std140-unsafe member '" + member.name + "' of type " + member.glslType + ": " + why);
      continue;
    }
    if (!layoutOf(member.glslType, layout)) {
      diags.error(member.loc, "unsupported type '" + member.glslType + "' for block member '" + member.name +
                                  "' (allowed: float int uint vec2 ivec2 uvec2 vec4 ivec4 uvec4 mat4)");
      continue;
    }
    if (m[3].matched && (!layout.arrayable || member.arraySize <= 0)) {
      diags.error(member.loc, "std140-unsafe member '" + member.name + "': arrays of " + member.glslType +
                                  " have a 16-byte stride in std140; use an array of vec4/ivec4/uvec4/mat4");
      continue;
    }
    for (const auto& other : block.members)
      if (other.name == member.name) diags.error(member.loc, "duplicate block member '" + member.name + "'");
    offset = (offset + layout.align - 1) / layout.align * layout.align;
    member.offset = offset;
    member.size = layout.size * (member.arraySize > 0 ? member.arraySize : 1);
    if (offset + member.size > kMaxBlockBytes) {
      diags.error(member.loc, "block member '" + member.name + "' ends at byte " + std::to_string(offset + member.size) +
                                  "; the block must fit " + std::to_string(kMaxBlockBytes) + " bytes");
      continue;
    }
    offset += member.size;
    block.members.push_back(member);
  }
  diags.error(directiveLoc, "parameter block '" + name + "' has no closing '};'");
  return block;
}

}  // namespace sao::codegen
