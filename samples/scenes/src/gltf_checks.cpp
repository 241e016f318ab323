#include "gltf_checks.h"

#include <algorithm>
#include <map>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "file_checks.h"
#include "gltf_accessors.h"
#include "gltf_cameras.h"
#include "gltf_schema.h"

namespace sao::scenes::detail {

namespace {

using nlohmann::json;

std::uint32_t le32(std::string_view b, std::size_t at) {
  return std::uint32_t(std::uint8_t(b[at])) | std::uint32_t(std::uint8_t(b[at + 1])) << 8 |
         std::uint32_t(std::uint8_t(b[at + 2])) << 16 | std::uint32_t(std::uint8_t(b[at + 3])) << 24;
}

constexpr std::uint32_t kJsonChunk = 0x4E4F534Au;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942u;   // "BIN\0"
// JSON nested deeper than this is refused: tinygltf copies "extras" recursively.
constexpr int kMaxDepth = 64;

// The media types of a buffer's data URI (glTF 2.0); such strings are kept whole when parsing.
bool isBufferDataUri(const std::string& s) {
  return s.rfind("data:application/octet-stream", 0) == 0 || s.rfind("data:application/gltf-buffer", 0) == 0;
}

// The length of base64 text's data; nullopt for a character outside the alphabet, a misplaced
// '=' or a length that is no multiple of 4.
std::optional<std::size_t> base64Length(std::string_view text) {
  auto isDigit = [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '/';
  };
  if (text.size() % 4 != 0) return std::nullopt;
  std::size_t padding = 0;
  if (text.ends_with("==")) padding = 2;
  else if (text.ends_with("=")) padding = 1;
  if (!std::all_of(text.begin(), text.end() - std::ptrdiff_t(padding), isDigit)) return std::nullopt;
  return text.size() / 4 * 3 - padding;
}

// A buffer's data URI: one of glTF 2.0's two media types without parameters, base64, and exactly
// byteLength bytes.
Status checkBufferDataUri(const json& buffer, const std::string& uri, std::size_t index, std::string_view name) {
  const std::string where = "glTF: buffers[" + std::to_string(index) + "].uri: ";
  const std::size_t comma = uri.find(',');
  const std::string header = uri.substr(0, std::min(comma, uri.size()));
  if (!isBufferDataUri(uri) || comma == std::string::npos)
    return fileError(StatusCode::IoError, name,
                     where + "a data URI '" + header.substr(0, 64) +
                         "' is not of glTF 2.0's buffer media types (application/octet-stream, application/gltf-buffer)");
  if (!header.ends_with(";base64"))
    return fileError(StatusCode::IoError, name, where + "the data URI is not base64 (its header does not end in ;base64)");
  // tinygltf decodes these two headers only, and takes any other for a file name.
  if (header != "data:application/octet-stream;base64" && header != "data:application/gltf-buffer;base64")
    return fileError(StatusCode::IoError, name,
                     where + "the data URI's header '" + header.substr(0, 64) + (header.size() > 64 ? "..." : "") +
                         "' has parameters; only 'data:application/octet-stream;base64' and "
                         "'data:application/gltf-buffer;base64' are read");
  const auto bytes = base64Length(std::string_view(uri).substr(comma + 1));
  if (!bytes)
    return fileError(StatusCode::IoError, name,
                     where + "the data is not valid base64 (a character outside the alphabet, misplaced '=', or a "
                             "length that is no multiple of 4)");
  const auto length = buffer.find("byteLength");
  if (length != buffer.end() && length->get<double>() != double(*bytes))
    return fileError(StatusCode::IoError, name,
                     where + "the data holds " + std::to_string(*bytes) + " bytes, but byteLength is " + length->dump());
  return Status::success();
}

// A URI's %XX escapes decoded (as tinygltf does before it opens the file).
std::string percentDecoded(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(std::uint8_t(uri[i + 1])) &&
        std::isxdigit(std::uint8_t(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// A buffer in another file: a regular file of byteLength bytes next to the glTF file.
Status checkBufferFile(const json& buffer, const std::string& uri, std::size_t index, std::string_view name,
                       const std::optional<std::filesystem::path>& folder) {
  const std::string file = percentDecoded(uri);
  const std::string where = "glTF: buffers[" + std::to_string(index) + "].uri: could not open the referenced file \"" +
                            file.substr(0, 200) + "\"";
  if (!folder) return fileError(StatusCode::IoError, name, where + " (no file is opened for data in memory)");
  if (uri.find("://") != std::string::npos || file.find('\0') != std::string::npos)
    return fileError(StatusCode::IoError, name, where + " (not a file name)");
  std::error_code ec;
  const std::filesystem::path path = *folder / file;
  const auto status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found)
    return fileError(StatusCode::IoError, name, where + " (no such file)");
  if (status.type() != std::filesystem::file_type::regular)
    return fileError(StatusCode::IoError, name, where + " (not a regular file)");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  const auto length = buffer.find("byteLength");
  if (!ec && length != buffer.end() && double(size) != length->get<double>())
    return fileError(StatusCode::IoError, name,
                     where + " (it has " + std::to_string(size) + " bytes, but byteLength is " + length->dump() + ")");
  return Status::success();
}

// A glTF 2.0 asset: asset.version "2.x". glTF 1.0 files have "1.0", the number 1, or no asset.
Status checkVersion(const json& doc, std::string_view name) {
  const auto asset = doc.find("asset");
  const std::string notSupported = "glTF 1.0 is not supported (glTF 2.0 only): ";
  if (asset == doc.end())
    return fileError(StatusCode::IoError, name, notSupported + "there is no \"asset\", which glTF 2.0 requires");
  if (!asset->is_object()) return Status::success();  // a wrong type: checkGltfTypes names it
  const auto version = asset->find("version");
  if (version == asset->end())
    return fileError(StatusCode::IoError, name,
                     notSupported + "\"asset\" has no \"version\", which glTF 2.0 requires");
  if (version->is_number())
    return fileError(StatusCode::IoError, name,
                     notSupported + "asset.version is the number " + version->dump() +
                         " (glTF 1.0 allowed a number; glTF 2.0 writes the string \"2.0\")");
  if (!version->is_string()) return Status::success();  // checkGltfTypes names the wrong type
  const std::string& v = version->get_ref<const std::string&>();
  const std::string major = v.substr(0, v.find('.'));
  if (major == "1" || major == "0")
    return fileError(StatusCode::IoError, name, notSupported + "asset.version is \"" + v + "\"");
  if (major != "2")
    return fileError(StatusCode::IoError, name,
                     "glTF: asset.version \"" + v.substr(0, 40) + "\" is not supported (glTF 2.0 only)");
  return Status::success();
}

// The URIs of buffers and images (the members have their types: checkGltfTypes).
Status checkUris(const json& doc, std::string_view name, const std::optional<std::filesystem::path>& folder) {
  for (const char* key : {"buffers", "images"}) {
    const auto list = doc.find(key);
    for (std::size_t i = 0; list != doc.end() && i < list->size(); ++i) {
      const json& item = (*list)[i];
      const auto uri = item.find("uri");
      if (uri == item.end()) continue;
      const std::string& text = uri->get_ref<const std::string&>();
      const bool buffer = std::string_view(key) == "buffers";
      if (text.rfind("data:", 0) != 0) {
        if (buffer)
          if (Status s = checkBufferFile(item, text, i, name, folder); !s) return s;
        continue;  // an image file: never opened
      }
      // A long header was read outside the string by assimp 5.2; still refused (no reader needs it).
      const std::size_t comma = text.find(',');
      if (comma != std::string::npos && comma > 126)
        return fileError(StatusCode::IoError, name,
                         "glTF: " + std::string(key) + "[" + std::to_string(i) + "].uri: the data URI's header (before " +
                             "its comma) is " + std::to_string(comma) + " characters long, more than 126");
      if (buffer)
        if (Status s = checkBufferDataUri(item, text, i, name); !s) return s;
    }
  }
  return Status::success();
}

// Every mesh primitive: positions, a mode that is read (line loops are refused rather than
// dropped: a mesh that is mostly lines is not what this reader is for), no Draco compression (not
// built in), and indexed attribute sets numbered from 0 without gaps (TEXCOORD_1 needs TEXCOORD_0).
Status checkPrimitives(const json& doc, std::string_view name) {
  const auto meshes = doc.find("meshes");
  for (std::size_t m = 0; meshes != doc.end() && m < meshes->size(); ++m) {
    const json& mesh = (*meshes)[m];
    const auto primitives = mesh.find("primitives");
    for (std::size_t p = 0; primitives != mesh.end() && p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      const std::string which = "glTF: mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      const auto attributes = primitive.find("attributes");
      if (attributes == primitive.end() || !attributes->contains("POSITION"))
        return fileError(StatusCode::IoError, name, which + " has no POSITION attribute");
      const double mode = primitive.value("mode", 4.0);
      if (mode == 2.0)
        return fileError(StatusCode::IoError, name, which + " is a line loop (mode 2); only triangles are read");
      if (mode > 6.0)
        return fileError(StatusCode::IoError, name,
                         which + " has mode " + primitive["mode"].dump() + "; glTF 2.0's modes are 0 to 6");
      const auto extensions = primitive.find("extensions");
      if (extensions != primitive.end() && extensions->contains("KHR_draco_mesh_compression"))
        return fileError(StatusCode::IoError, name,
                         which + " is Draco-compressed (KHR_draco_mesh_compression), which is not supported");
      std::map<std::string, std::set<unsigned long>> sets;
      for (const auto& [key, value] : attributes->items()) {
        const std::size_t underscore = key.rfind('_');
        const std::string semantic = key.substr(0, underscore);
        if (underscore == std::string::npos || (semantic != "TEXCOORD" && semantic != "COLOR" &&
                                                semantic != "JOINTS" && semantic != "WEIGHTS"))
          continue;
        const std::string number = key.substr(underscore + 1);
        if (number.empty() || number.size() > 9 || !std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; }))
          return fileError(StatusCode::IoError, name, which + ": attribute " + key + " is not SEMANTIC_n");
        sets[semantic].insert(std::stoul(number));
      }
      for (const auto& [semantic, numbers] : sets)
        if (*numbers.rbegin() + 1 != numbers.size())
          return fileError(StatusCode::IoError, name,
                           which + ": its " + semantic + "_n attributes are not numbered 0, 1, ... without gaps " +
                               "(there are " + std::to_string(numbers.size()) + ", the highest is " + semantic + "_" +
                               std::to_string(*numbers.rbegin()) + ")");
    }
  }
  return Status::success();
}

struct TooDeep {};

}  // namespace

Status checkGltfJson(std::string_view text, std::string_view name, const std::optional<std::filesystem::path>& folder) {
  json doc;
  try {
    // Long strings (embedded images) are cut to their first 1 KiB: only the start of their data
    // URI is looked at here. Buffers' data URIs stay whole: their base64 is checked.
    doc = json::parse(text, [](int depth, json::parse_event_t event, json& parsed) {
      if (depth > kMaxDepth) throw TooDeep{};
      if (event == json::parse_event_t::value && parsed.is_string() && parsed.get_ref<std::string&>().size() > 1024 &&
          !isBufferDataUri(parsed.get_ref<std::string&>()))
        parsed.get_ref<std::string&>().resize(1024);
      return true;
    });
  } catch (const TooDeep&) {
    return fileError(StatusCode::IoError, name, "glTF: the JSON is nested more than " + std::to_string(kMaxDepth) + " deep");
  } catch (const json::parse_error& e) {
    return fileError(StatusCode::IoError, name, "not valid JSON (at byte " + std::to_string(e.byte) + ")");
  } catch (const json::exception& e) {
    return fileError(StatusCode::IoError, name, std::string("not valid JSON (") + e.what() + ")");
  }
  if (doc.is_object())
    if (Status s = checkVersion(doc, name); !s) return s;
  if (Status s = checkGltfTypes(doc, name); !s) return s;
  if (Status s = checkUris(doc, name, folder); !s) return s;
  if (Status s = checkPrimitives(doc, name); !s) return s;
  if (Status s = checkGltfCameras(doc, name); !s) return s;
  return checkGltfAccessors(doc, name);
}

Status checkGlb(std::string_view bytes, std::string_view name, const std::optional<std::filesystem::path>& folder) {
  auto error = [&](const std::string& problem) { return fileError(StatusCode::IoError, name, "binary glTF: " + problem); };
  const std::uint64_t size = bytes.size();
  if (size < 12 || !bytes.starts_with("glTF")) return error("does not start with the magic \"glTF\"");
  const std::uint32_t version = le32(bytes, 4), length = le32(bytes, 8);
  if (version != 2) return error("version " + std::to_string(version) + " is not supported (glTF 2.0 only)");
  if (length > size)
    return error("the header declares " + std::to_string(length) + " bytes, the file has " + std::to_string(size));
  if (size < 20) return error("no JSON chunk");
  const std::uint64_t jsonLength = le32(bytes, 12);
  if (le32(bytes, 16) != kJsonChunk) return error("the first chunk is not JSON");
  if (jsonLength > size - 20)
    return error("the JSON chunk declares " + std::to_string(jsonLength) + " bytes, " + std::to_string(size - 20) +
                 " follow");
  const std::string_view chunk = bytes.substr(20, std::size_t(jsonLength));
  if (chunk.starts_with(kUtf8ByteOrderMark))
    return error("the JSON chunk starts with a UTF-8 byte-order mark, which glTF 2.0 forbids there; write the chunk "
                 "without it");
  const std::uint64_t next = 20 + jsonLength;
  if (next + 8 <= size && le32(bytes, std::size_t(next) + 4) == kBinChunk) {
    const std::uint64_t binLength = le32(bytes, std::size_t(next));
    if (binLength > size - next - 8)
      return error("the BIN chunk declares " + std::to_string(binLength) + " bytes, " +
                   std::to_string(size - next - 8) + " follow");
  }
  return checkGltfJson(chunk, name, folder);
}

}  // namespace sao::scenes::detail
