// loadScene: a built-in scene's name, a mesh file or a scene file.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "file_checks.h"
#include "sao/scenes/default_view.h"
#include "sao/scenes/mesh_file.h"
#include "sao/scenes/scene.h"
#include "sao/scenes/scene_file.h"

namespace sao::scenes {

Status loadScene(std::string_view nameOrPath, Scene& out) {
  const auto names = builtinSceneNames();
  if (std::find(names.begin(), names.end(), nameOrPath) != names.end()) return makeBuiltinScene(nameOrPath, out);

  const std::string path(nameOrPath);
  const std::string ext = detail::lowerExtension(path);
  if (ext == ".scene") return loadSceneFile(path, out);
  if (isMeshFileExtension(path)) {
    Scene scene;
    std::vector<View> cameras;
    if (Status s = loadMeshFile(path, scene.mesh, &cameras); !s) return s;
    removeDegenerateTriangles(scene.mesh, path, scene.warnings);
    scene.name = std::filesystem::path(path).filename().string();
    // The default view first: view 0 of a mesh file is the same whether it has cameras or not.
    scene.views.push_back(defaultView(scene.mesh));
    scene.views.insert(scene.views.end(), cameras.begin(), cameras.end());
    if (ext == ".gltf" || ext == ".glb") scene.units = DeclaredUnits{LengthUnit::Metre, "glTF: metres by its specification"};
    out = std::move(scene);
    return Status::success();
  }
  std::error_code ec;
  const bool exists = std::filesystem::exists(path, ec);
  if (!exists && ext.empty() && path.find('/') == std::string::npos) {
    Status s = makeBuiltinScene(nameOrPath, out);  // its message lists the built-in scenes
    s.message += ", and no file of that name either";
    return s;
  }
  if (exists && std::filesystem::is_directory(path, ec))
    return detail::fileError(StatusCode::IoError, path, "is a directory, not a scene or mesh file");
  return detail::fileError(StatusCode::UnsupportedFormat, path,
                           (ext.empty() ? std::string("has no extension") : "unknown extension '" + ext + "'") +
                               " (scene files: .scene; mesh files: .gltf, .glb, .obj, .ply)");
}

}  // namespace sao::scenes
