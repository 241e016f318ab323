// Mesh files: OBJ and PLY to sao's own readers, glTF through sao's checks to assimp; then the
// same checks of the mesh (validateMesh) for all.
#include "sao/scenes/mesh_file.h"

#include <assimp/BaseImporter.h>
#include <assimp/DefaultIOSystem.h>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <string>

#include "assimp_assert.h"
#include "file_checks.h"
#include "gltf_checks.h"
#include "obj_reader.h"
#include "ply_reader.h"

namespace sao::scenes {

namespace {

using detail::fileError;

std::string point(glm::vec3 p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", double(p.x), double(p.y), double(p.z));
  return text;
}

constexpr std::string_view kMeshExtensions[] = {".gltf", ".glb", ".obj", ".ply"};

// Files a glTF refers to (its buffers) are opened only when they are
// regular files: a FIFO would block, a device (say /dev/zero as a glTF buffer) never end.
// `mainText`, when not empty, is read instead of the file `mainPath` (a .gltf without its
// byte-order mark, which assimp 5.2 refuses as "JSON parse error, offset 0").
class RegularFilesOnly : public Assimp::DefaultIOSystem {
 public:
  RegularFilesOnly(std::string mainPath, const std::string& mainText)
      : mainPath_(std::move(mainPath)), mainText_(mainText) {}
  bool Exists(const char* file) const override { return isRegular(file); }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!isRegular(file) || mode == nullptr || std::strchr(mode, 'r') == nullptr || std::strpbrk(mode, "wa+"))
      return nullptr;
    if (!mainText_.empty() && mainPath_ == file)
      return new Assimp::MemoryIOStream(reinterpret_cast<const std::uint8_t*>(mainText_.data()), mainText_.size());
    return DefaultIOSystem::Open(file, mode);
  }

 private:
  std::string mainPath_;
  const std::string& mainText_;  // outlives the importer
  static bool isRegular(const char* file) {
    if (file == nullptr || *file == '\0') return false;
    std::error_code ec;
    return std::filesystem::is_regular_file(file, ec);
  }
};

// For data in memory: no other file is ever opened (assimp's memory reader would otherwise pass
// any other name a glTF mentions on to the file system).
class NoFiles : public Assimp::IOSystem {
 public:
  bool Exists(const char*) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char*, const char*) override { return nullptr; }
  void Close(Assimp::IOStream* stream) override { delete stream; }
};

constexpr unsigned kPostProcess = aiProcess_ValidateDataStructure | aiProcess_RemoveComponent |
                                  aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_PreTransformVertices;

// Only assimp's glTF 2 reader stays. Otherwise assimp tries every reader it has on a file its
// extension's reader refuses (a damaged .glb was read by the DXF reader): input nobody meant to
// give, code nobody here has fuzzed. The glTF 1.0 reader leaks on every file, even valid ones
// (LeakSanitizer, all five glTF 1.0 models of assimp-testmodels), and glTF 1.0 is long superseded.
// UnregisterLoader hands a reader back to the caller, who deletes it.
void keepOnlyGltf2Reader(Assimp::Importer& importer) {
  for (std::size_t i = importer.GetImporterCount(); i-- > 0;) {
    Assimp::BaseImporter* reader = importer.GetImporter(i);
    const aiImporterDesc* info = reader->GetInfo();
    const bool ours = info != nullptr && info->mName != nullptr && std::string_view(info->mName) == "glTF2 Importer";
    if (!ours && importer.UnregisterLoader(reader) == aiReturn_SUCCESS) delete reader;
  }
}

Status configure(Assimp::Importer& importer, std::string_view name) {
  // assimp's ai_assert checks must throw, not abort (assimp_assert.cpp); checked once.
  static const bool assertionsThrow = detail::assimpAssertionsThrow();
  if (!assertionsThrow)
    return fileError(StatusCode::DriverError, name, "assimp's internal checks would abort the program; not reading it");
  keepOnlyGltf2Reader(importer);
  // Positions are all that is kept: drop the rest before vertices are joined, so that vertices
  // that differ only in normals or texture coordinates become one.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS,
                              aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS | aiComponent_COLORS |
                                  aiComponent_TEXCOORDS | aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                  aiComponent_TEXTURES | aiComponent_LIGHTS | aiComponent_CAMERAS |
                                  aiComponent_MATERIALS);
  return Status::success();
}

