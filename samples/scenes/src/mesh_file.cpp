// Mesh files: OBJ and PLY to sao's own readers, glTF through sao's checks to tinygltf; then the
// same checks of the mesh (validateMesh) for all.
#include "sao/scenes/mesh_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <new>
#include <optional>
#include <string>

#include "file_checks.h"
#include "gltf_cameras.h"
#include "gltf_checks.h"
#include "gltf_load.h"
#include "gltf_mesh.h"
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

// Runs `read` with every exception (std::bad_alloc, or one from a library) turned into a Status.
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

// The mesh a reader made, after the same checks for every format.
Status validated(Mesh& mesh, std::string_view name, Mesh& out) {
  if (Status s = validateMesh(mesh, name); !s) return s;
  out = std::move(mesh);
  return Status::success();
}

// OBJ and PLY go to our own readers (obj_reader.h, ply_reader.h); they have no cameras.
Status fromOwnReader(bool obj, std::string_view bytes, std::string_view name, Mesh& out, std::vector<View>* cameras) {
  Mesh mesh;
  if (Status s = obj ? detail::readObj(bytes, name, mesh) : detail::readPly(bytes, name, mesh); !s) return s;
  if (Status s = validated(mesh, name, out); !s) return s;
  if (cameras) cameras->clear();
  return Status::success();
}

// glTF (`binary`: a .glb): sao's checks (gltf_checks.h), then tinygltf, then the triangles of its
// model and, when asked for, the views of its cameras. `folder`: where a file's external buffers
// are; none for data in memory.
Status fromGltf(std::string_view bytes, bool binary, const std::optional<std::filesystem::path>& folder,
                std::string_view name, Mesh& out, std::vector<View>* cameras) {
  // The glTF 2.0 specification lets readers ignore a byte-order mark before a .gltf's JSON.
  if (!binary && bytes.starts_with(detail::kUtf8ByteOrderMark)) bytes.remove_prefix(detail::kUtf8ByteOrderMark.size());
  if (Status s = binary ? detail::checkGlb(bytes, name, folder) : detail::checkGltfJson(bytes, name, folder); !s)
    return s;
  tinygltf::Model model;
  if (Status s = detail::parseGltf(bytes, binary, folder, name, model); !s) return s;
  Mesh mesh;
  std::vector<detail::GltfCameraNode> nodes;
  if (Status s = detail::gltfTriangles(model, name, mesh, &nodes); !s) return s;
  if (Status s = validateMesh(mesh, name); !s) return s;
  std::vector<View> views;
  if (cameras)
    if (Status s = detail::gltfCameraViews(model, nodes, mesh, name, views); !s) return s;
  out = std::move(mesh);
  if (cameras) *cameras = std::move(views);
  return Status::success();
}

}  // namespace

bool isMeshFileExtension(std::string_view path) {
  const std::string ext = detail::lowerExtension(path);
  for (std::string_view e : kMeshExtensions)
    if (ext == e) return true;
  return false;
}

Status loadMeshFile(const std::string& path, Mesh& out, std::vector<View>* cameras) {
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
  std::string bytes;
  if (Status s = detail::readWholeFile(path, kMaxMeshFileBytes, bytes); !s) return s;
  return guarded(path, [&] {
    if (ext == ".ply" || ext == ".obj") return fromOwnReader(ext == ".obj", bytes, path, out, cameras);
    return fromGltf(bytes, ext == ".glb", std::filesystem::path(path).parent_path(), path, out, cameras);
  });
}

Status loadMeshFromMemory(std::span<const std::uint8_t> bytes, std::string_view formatHint, std::string_view name,
                          Mesh& out, std::vector<View>* cameras) {
  const std::string hint(formatHint);
  if (!isMeshFileExtension("x." + hint))
    return fileError(StatusCode::UnsupportedFormat, name,
                     "unknown format '" + hint + "' (mesh formats: gltf, glb, obj, ply)");
  if (bytes.empty()) return fileError(StatusCode::IoError, name, "is empty");
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  return guarded(name, [&] {
    if (hint == "ply" || hint == "obj") return fromOwnReader(hint == "obj", text, name, out, cameras);
    return fromGltf(text, hint == "glb", std::nullopt, name, out, cameras);
  });
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
