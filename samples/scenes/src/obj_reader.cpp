// The OBJ reader: logical lines (with backslash continuation), then `v` and `f` statements.
#include "obj_reader.h"

#include <charconv>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "file_checks.h"
#include "float_conversion.h"
#include "sao/scenes/mesh_file.h"

namespace sao::scenes::detail {

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isBlank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !isBlank(line[i])) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

// A word for a message: printable, at most 40 characters.
std::string shown(std::string_view word) {
  std::string s = "'";
  for (char c : word.substr(0, 40)) s += (c >= 32 && c < 127) ? c : '?';
  return s + (word.size() > 40 ? "...'" : "'");
}

// A face that refers to a vertex not read yet (OBJ allows it): checked at the end.
struct ForwardReference {
  int line;
  std::int64_t index;  // 0-based
};

// Text that is not ASCII-compatible (UTF-16 or UTF-32, as Windows editors save "Unicode"): every
// other byte is NUL, so no statement parses and the file read as empty ("has no triangles").
// Known by its byte-order mark, or without one by its first character: ASCII beside NUL bytes.
std::optional<std::string> notAsciiCompatible(std::string_view text) {
  using namespace std::string_view_literals;
  const auto starts = [&](std::string_view prefix) { return text.starts_with(prefix); };
  const auto ascii = [&](std::size_t i) { return i < text.size() && text[i] >= 9 && text[i] < 127; };
  const auto nul = [&](std::size_t i) { return i < text.size() && text[i] == '\0'; };
  if (starts("\xFF\xFE\0\0"sv) || starts("\0\0\xFE\xFF"sv)) return "UTF-32 text (it starts with a UTF-32 byte-order mark)";
  if (starts("\xFF\xFE"sv) || starts("\xFE\xFF"sv)) return "UTF-16 text (it starts with a UTF-16 byte-order mark)";
  if ((ascii(0) && nul(1) && nul(2) && nul(3)) || (nul(0) && nul(1) && nul(2) && ascii(3)))
    return "UTF-32 text (its first character is four bytes, three of them NUL)";
  if ((ascii(0) && nul(1)) || (nul(0) && ascii(1))) return "UTF-16 text (its first character is two bytes, one NUL)";
  return std::nullopt;
}

}  // namespace

Status readObj(std::string_view text, std::string_view name, Mesh& out) {
  if (const auto encoding = notAsciiCompatible(text))
    return fileError(StatusCode::InvalidInput, name, "is " + *encoding + ": save it as UTF-8 or ASCII text");
  Mesh mesh;
  std::vector<ForwardReference> forward;
  std::vector<std::uint32_t> polygon;
  std::string joined;  // a logical line made of continued physical lines
  int lineNumber = 0;
  // A UTF-8 byte-order mark (Windows editors write one) is skipped: glued to the first word, it
  // made the first statement unknown and so ignored, a lost first vertex and every index shifted.
  std::size_t pos = text.starts_with(kUtf8ByteOrderMark) ? kUtf8ByteOrderMark.size() : 0;
  while (pos < text.size()) {
    // One logical line: physical lines ending in a backslash continue on the next.
    const int firstLine = lineNumber + 1;
    std::string_view line;
    joined.clear();
    bool continued = false;
    while (pos < text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      std::string_view physical = text.substr(pos, end - pos);
      pos = end + 1;
      ++lineNumber;
      while (!physical.empty() && isBlank(physical.back())) physical.remove_suffix(1);
      if (!physical.empty() && physical.back() == '\\') {
        physical.remove_suffix(1);
        joined.append(physical).push_back(' ');
        continued = true;
        continue;
      }
      if (continued) {
        joined.append(physical);
        line = joined;
      } else {
        line = physical;
      }
      break;
    }
    if (continued) line = joined;  // (also when the file ends in a backslash)
    auto error = [&](const std::string& problem) {
      return fileError(StatusCode::IoError, name, "OBJ line " + std::to_string(firstLine) + ": " + problem);
    };
    const auto w = words(line);
    if (w.empty()) continue;
    if (w[0] == "v") {
      if (w.size() < 4) return error("a vertex needs 3 coordinates, got " + std::to_string(w.size() - 1));
      double xyz[3];
      for (int k = 0; k < 3; ++k) {
        if (!parseNumber(w[std::size_t(k) + 1], xyz[k])) return error(shown(w[std::size_t(k) + 1]) + " is not a number");
      }
      if (mesh.positions.size() == std::numeric_limits<std::uint32_t>::max())
        return fileError(StatusCode::InvalidInput, name, "has more than 2^32 - 1 vertices");
      mesh.positions.emplace_back(toFloat(xyz[0]), toFloat(xyz[1]), toFloat(xyz[2]));
    } else if (w[0] == "f") {
      polygon.clear();
      for (std::size_t k = 1; k < w.size(); ++k) {
        const std::string_view ref = w[k].substr(0, w[k].find('/'));
        std::int64_t i = 0;
        const auto [p, ec] = std::from_chars(ref.data(), ref.data() + ref.size(), i);
        if (ec != std::errc() || p != ref.data() + ref.size() || i == 0)
          return error(shown(w[k]) + " is not a vertex reference (1, 2, ... or -1, -2, ...)");
        const std::int64_t count = std::int64_t(mesh.positions.size());
        const std::int64_t index = i > 0 ? i - 1 : count + i;
        if (index < 0)
          return fileError(StatusCode::InvalidInput, name,
                           "OBJ line " + std::to_string(firstLine) + ": vertex " + std::to_string(i) + " is before the first of the " +
                               std::to_string(count) + " vertices so far");
        if (index > std::int64_t(std::numeric_limits<std::uint32_t>::max()))
          return fileError(StatusCode::InvalidInput, name,
                           "OBJ line " + std::to_string(firstLine) + ": vertex " + std::to_string(i) + " is beyond 2^32 - 1");
        if (index >= count) forward.push_back({firstLine, index});
        polygon.push_back(std::uint32_t(index));
      }
      if (polygon.size() < 3) continue;  // a point or a line
      if (mesh.triangleCount() + polygon.size() - 2 > kMaxMeshTriangles)
        return fileError(StatusCode::InvalidInput, name,
                         "has more than the limit of " + std::to_string(kMaxMeshTriangles) + " triangles");
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
        mesh.indices.insert(mesh.indices.end(), {polygon[0], polygon[k], polygon[k + 1]});
    }
    // Every other statement (vt, vn, vp, g, o, s, usemtl, mtllib, l, p, #, ...) carries no geometry.
  }
  for (const ForwardReference& f : forward)
    if (f.index >= std::int64_t(mesh.positions.size()))
      return fileError(StatusCode::InvalidInput, name,
                       "OBJ line " + std::to_string(f.line) + ": a face refers to vertex " + std::to_string(f.index + 1) +
                           ", but there are only " + std::to_string(mesh.positions.size()) + " vertices");
  out = std::move(mesh);
  return Status::success();
}

}  // namespace sao::scenes::detail