// The triangles of an imported scene (in world space after aiProcess_PreTransformVertices); points
// and lines are left out.
Status extract(const aiScene& scene, std::string_view name, Mesh& out) {
  std::size_t vertices = 0, triangles = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes ? scene.mMeshes[m] : nullptr;
    if (mesh == nullptr) return fileError(StatusCode::IoError, name, "assimp returned an empty mesh slot");
    if (mesh->mNumVertices > 0 && mesh->mVertices == nullptr)
      return fileError(StatusCode::IoError, name, "assimp returned a mesh without positions");
    vertices += mesh->mNumVertices;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f)
      if (mesh->mFaces[f].mNumIndices == 3) ++triangles;
  }
  if (triangles == 0) return fileError(StatusCode::InvalidInput, name, "has no triangles");
  if (triangles > kMaxMeshTriangles)
    return fileError(StatusCode::InvalidInput, name,
                     "has " + std::to_string(triangles) + " triangles, more than the limit of " +
                         std::to_string(kMaxMeshTriangles));
  if (vertices > std::numeric_limits<std::uint32_t>::max())
    return fileError(StatusCode::InvalidInput, name, "has " + std::to_string(vertices) + " vertices, more than 2^32 - 1");

  Mesh result;
  result.positions.reserve(vertices);
  result.indices.reserve(triangles * 3);
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    const auto base = static_cast<std::uint32_t>(result.positions.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v)
      result.positions.emplace_back(mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices)
          return fileError(StatusCode::InvalidInput, name,
                           "mesh " + std::to_string(m) + " face " + std::to_string(f) + " refers to vertex " +
                               std::to_string(face.mIndices[k]) + ", but the mesh has " +
                               std::to_string(mesh.mNumVertices) + " vertices");
        result.indices.push_back(base + face.mIndices[k]);
      }
    }
  }
  if (Status s = validateMesh(result, name); !s) return s;
  out = std::move(result);
  return Status::success();
}

Status assimpFailed(std::string_view name, const Assimp::Importer& importer) {
  const char* text = importer.GetErrorString();
  std::string reason = text && *text ? text : "the file could not be read (no reason given)";
  // An exception other than assimp's own (ours from a failed ai_assert, std::bad_alloc) leaves
  // "Unknown exception" as the error string; the exception says more.
  if (const std::exception_ptr& e = importer.GetException(); e && reason == "Unknown exception") {
    try {
      std::rethrow_exception(e);
    } catch (const std::bad_alloc&) {
      reason = "out of memory";
    } catch (const std::exception& x) {
      reason = x.what();
    } catch (...) {
    }
  }
  return fileError(StatusCode::IoError, name, "assimp: " + reason);
}

// Runs `read` with every exception (from assimp, or std::bad_alloc) turned into a Status.
template <class Read>
Status guarded(std::string_view name, Read&& read) {
  try {
    return read();
  } catch (const std::bad_alloc&) {
    return fileError(StatusCode::IoError, name, "out of memory while reading it");
  } catch (const std::exception& e) {
    return fileError(StatusCode::IoError, name, std::string("reading it failed: ") + e.what());
  } catch (...) {
    return fileError(StatusCode::IoError, name, "reading it failed (an unknown exception)");
  }
}

// Data in memory through assimp; no other file is opened.
Status assimpFromMemory(std::string_view bytes, const std::string& hint, std::string_view name, Mesh& out) {
  Assimp::Importer importer;
  if (Status s = configure(importer, name); !s) return s;
  importer.SetIOHandler(new NoFiles);
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), kPostProcess, hint.c_str());
  if (scene == nullptr) return assimpFailed(name, importer);
  return extract(*scene, name, out);
}

