#include "gltf_load.h"

#include <limits>
#include <string>

#include "file_checks.h"
#include "sao/scenes/mesh_file.h"

namespace sao::scenes::detail {

namespace {

// File access for tinygltf: regular files only (a FIFO would block, a device never end), and no
// file at all for data in memory (user_data is null then).
bool fileExists(const std::string& path, void* folder) {
  std::error_code ec;
  return folder != nullptr && std::filesystem::is_regular_file(path, ec);
}

std::string samePath(const std::string& path, void*) { return path; }

bool readFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* folder) {
  std::string bytes;
  Status s = folder ? readWholeFile(path, kMaxMeshFileBytes, bytes)
                    : Status::error(StatusCode::IoError, path + ": files are not opened for data in memory");
  if (!s) {
    if (err) *err += s.message + "\n";
    return false;
  }
  out->assign(bytes.begin(), bytes.end());
  return true;
}

bool writeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing files is not allowed\n";
  return false;
}

// Images are not used: their data is left undecoded.
bool ignoreImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

// tinygltf's first line of errors, without its newline, cut to 200 characters (it may quote a
// whole data URI).
std::string firstLine(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  if (line.size() > 200) line = line.substr(0, 200) + "...";
  return line.empty() ? "the data could not be read (no reason given)" : line;
}

}  // namespace

Status parseGltf(std::string_view bytes, bool binary, const std::optional<std::filesystem::path>& folder,
                 std::string_view name, tinygltf::Model& model) {
  if (bytes.size() > std::numeric_limits<unsigned int>::max())  // tinygltf takes an unsigned int size
    return fileError(StatusCode::IoError, name, "is larger than tinygltf reads (4 GiB)");
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(ignoreImage, nullptr);
  // A non-null user_data tells the callbacks that files may be opened.
  static int filesAllowed = 0;
  loader.SetFsCallbacks({fileExists, samePath, readFile, writeFile, folder ? &filesAllowed : nullptr});
  std::string err, warn;
  const std::string base = folder ? folder->string() : std::string();
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const auto size = static_cast<unsigned int>(bytes.size());
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, data, size, base)
                         : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), size, base);
  if (!ok) return fileError(StatusCode::IoError, name, "tinygltf: " + firstLine(err));
  return Status::success();
}

}  // namespace sao::scenes::detail
