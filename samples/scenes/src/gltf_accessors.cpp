// glTF buffer views and accessors, on the JSON: strides and bounds, index types, views within
// their buffers.
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

// A non-negative whole number, or nullopt for another type (checkGltfTypes named those).
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

// Item i of a top-level array, or null when there is none (tinygltf or gltf_mesh.cpp reports it).
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

// Checks accessor `a`'s layout when it has its data in a buffer view.
Status checkLayout(const json& doc, std::size_t a, std::string_view name) {
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
    if (!s->is_number())
      return fileError(StatusCode::IoError, name,
                       which + ": its bufferView " + v + " has a byteStride that is not a number; glTF 2.0 requires "
                               "a multiple of 4 from 4 to 252");
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
  return Status::success();
}

// The type of a triangle primitive's indices: SCALAR of an unsigned integer type.
Status checkIndexType(const json& doc, std::size_t m, std::size_t p, std::uint64_t indexAccessor, std::string_view name) {
  const json& accessor = *item(doc, "accessors", indexAccessor);
  const auto componentType = member(accessor, "componentType");
  const auto type = accessor.find("type");
  if (!componentType || type == accessor.end()) return Status::success();  // tinygltf refuses them
  if ((*componentType != 5121 && *componentType != 5123 && *componentType != 5125) || *type != "SCALAR")
    return fileError(StatusCode::IoError, name,
                     "glTF: mesh " + std::to_string(m) + " primitive " + std::to_string(p) + ": its indices, accessor " +
                         std::to_string(indexAccessor) + ", are " + describe(accessor) +
                         "; indices must be SCALAR of an unsigned integer type (5121, 5123 or 5125)");
  return Status::success();
}

// The buffer view of every image in a buffer view lies within its buffer: tinygltf takes the
// address of its first byte (a view of a mesh accessor is checked by checkLayout; other views are
// not read, and a file whose unused views run past their buffer still loads).
Status checkImageViews(const json& doc, std::string_view name) {
  const auto images = doc.find("images");
  for (std::size_t i = 0; images != doc.end() && i < images->size(); ++i) {
    const auto v = member((*images)[i], "bufferView");
    const json* view = item(doc, "bufferViews", v);
    if (view == nullptr) continue;  // none, or one that does not exist: tinygltf refuses the latter
    const auto length = member(*view, "byteLength"), offset = member(*view, "byteOffset", 0), b = member(*view, "buffer");
    const json* buffer = item(doc, "buffers", b);
    const auto bufferLength = buffer ? member(*buffer, "byteLength") : std::nullopt;
    if (!length || !bufferLength || (unsigned __int128)*offset + *length > *bufferLength)
      return fileError(StatusCode::IoError, name,
                       "glTF: images[" + std::to_string(i) + "]: its bufferView " + std::to_string(*v) +
                           " is not within a buffer");
  }
  return Status::success();
}

}  // namespace

Status checkGltfAccessors(const json& doc, std::string_view name) {
  const auto accessors = doc.find("accessors");
  const auto meshes = doc.find("meshes");
  if (accessors == doc.end() || meshes == doc.end()) return checkImageViews(doc, name);
  // The accessors of the meshes: every primitive's attributes and indices. (Others, of animations
  // or skins, are not used; a broken one there changes no geometry.)
  std::vector<bool> used(accessors->size());
  for (const json& mesh : *meshes) {
    const auto primitives = mesh.find("primitives");
    if (primitives == mesh.end()) continue;
    for (const json& primitive : *primitives) {
      if (const auto i = member(primitive, "indices"); i && *i < used.size()) used[std::size_t(*i)] = true;
      for (const json& a : primitive.at("attributes"))  // checkGltfJson made sure there is one
        if (const auto i = wholeNumber(a); i && *i < used.size()) used[std::size_t(*i)] = true;
    }
  }
  for (std::size_t a = 0; a < accessors->size(); ++a)
    if (used[a])
      if (Status s = checkLayout(doc, a, name); !s) return s;

  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const json& mesh = (*meshes)[m];
    const auto primitives = mesh.find("primitives");
    for (std::size_t p = 0; primitives != mesh.end() && p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      const auto mode = member(primitive, "mode", 4);
      if (*mode < 4) continue;  // only triangles are used; points and lines are dropped
      const auto indices = member(primitive, "indices");
      if (indices && item(doc, "accessors", indices))
        if (Status s = checkIndexType(doc, m, p, *indices, name); !s) return s;
    }
  }
  return checkImageViews(doc, name);
}

}  // namespace sao::scenes::detail