// OBJ and PLY go to our own readers (obj_reader.h, ply_reader.h), then the same checks as an
// imported mesh.
Status fromOwnReader(bool obj, std::string_view bytes, std::string_view name, Mesh& out) {
  Mesh mesh;
  if (Status s = obj ? detail::readObj(bytes, name, mesh) : detail::readPly(bytes, name, mesh); !s) return s;
  if (Status s = validateMesh(mesh, name); !s) return s;
  out = std::move(mesh);
  return Status::success();
}

// What assimp is not given (gltf_checks.h): binary glTF chunks larger than the file, invalid JSON.
// A .gltf that starts with a UTF-8 byte-order mark leaves its text without the mark in
// `withoutMark` (for assimp); otherwise that stays empty.
Status checkGltfFile(const std::string& path, const std::string& ext, std::string& withoutMark) {
  if (ext == ".gltf") {
    std::string text;
    if (Status s = detail::readWholeFile(path, kMaxMeshFileBytes, text); !s) return s;
    if (Status s = detail::checkGltfJson(text, path, {{}, std::filesystem::path(path).parent_path()}); !s) return s;
    if (std::string_view(text).starts_with(detail::kUtf8ByteOrderMark))
      withoutMark = text.substr(detail::kUtf8ByteOrderMark.size());
    return Status::success();
  }
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return fileError(StatusCode::IoError, path, "cannot read its size: " + ec.message());
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) return fileError(StatusCode::IoError, path, "cannot open it");
  return detail::checkGlb(size, [&](std::uint64_t offset, std::size_t count, std::string& bytes) {
    bytes.assign(count, '\0');
    in.clear();
    in.seekg(std::streamoff(offset));
    in.read(bytes.data(), std::streamsize(count));
    return in.gcount() == std::streamsize(count);
  }, path, std::filesystem::path(path).parent_path());
}

}  // namespace

bool isMeshFileExtension(std::string_view path) {
  const std::string ext = detail::lowerExtension(path);
  for (std::string_view e : kMeshExtensions)
    if (ext == e) return true;
  return false;
}

Status loadMeshFile(const std::string& path, Mesh& out) {
  if (!isMeshFileExtension(path)) {
    const std::string ext = detail::lowerExtension(path);
    return fileError(StatusCode::UnsupportedFormat, path,
                     (ext.empty() ? std::string("has no extension") : "unknown extension '" + ext + "'") +
                         " (mesh files: .gltf, .glb, .obj, .ply)");
  }
  if (Status s = detail::checkRegularFile(path); !s) return s;
  std::error_code ec;
  if (std::filesystem::file_size(path, ec) == 0 && !ec) return fileError(StatusCode::IoError, path, "is empty");
  const std::string ext = detail::lowerExtension(path);
  if (ext == ".ply" || ext == ".obj") {
    std::string bytes;
    if (Status s = detail::readWholeFile(path, kMaxMeshFileBytes, bytes); !s) return s;
    return guarded(path, [&] { return fromOwnReader(ext == ".obj", bytes, path, out); });
  }
  std::string withoutMark;
  if (ext == ".gltf" || ext == ".glb")
    if (Status s = guarded(path, [&] { return checkGltfFile(path, ext, withoutMark); }); !s) return s;
  return guarded(path, [&]() -> Status {
    Assimp::Importer importer;
    if (Status s = configure(importer, path); !s) return s;
    importer.SetIOHandler(new RegularFilesOnly(path, withoutMark));  // the importer owns it
    const aiScene* scene = importer.ReadFile(path, kPostProcess);
    if (scene == nullptr) return assimpFailed(path, importer);
    return extract(*scene, path, out);
  });
}

