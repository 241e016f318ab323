// Fuzz target: scenes from files (samples/scenes): the .scene parser (parseSceneFile) on every
// input, and the mesh readers from memory (loadMeshFromMemory: sao's OBJ and PLY readers; for
// glTF, sao's JSON and binary-container checks, then tinygltf) in the format the bytes start like, as
// a program picks a reader by extension: "ply" -> ply, "glTF" -> glb, a '{' (after blanks) ->
// gltf, anything else -> obj. No file is opened (meshes named by a scene file are not loaded; a
// glTF's external buffers are refused from memory).
//
// Invariants: no crash, no exception, no sanitizer report, no leak (tinygltf is compiled into
// sao_scenes, so it is instrumented too). Scene text:
// an error is InvalidInput "NAME:" or "NAME:LINE: ..." and leaves the output untouched; a success
// has at least one mesh with a mesh extension and a finite, invertible transform, and views whose
// eye and target differ, with fovy in (0, pi) and a positive near plane when given. Mesh: an error
// is IoError or InvalidInput naming the data and leaves the outputs untouched; a success passes
// validateMesh, its default view is finite with a positive near plane, and a glTF's camera views
// have unique one-line names other than "default", a finite view matrix, and a fovy in (0, pi)
// with a near plane > 0 or an orthographic height > 0 with 0 <= near < far, all finite.
#include <cmath>
#include <cstdint>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.h"
#include "sao/scenes/default_view.h"
#include "sao/scenes/mesh_file.h"
#include "sao/scenes/scene_file.h"

namespace {

using namespace sao::scenes;

constexpr const char* kScenePath = "fuzz/input.scene";
constexpr const char* kMeshName = "fuzz-input";

bool finite(glm::dvec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool startsWith(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

void checkSceneText(std::string_view text) {
  SceneFile file;
  file.views.resize(2);
  const sao::Status st = parseSceneFile(text, kScenePath, file);
  if (!st) {
    SAO_FUZZ_CHECK(st.code == sao::StatusCode::InvalidInput, "%s", st.message.c_str());
    SAO_FUZZ_CHECK(startsWith(st.message, std::string(kScenePath) + ":") && st.message.size() > 20, "%s",
                   st.message.c_str());
    SAO_FUZZ_CHECK(file.meshes.empty() && file.views.size() == 2, "outputs changed on error");
    return;
  }
  SAO_FUZZ_CHECK(!file.meshes.empty());
  for (const SceneFileMesh& m : file.meshes) {
    SAO_FUZZ_CHECK(isMeshFileExtension(m.path) && (startsWith(m.path, "fuzz/") || m.path[0] == '/'), "%s",
                   m.path.c_str());
    SAO_FUZZ_CHECK(m.line >= 1);
    for (int c = 0; c < 4; ++c) SAO_FUZZ_CHECK(finite(glm::dvec3(m.transform[c])) && std::isfinite(m.transform[c][3]));
    SAO_FUZZ_CHECK(glm::determinant(glm::dmat3(m.transform)) != 0.0);
  }
  for (const SceneFileView& v : file.views) {
    SAO_FUZZ_CHECK(finite(v.view.eye) && finite(v.view.target) && v.view.eye != v.view.target);
    SAO_FUZZ_CHECK(v.view.fovyRadians > 0 && v.view.fovyRadians < 3.14159266);
    SAO_FUZZ_CHECK(!v.nearDistance || *v.nearDistance > 0);
    SAO_FUZZ_CHECK(v.view.orthoHeight == 0 || (v.view.orthoHeight > 0 && std::isfinite(v.view.orthoHeight)));
    const glm::dmat4 m = viewMatrix(v.view);
    for (int c = 0; c < 4; ++c) SAO_FUZZ_CHECK(finite(glm::dvec3(m[c])), "view '%s' has a non-finite matrix", v.view.name.c_str());
  }
}

const char* formatOf(std::string_view bytes) {
  if (startsWith(bytes, "ply")) return "ply";
  if (startsWith(bytes, "glTF")) return "glb";
  const std::size_t first = bytes.find_first_not_of(" \t\r\n");
  if (first != std::string_view::npos && bytes[first] == '{') return "gltf";
  return "obj";
}

void checkCameraView(const View& v, std::set<std::string>& names) {
  SAO_FUZZ_CHECK(!v.name.empty() && v.name != "default" && names.insert(v.name).second, "view name '%s'",
                 v.name.c_str());
  for (char c : v.name) SAO_FUZZ_CHECK(static_cast<unsigned char>(c) >= 0x20 && c != 0x7f, "control character in a name");
  SAO_FUZZ_CHECK(finite(v.eye) && finite(v.target) && finite(v.up) && v.eye != v.target, "view '%s'", v.name.c_str());
  if (v.orthographic())
    SAO_FUZZ_CHECK(std::isfinite(v.orthoHeight) && v.nearDistance >= 0 && v.orthoFar > v.nearDistance &&
                   std::isfinite(v.orthoFar), "orthographic view '%s'", v.name.c_str());
  else
    SAO_FUZZ_CHECK(v.fovyRadians > 0 && v.fovyRadians < 3.14159266 && v.nearDistance > 0 &&
                   std::isfinite(v.nearDistance), "perspective view '%s'", v.name.c_str());
  const glm::dmat4 m = viewMatrix(v);
  for (int c = 0; c < 4; ++c) SAO_FUZZ_CHECK(finite(glm::dvec3(m[c])), "view '%s' has a non-finite matrix", v.name.c_str());
}

void checkMesh(std::span<const std::uint8_t> bytes, const char* format) {
  Mesh mesh;
  mesh.positions = {{4, 5, 6}};
  std::vector<View> cameras(1);
  const sao::Status st = loadMeshFromMemory(bytes, format, kMeshName, mesh, &cameras);
  if (!st) {
    SAO_FUZZ_CHECK(st.code == sao::StatusCode::IoError || st.code == sao::StatusCode::InvalidInput, "%s: %s",
                   sao::toString(st.code), st.message.c_str());
    SAO_FUZZ_CHECK(startsWith(st.message, std::string(kMeshName) + ": "), "%s", st.message.c_str());
    SAO_FUZZ_CHECK(mesh.positions.size() == 1 && mesh.indices.empty() && cameras.size() == 1, "outputs changed on error");
    return;
  }
  std::set<std::string> names;
  for (const View& v : cameras) checkCameraView(v, names);
  const sao::Status valid = validateMesh(mesh, kMeshName);
  SAO_FUZZ_CHECK(valid.ok(), "%s", valid.message.c_str());
  const View v = defaultView(mesh);
  SAO_FUZZ_CHECK(finite(v.eye) && finite(v.target) && v.eye != v.target && v.nearDistance > 0 &&
                 std::isfinite(v.nearDistance), "default view of a valid mesh");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  checkSceneText(text);
  checkMesh({data, size}, formatOf(text));
  return 0;
}
