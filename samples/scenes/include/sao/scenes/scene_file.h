// Scene files (.scene): meshes with transforms and named views, in a line-based text format
// (docs/scene-format.md). Errors name the file and line as "PATH:LINE: PROBLEM".
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "sao/scenes/scene.h"
#include "sao/status.h"

namespace sao::scenes {

// Scene files larger than this are refused (they are a few lines of text).
inline constexpr std::size_t kMaxSceneFileBytes = 1 << 20;

struct SceneFileMesh {
  std::string path;              // as written, resolved against the scene file's folder
  glm::dmat4 transform{1.0};     // model -> world, the transform lines after the mesh line
  int line = 0;                  // of the mesh line
};

struct SceneFileView {
  View view;                     // up is +y
  std::optional<double> nearDistance;  // absent: a hundredth of the scene's bounding-box diagonal
  int line = 0;
};

struct SceneFile {
  std::vector<SceneFileMesh> meshes;  // at least one
  std::vector<SceneFileView> views;   // may be empty: then the default view (default_view.h)
  std::optional<DeclaredUnits> units; // the `units` line (source "PATH:LINE"), if any
};

// Parses the text of a scene file; `path` is used in messages and to resolve mesh paths. Opens no
// file. InvalidInput "PATH:LINE: PROBLEM" for a syntax error; out is left untouched on error.
Status parseSceneFile(std::string_view text, const std::string& path, SceneFile& out);

// Reads a scene file, its meshes (mesh_file.h) and builds the scene: the meshes transformed into
// world space and appended in order (kMaxMeshTriangles in all), the views, named after the file.
// Errors of a mesh are prefixed with the scene file's "PATH:LINE: ".
Status loadSceneFile(const std::string& path, Scene& out);

}  // namespace sao::scenes
