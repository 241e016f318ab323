#include "gltf_checks.h"

#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

#include "file_checks.h"
#include "gltf_accessors.h"

namespace sao::scenes::detail {

namespace {

std::uint32_t le32(const std::string& b, std::size_t at) {
  return std::uint32_t(std::uint8_t(b[at])) | std::uint32_t(std::uint8_t(b[at + 1])) << 8 |
         std::uint32_t(std::uint8_t(b[at + 2])) << 16 | std::uint32_t(std::uint8_t(b[at + 3])) << 24;
}

constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942u;   // "BIN\0"

// The media types of a buffer's data URI (glTF 2.0); such strings are kept whole when parsing.
bool isBufferDataUri(const std::string& s) {
  return s.rfind("data:application/octet-stream", 0) == 0 || s.rfind("data:application/gltf-buffer", 0) == 0;
}

// Base64 to bytes; false for a character outside the alphabet or a length that is no multiple of 4.
bool decodeBase64(std::string_view text, std::string& out) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : c == '/' ? 63 : -1;
  };
  if (text.size() % 4 != 0) return false;
  out.clear();
  out.reserve(text.size() / 4 * 3);
  for (std::size_t i = 0; i < text.size(); i += 4) {
    int v[4];
    int n = 4;
    for (int k = 0; k < 4; ++k) {
      const char c = text[i + std::size_t(k)];
      if (c == '=' && i + 4 == text.size() && k >= 2) {
        v[k] = 0;
        n = std::min(n, k);
        continue;
      }
      if (n < 4 || (v[k] = value(c)) < 0) return false;  // a character after '=', or not base64
    }
    const std::uint32_t bits =
        std::uint32_t(v[0]) << 18 | std::uint32_t(v[1]) << 12 | std::uint32_t(v[2]) << 6 | std::uint32_t(v[3]);
    out.push_back(char(bits >> 16));
    if (n > 2) out.push_back(char(bits >> 8 & 0xFF));
    if (n > 3) out.push_back(char(bits & 0xFF));
  }
  return true;
}

// A buffer's data URI: one of glTF 2.0's two media types, base64, and exactly byteLength bytes.
// assimp 5.2 decodes it and throws on a length other than byteLength without freeing what it
// decoded (found by fuzzing: a media type of "~application/octet-stream" and a two-byte UTF-8
// character in the base64 text, then a leak).
Status checkBufferDataUri(const nlohmann::json& buffer, const std::string& uri, std::size_t index,
                          std::string_view name) {
  const std::string where = "glTF: buffers[" + std::to_string(index) + "].uri: ";
  const std::size_t comma = uri.find(',');
  const std::string header = uri.substr(0, std::min(comma, uri.size()));
  if (!isBufferDataUri(uri) || comma == std::string::npos)
    return fileError(StatusCode::IoError, name,
                     where + "a data URI '" + header.substr(0, 64) +
                         "' is not of glTF 2.0's buffer media types (application/octet-stream, application/gltf-buffer)");
  if (header.size() < 7 || header.compare(header.size() - 7, 7, ";base64") != 0)
    return fileError(StatusCode::IoError, name, where + "the data URI is not base64 (its header does not end in ;base64)");
  std::string bytes;
  if (!decodeBase64(std::string_view(uri).substr(comma + 1), bytes))
    return fileError(StatusCode::IoError, name,
                     where + "the data is not valid base64 (a character outside the alphabet, misplaced '=', or a "
                             "length that is no multiple of 4)");
  const auto length = buffer.find("byteLength");
  if (length != buffer.end() && length->is_number() && length->get<double>() != double(bytes.size()))
    return fileError(StatusCode::IoError, name,
                     where + "the data holds " + std::to_string(bytes.size()) + " bytes, but byteLength is " +
                         length->dump());
  return Status::success();
}

// A glTF 2.0 asset: asset.version "2.x". glTF 1.0 files have "1.0", the number 1, or no asset.
Status checkVersion(const nlohmann::json& doc, std::string_view name) {
  const auto asset = doc.find("asset");
  const std::string notSupported = "glTF 1.0 is not supported (glTF 2.0 only): ";
  if (asset == doc.end())
    return fileError(StatusCode::IoError, name, notSupported + "there is no \"asset\", which glTF 2.0 requires");
  if (!asset->is_object()) return Status::success();  // a wrong type: assimp names it
  const auto version = asset->find("version");
  if (version == asset->end())
    return fileError(StatusCode::IoError, name,
                     notSupported + "\"asset\" has no \"version\", which glTF 2.0 requires");
  if (version->is_number())
    return fileError(StatusCode::IoError, name,
                     notSupported + "asset.version is the number " + version->dump() +
                         " (glTF 1.0 allowed a number; glTF 2.0 writes the string \"2.0\")");
  if (!version->is_string()) return Status::success();  // assimp names the wrong type
  const std::string& v = version->get_ref<const std::string&>();
  const std::string major = v.substr(0, v.find('.'));
  if (major == "1" || major == "0")
    return fileError(StatusCode::IoError, name, notSupported + "asset.version is \"" + v + "\"");
  if (major != "2")
    return fileError(StatusCode::IoError, name,
                     "glTF: asset.version \"" + v.substr(0, 40) + "\" is not supported (glTF 2.0 only)");
  return Status::success();
}

