// glTF buffer views and accessors: their layout first (strides, bounds), then the index values of
// the triangle primitives, read in chunks from the buffers.
#include "gltf_accessors.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "file_checks.h"

namespace sao::scenes::detail {

namespace {

using nlohmann::json;

// A non-negative whole number, or nullopt for another type (assimp names members of a wrong type).
std::optional<std::uint64_t> wholeNumber(const json& value) {
  if (value.is_number_unsigned()) return value.get<std::uint64_t>();
  if (value.is_number_integer()) {
    const std::int64_t v = value.get<std::int64_t>();
    return v >= 0 ? std::optional<std::uint64_t>(std::uint64_t(v)) : std::nullopt;
  }
  if (value.is_number_float()) {
    const double v = value.get<double>();
    if (v >= 0 && v < 0x1p63 && v == std::floor(v)) return std::uint64_t(v);
  }
  return std::nullopt;
}

// A member that is a non-negative whole number; `absent` when it is missing, nullopt for a wrong type.
std::optional<std::uint64_t> member(const json& object, const char* key, std::optional<std::uint64_t> absent = {}) {
  const auto it = object.find(key);
  return it == object.end() ? absent : wholeNumber(*it);
}

// Item i of a top-level array, or null when there is none (assimp reports a bad reference).
const json* item(const json& doc, const char* array, std::optional<std::uint64_t> i) {
  const auto it = doc.find(array);
  if (!i || it == doc.end() || !it->is_array() || *i >= it->size() || !(*it)[std::size_t(*i)].is_object())
    return nullptr;
  return &(*it)[std::size_t(*i)];
}

std::uint64_t componentSize(std::uint64_t componentType) {
  switch (componentType) {
    case 5120: case 5121: return 1;  // (UNSIGNED_)BYTE
    case 5122: case 5123: return 2;  // (UNSIGNED_)SHORT
    case 5125: case 5126: return 4;  // UNSIGNED_INT, FLOAT
    default: return 0;
  }
}

// The size of one element; 0 for an unknown type. Matrix columns start on 4-byte boundaries.
std::uint64_t elementSize(const json& accessor) {
  const std::uint64_t c = componentSize(member(accessor, "componentType").value_or(0));
  const auto type = accessor.find("type");
  if (c == 0 || type == accessor.end() || !type->is_string()) return 0;
  const std::string& t = type->get_ref<const std::string&>();
  if (t == "SCALAR") return c;
  if (t == "VEC2") return 2 * c;
  if (t == "VEC3") return 3 * c;
  if (t == "VEC4") return 4 * c;
  const std::uint64_t n = t == "MAT2" ? 2 : t == "MAT3" ? 3 : t == "MAT4" ? 4 : 0;
  return n * ((n * c + 3) / 4 * 4);
}

std::string describe(const json& accessor) {
  const auto type = accessor.find("type");
  return (type != accessor.end() && type->is_string() ? type->get<std::string>() : std::string("?")) +
         " of componentType " + std::to_string(member(accessor, "componentType").value_or(0));
}

// Where an accessor's elements are: the first one's byte in its buffer, and the stride.
struct Layout {
  std::uint64_t buffer = 0, first = 0, stride = 0, count = 0, element = 0;
};

// Checks accessor `a`'s layout; sets `layout` when the accessor has its data in a buffer view and
// its members have the right types (otherwise assimp reports them).
Status checkLayout(const json& doc, std::size_t a, std::string_view name, std::optional<Layout>& layout) {
  layout.reset();
  const json& accessor = *item(doc, "accessors", a);
  const json* view = item(doc, "bufferViews", member(accessor, "bufferView"));
  const std::uint64_t element = elementSize(accessor);
  const auto count = member(accessor, "count");
  const auto offset = member(accessor, "byteOffset", 0);
  if (view == nullptr || element == 0 || !count || *count == 0 || !offset) return Status::success();
  const auto viewLength = member(*view, "byteLength");
  const auto viewOffset = member(*view, "byteOffset", 0);
  const auto bufferIndex = member(*view, "buffer");
  if (!viewLength || !viewOffset || !bufferIndex) return Status::success();
  const std::string v = std::to_string(*member(accessor, "bufferView"));
  const std::string which = "glTF: accessor " + std::to_string(a) + " (" + describe(accessor) + ", " +
                            std::to_string(element) + " bytes an element)";
  std::uint64_t stride = element;
  if (const auto s = view->find("byteStride"); s != view->end()) {
    if (!s->is_number()) return Status::success();
    const double given = s->get<double>();
    const auto whole = wholeNumber(*s);
    char shown[32];
    std::snprintf(shown, sizeof shown, "%.17g", given);
    if (!whole || *whole < 4 || *whole > 252 || *whole % 4 != 0)
      return fileError(StatusCode::IoError, name,
                       which + ": its bufferView " + v + " has byteStride " + shown +
                           "; glTF 2.0 requires a multiple of 4 from 4 to 252");
    if (*whole < element)
      return fileError(StatusCode::IoError, name,
                       which + ": the byteStride " + shown + " of its bufferView " + v +
                           " is smaller than an element, so elements would overlap");
    stride = *whole;
  }
  // The last element's end, in 128 bits: count and stride come from the file.
  const unsigned __int128 end = (unsigned __int128)*offset + (unsigned __int128)stride * (*count - 1) + element;
  if (end > *viewLength)
    return fileError(StatusCode::IoError, name,
                     which + ": " + std::to_string(*count) + " elements from byteOffset " + std::to_string(*offset) +
                         " with a stride of " + std::to_string(stride) + " run past the byteLength " +
                         std::to_string(*viewLength) + " of its bufferView " + v);
  const json* buffer = item(doc, "buffers", bufferIndex);
  const auto bufferLength = buffer ? member(*buffer, "byteLength") : std::nullopt;
  if (!bufferLength) return Status::success();
  if ((unsigned __int128)*viewOffset + *viewLength > *bufferLength)
    return fileError(StatusCode::IoError, name,
                     "glTF: bufferView " + v + " (byteOffset " + std::to_string(*viewOffset) + ", byteLength " +
                         std::to_string(*viewLength) + ") runs past the byteLength " + std::to_string(*bufferLength) +
                         " of buffer " + std::to_string(*bufferIndex));
  layout = Layout{*bufferIndex, *viewOffset + *offset, stride, *count, element};
  return Status::success();
}

// The index values of a triangle primitive, each below its vertex count.
Status checkIndices(const json& doc, std::size_t m, std::size_t p, const std::optional<Layout>& layout,
                    std::uint64_t indexAccessor, std::uint64_t vertices, std::uint64_t positionAccessor,
                    const ReadBuffer& read, std::string_view name) {
  const std::string which = "glTF: mesh " + std::to_string(m) + " primitive " + std::to_string(p);
  const json& accessor = *item(doc, "accessors", indexAccessor);
  const auto componentType = member(accessor, "componentType");
  const auto type = accessor.find("type");
  if (!componentType || type == accessor.end() || !type->is_string()) return Status::success();  // assimp's
  if ((*componentType != 5121 && *componentType != 5123 && *componentType != 5125) || *type != "SCALAR")
    return fileError(StatusCode::IoError, name,
                     which + ": its indices, accessor " + std::to_string(indexAccessor) + ", are " +
                         describe(accessor) + "; indices must be SCALAR of an unsigned integer type (5121, 5123 or 5125)");
  if (!layout || accessor.contains("sparse") || !read) return Status::success();
  const std::uint64_t size = componentSize(*componentType);
  constexpr std::uint64_t kChunk = 1 << 16;  // elements read at a time
  std::string bytes;
  for (std::uint64_t k0 = 0; k0 < layout->count; k0 += kChunk) {
    const std::uint64_t n = std::min(kChunk, layout->count - k0);
    if (!read(std::size_t(layout->buffer), layout->first + k0 * layout->stride,
              std::size_t((n - 1) * layout->stride + size), bytes))
      return Status::success();  // the data is not at hand; assimp reports it
    for (std::uint64_t k = 0; k < n; ++k) {
      const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + k * layout->stride);
      std::uint64_t index = 0;
      for (std::uint64_t i = 0; i < size; ++i) index |= std::uint64_t(b[i]) << (8 * i);  // little-endian
      if (index >= vertices)
        return fileError(StatusCode::IoError, name,
                         which + ": index " + std::to_string(index) + " (element " + std::to_string(k0 + k) +
                             " of accessor " + std::to_string(indexAccessor) + ") is out of range: its POSITION, " +
                             "accessor " + std::to_string(positionAccessor) + ", has " + std::to_string(vertices) +
                             " vertices");
    }
  }
  return Status::success();
}

}  // namespace