Status loadMeshFromMemory(std::span<const std::uint8_t> bytes, std::string_view formatHint, std::string_view name,
                          Mesh& out) {
  std::string hint(formatHint);
  if (!isMeshFileExtension("x." + hint))
    return fileError(StatusCode::UnsupportedFormat, name,
                     "unknown format '" + hint + "' (mesh formats: gltf, glb, obj, ply)");
  if (bytes.empty()) return fileError(StatusCode::IoError, name, "is empty");
  std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (hint == "ply" || hint == "obj") return guarded(name, [&] { return fromOwnReader(hint == "obj", text, name, out); });
  if (hint == "gltf") {
    if (Status s = guarded(name, [&] { return detail::checkGltfJson(text, name); }); !s) return s;
    // assimp 5.2 refuses a byte-order mark ("JSON parse error, offset 0"); the glTF 2.0
    // specification lets readers ignore it.
    if (text.starts_with(detail::kUtf8ByteOrderMark)) text.remove_prefix(detail::kUtf8ByteOrderMark.size());
  }
  if (hint == "glb") {
    const auto read = [&](std::uint64_t offset, std::size_t count, std::string& chunk) {
      if (offset > text.size() || count > text.size() - offset) return false;
      chunk.assign(text.substr(std::size_t(offset), count));
      return true;
    };
    if (Status s = guarded(name, [&] { return detail::checkGlb(text.size(), read, name); }); !s) return s;
  }
  return guarded(name, [&] { return assimpFromMemory(text, hint, name, out); });
}

Status validateMesh(const Mesh& mesh, std::string_view name, std::size_t maxTriangles) {
  if (mesh.indices.size() % 3 != 0)
    return fileError(StatusCode::InvalidInput, name,
                     "has " + std::to_string(mesh.indices.size()) + " indices, not a whole number of triangles");
  const std::size_t triangles = mesh.triangleCount();
  if (triangles == 0) return fileError(StatusCode::InvalidInput, name, "has no triangles");
  if (triangles > maxTriangles)
    return fileError(StatusCode::InvalidInput, name,
                     "has " + std::to_string(triangles) + " triangles, more than the limit of " +
                         std::to_string(maxTriangles));
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const glm::vec3 p = mesh.positions[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return fileError(StatusCode::InvalidInput, name,
                       "vertex " + std::to_string(v) + " has a non-finite coordinate " + point(p));
  }
  for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
    if (mesh.indices[i] >= mesh.positions.size())
      return fileError(StatusCode::InvalidInput, name,
                       "triangle " + std::to_string(i / 3) + " refers to vertex " + std::to_string(mesh.indices[i]) +
                           ", but there are only " + std::to_string(mesh.positions.size()) + " vertices");
    lo = glm::min(lo, mesh.positions[mesh.indices[i]]);
    hi = glm::max(hi, mesh.positions[mesh.indices[i]]);
  }
  if (lo == hi)
    return fileError(StatusCode::InvalidInput, name,
                     "all its triangles are at one point " + point(lo));
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    const auto& p = mesh.positions;
    if (!isDegenerateTriangle(p[mesh.indices[i]], p[mesh.indices[i + 1]], p[mesh.indices[i + 2]]))
      return Status::success();
  }
  return fileError(StatusCode::InvalidInput, name,
                   "all its " + std::to_string(triangles) +
                       " triangles are degenerate (no area: corners repeated or on one line), so nothing would be "
                       "drawn");
}

bool isDegenerateTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const glm::dvec3 ab = glm::dvec3(b) - glm::dvec3(a), ac = glm::dvec3(c) - glm::dvec3(a);
  const glm::dvec3 bc = glm::dvec3(c) - glm::dvec3(b);
  const double longest2 = std::max({glm::dot(ab, ab), glm::dot(ac, ac), glm::dot(bc, bc)});
  // |ab x ac| is twice the area: the longest edge times the height on it.
  return glm::length(glm::cross(ab, ac)) <= 1e-6 * longest2;
}

std::size_t removeDegenerateTriangles(Mesh& mesh, std::string_view name, std::vector<std::string>& warnings) {
  std::size_t kept = 0;
  const auto& p = mesh.positions;
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    const std::uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
    if (isDegenerateTriangle(p[a], p[b], p[c])) continue;
    mesh.indices[kept++] = a;
    mesh.indices[kept++] = b;
    mesh.indices[kept++] = c;
  }
  const std::size_t removed = (mesh.indices.size() - kept) / 3;
  if (removed > 0)
    warnings.push_back(std::string(name) + ": " + std::to_string(removed) + " of " +
                       std::to_string(mesh.triangleCount()) +
                       " triangles are degenerate (no area: corners repeated or on one line) and were left out");
  mesh.indices.resize(kept);
  return removed;
}

}  // namespace sao::scenes
