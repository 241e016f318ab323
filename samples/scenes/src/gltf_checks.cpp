#include "gltf_checks.h"

#include <cstring>

#include <nlohmann/json.hpp>

#include "file_checks.h"

namespace sao::scenes::detail {

namespace {

std::uint32_t le32(const std::string& b, std::size_t at) {
  return std::uint32_t(std::uint8_t(b[at])) | std::uint32_t(std::uint8_t(b[at + 1])) << 8 |
         std::uint32_t(std::uint8_t(b[at + 2])) << 16 | std::uint32_t(std::uint8_t(b[at + 3])) << 24;
}

constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942u;   // "BIN\0"

}  // namespace

Status checkGltfJson(std::string_view text, std::string_view name) {
  using nlohmann::json;
  json doc;
  try {
    // A SAX pass first: nothing is built for text that is not JSON.
    if (!json::accept(text)) {
      const auto parsed = json::parse(text);  // only to get the position of the error
      (void)parsed;
      return fileError(StatusCode::IoError, name, "not valid JSON");
    }
    // The document, with long strings (embedded base64 data) cut to their first 1 KiB: only the
    // start of a data URI is looked at here.
    doc = json::parse(text, [](int, json::parse_event_t event, json& parsed) {
      if (event == json::parse_event_t::value && parsed.is_string() && parsed.get_ref<std::string&>().size() > 1024)
        parsed.get_ref<std::string&>().resize(1024);
      return true;
    });
  } catch (const json::parse_error& e) {
    return fileError(StatusCode::IoError, name, "not valid JSON (at byte " + std::to_string(e.byte) + ")");
  } catch (const std::exception& e) {
    return fileError(StatusCode::IoError, name, std::string("not valid JSON (") + e.what() + ")");
  }
  if (!doc.is_object()) return Status::success();  // assimp reports it
  auto arrayMember = [&](const char* key) -> const json* {
    const auto it = doc.find(key);
    return it != doc.end() && it->is_array() ? &*it : nullptr;
  };
  // A data URI's header (up to its comma) must be shorter than 127 characters: assimp 5.2 keeps
  // offsets into it in a signed char and reads outside the string beyond that (found by fuzzing:
  // a long media type, then a leak).
  for (const char* key : {"buffers", "images"}) {
    const json* list = arrayMember(key);
    for (std::size_t i = 0; list && i < list->size(); ++i) {
      const json& item = (*list)[i];
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string& uri = item["uri"].get_ref<const std::string&>();
      if (uri.rfind("data:", 0) != 0) continue;
      const std::size_t comma = uri.find(',');
      if (comma != std::string::npos && comma > 126)
        return fileError(StatusCode::IoError, name,
                         "glTF: " + std::string(key) + "[" + std::to_string(i) + "].uri: the data URI's header (before " +
                             "its comma) is " + std::to_string(comma) + " characters long, more than 126");
    }
  }
  // Every mesh primitive has positions, and none is a line loop: assimp 5.2 closes a line loop
  // with the first segment it kept, a null pointer when it dropped that one (an index out of
  // range, or no positions at all; found by fuzzing, twice). Lines are not used anyway. Members of
  // the wrong type are left to assimp, which reports them.
  const json* meshes = arrayMember("meshes");
  for (std::size_t m = 0; meshes && m < meshes->size(); ++m) {
    const json& mesh = (*meshes)[m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    const json& primitives = mesh["primitives"];
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const json& primitive = primitives[p];
      if (!primitive.is_object()) continue;
      const bool hasPositions = primitive.contains("attributes") && primitive["attributes"].is_object() &&
                                primitive["attributes"].contains("POSITION");
      const std::string which = "glTF: mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      if (!hasPositions) return fileError(StatusCode::IoError, name, which + " has no POSITION attribute");
      if (primitive.contains("mode") && primitive["mode"].is_number() && primitive["mode"].get<double>() == 2.0)
        return fileError(StatusCode::IoError, name,
                         which + " is a line loop (mode 2), which assimp 5.2 does not read safely; only "
                                 "triangles are used");
    }
  }
  return Status::success();
}

Status checkGlb(std::uint64_t size, const ReadBytes& read, std::string_view name) {
  std::string head;
  if (size < 12 || !read(0, 12, head) || head.compare(0, 4, "glTF") != 0) return Status::success();
  const std::uint32_t version = le32(head, 4), length = le32(head, 8);
  auto error = [&](const std::string& problem) { return fileError(StatusCode::IoError, name, "binary glTF: " + problem); };
  if (version != 2) return error("version " + std::to_string(version) + " is not supported (glTF 2.0 only)");
  if (length > size)
    return error("the header declares " + std::to_string(length) + " bytes, the file has " + std::to_string(size));
  std::string chunk;
  if (size < 20 || !read(12, 8, chunk)) return error("no JSON chunk");
  const std::uint64_t jsonLength = le32(chunk, 0);
  if (le32(chunk, 4) != kJsonChunk) return error("the first chunk is not JSON");
  if (jsonLength > size - 20)
    return error("the JSON chunk declares " + std::to_string(jsonLength) + " bytes, " + std::to_string(size - 20) +
                 " follow");
  std::string json;
  if (!read(20, std::size_t(jsonLength), json)) return error("truncated JSON chunk");
  if (Status s = checkGltfJson(json, name); !s) return s;
  const std::uint64_t next = 20 + jsonLength;
  if (next + 8 <= size) {
    if (!read(next, 8, chunk)) return error("truncated chunk header");
    const std::uint64_t binLength = le32(chunk, 0);
    if (le32(chunk, 4) == kBinChunk && binLength > size - next - 8)
      return error("the BIN chunk declares " + std::to_string(binLength) + " bytes, " +
                   std::to_string(size - next - 8) + " follow");
  }
  return Status::success();
}

}  // namespace sao::scenes::detail