Status checkGltfAccessors(const json& doc, const ReadBuffer& read, std::string_view name) {
  const auto accessors = doc.find("accessors");
  const auto meshes = doc.find("meshes");
  if (accessors == doc.end() || !accessors->is_array() || meshes == doc.end() || !meshes->is_array())
    return Status::success();
  // The accessors assimp reads for the meshes: every primitive's attributes and indices. (Others,
  // of animations or skins, are not used; a broken one there changes no geometry.)
  std::vector<bool> used(accessors->size());
  for (const json& mesh : *meshes) {
    const auto primitives = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (!mesh.is_object() || primitives == mesh.end() || !primitives->is_array()) continue;
    for (const json& primitive : *primitives) {
      if (!primitive.is_object()) continue;
      if (const auto i = member(primitive, "indices"); i && *i < used.size()) used[std::size_t(*i)] = true;
      const auto attributes = primitive.find("attributes");
      if (attributes == primitive.end() || !attributes->is_object()) continue;
      for (const json& a : *attributes)
        if (const auto i = wholeNumber(a); i && *i < used.size()) used[std::size_t(*i)] = true;
    }
  }
  std::vector<std::optional<Layout>> layouts(accessors->size());
  for (std::size_t a = 0; a < accessors->size(); ++a)
    if (used[a] && (*accessors)[a].is_object())
      if (Status s = checkLayout(doc, a, name, layouts[a]); !s) return s;

  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const json& mesh = (*meshes)[m];
    const auto primitives = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (!mesh.is_object() || primitives == mesh.end() || !primitives->is_array()) continue;
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      if (!primitive.is_object()) continue;
      const auto mode = member(primitive, "mode", 4);
      if (!mode || *mode < 4 || *mode > 6) continue;  // only triangles are used; points and lines are dropped
      const auto indices = member(primitive, "indices");
      const auto attributes = primitive.find("attributes");
      if (!indices || attributes == primitive.end() || !attributes->is_object()) continue;
      const auto position = member(*attributes, "POSITION");
      const json* positions = item(doc, "accessors", position);
      const auto vertices = positions ? member(*positions, "count") : std::nullopt;
      if (!vertices || !item(doc, "accessors", indices)) continue;
      const std::optional<Layout>& layout = layouts[std::size_t(*indices)];
      if (Status s = checkIndices(doc, m, p, layout, *indices, *vertices, *position, read, name); !s) return s;
    }
  }
  return Status::success();
}

}  // namespace sao::scenes::detail