// The bytes of buffer `index`: a .glb's BIN chunk, a base64 data URI (only the groups of 4
// characters that hold the bytes asked for are decoded), or a regular file next to the glTF file.
class BufferReader {
 public:
  BufferReader(const nlohmann::json& doc, const GltfBuffers& sources) : doc_(doc), sources_(sources) {}

  bool operator()(std::size_t index, std::uint64_t offset, std::size_t count, std::string& out) {
    const auto buffers = doc_.find("buffers");
    if (buffers == doc_.end() || !buffers->is_array() || index >= buffers->size()) return false;
    const nlohmann::json& buffer = (*buffers)[index];
    const auto uri = buffer.is_object() ? buffer.find("uri") : buffer.end();
    if (!buffer.is_object() || uri == buffer.end()) {
      return index == 0 && sources_.binChunk && sources_.binChunk(offset, count, out);
    }
    if (!uri->is_string()) return false;
    const std::string& u = uri->get_ref<const std::string&>();
    if (u.rfind("data:", 0) == 0) {
      const std::size_t comma = u.find(',');
      if (!isBufferDataUri(u) || comma == std::string::npos || u.compare(comma - 7, 7, ";base64") != 0) return false;
      const std::string_view data = std::string_view(u).substr(comma + 1);
      // Bytes [offset, offset + count) lie in the groups of 4 characters from offset / 3 on.
      if (offset / 3 >= data.size() / 4 || count > data.size()) return false;
      const std::uint64_t firstGroup = offset / 3, endGroup = (offset + count + 2) / 3;
      if (endGroup > data.size() / 4) return false;
      std::string bytes;
      if (!decodeBase64(data.substr(std::size_t(firstGroup * 4), std::size_t((endGroup - firstGroup) * 4)), bytes))
        return false;
      const std::uint64_t skip = offset - firstGroup * 3;
      if (bytes.size() < skip + count) return false;
      out.assign(bytes, std::size_t(skip), count);
      return true;
    }
    if (!sources_.folder || u.find("://") != std::string::npos) return false;
    const std::filesystem::path given(u);
    const std::filesystem::path file = given.is_absolute() ? given : *sources_.folder / given;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) return false;  // assimp reports a missing one
    std::ifstream in(file, std::ios::binary);
    out.assign(count, '\0');
    in.seekg(std::streamoff(offset));
    in.read(out.data(), std::streamsize(count));
    return in && in.gcount() == std::streamsize(count);
  }

 private:
  const nlohmann::json& doc_;
  const GltfBuffers& sources_;
};

}  // namespace

Status checkGltfJson(std::string_view text, std::string_view name, const GltfBuffers& buffers) {
  using nlohmann::json;
  json doc;
  try {
    // A SAX pass first: nothing is built for text that is not JSON.
    if (!json::accept(text)) {
      const auto parsed = json::parse(text);  // only to get the position of the error
      (void)parsed;
      return fileError(StatusCode::IoError, name, "not valid JSON");
    }
    // The document, with long strings (embedded images) cut to their first 1 KiB: only the start
    // of their data URI is looked at here. Buffers' data URIs stay whole: their indices are read.
    doc = json::parse(text, [](int, json::parse_event_t event, json& parsed) {
      if (event == json::parse_event_t::value && parsed.is_string() && parsed.get_ref<std::string&>().size() > 1024 &&
          !isBufferDataUri(parsed.get_ref<std::string&>()))
        parsed.get_ref<std::string&>().resize(1024);
      return true;
    });
  } catch (const json::parse_error& e) {
    return fileError(StatusCode::IoError, name, "not valid JSON (at byte " + std::to_string(e.byte) + ")");
  } catch (const std::exception& e) {
    return fileError(StatusCode::IoError, name, std::string("not valid JSON (") + e.what() + ")");
  }
  if (!doc.is_object()) return Status::success();  // assimp reports it
  if (Status s = checkVersion(doc, name); !s) return s;
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
      if (std::string_view(key) == "buffers")
        if (Status s = checkBufferDataUri(item, uri, i, name); !s) return s;
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
  BufferReader reader(doc, buffers);
  return checkGltfAccessors(doc, std::ref(reader), name);
}

Status checkGlb(std::uint64_t size, const ReadBytes& read, std::string_view name,
                const std::optional<std::filesystem::path>& folder) {
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
  // (A .gltf's mark is skipped before assimp reads it; a chunk inside a .glb cannot be.)
  if (std::string_view(json).starts_with(kUtf8ByteOrderMark))
    return error("the JSON chunk starts with a UTF-8 byte-order mark, which glTF 2.0 forbids there and assimp 5.2 "
                 "cannot read; write the chunk without it");
  const std::uint64_t next = 20 + jsonLength;
  GltfBuffers buffers{{}, folder};
  if (next + 8 <= size) {
    if (!read(next, 8, chunk)) return error("truncated chunk header");
    const std::uint64_t binLength = le32(chunk, 0);
    if (le32(chunk, 4) == kBinChunk && binLength > size - next - 8)
      return error("the BIN chunk declares " + std::to_string(binLength) + " bytes, " +
                   std::to_string(size - next - 8) + " follow");
    if (le32(chunk, 4) == kBinChunk)
      buffers.binChunk = [&read, start = next + 8, binLength](std::uint64_t offset, std::size_t count,
                                                              std::string& out) {
        return offset <= binLength && count <= binLength - offset && read(start + offset, count, out);
      };
  }
  return checkGltfJson(json, name, buffers);
}

}  // namespace sao::scenes::detail
