// Scenes: a world-space mesh and named camera views. Built-in scenes are generated in code,
// deterministically; others are read from mesh and scene files (loadScene).
#pragma once
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "sao/camera.h"
#include "sao/scenes/mesh.h"
#include "sao/scenes/units.h"
#include "sao/status.h"

namespace sao::scenes {

struct View {
  std::string name;
  glm::dvec3 eye{0, 1.6, 5};
  glm::dvec3 target{0, 1, 0};
  glm::dvec3 up{0, 1, 0};
  double fovyRadians = 1.0;
  double nearDistance = 0.1;
  // Orthographic when > 0: the full height of the view in scene units (fovyRadians is then
  // unused; the width follows the aspect). Primary rays are parallel, from the view plane.
  double orthoHeight = 0;
  // The far plane of an orthographic view, which needs a finite one (fitOrthoFar sets it just
  // beyond the mesh; a glTF camera brings its zfar); 0: makeCamera falls back to 1000 x the
  // eye-target distance.
  double orthoFar = 0;
  bool orthographic() const { return orthoHeight > 0; }
};

struct Scene {
  std::string name;
  Mesh mesh;
  std::vector<View> views;  // at least one
  // The unit the scene states: built-in scenes and glTF files metres, a scene file its `units`
  // line; none for OBJ and PLY (scenes::chooseUnits decides, units.h).
  std::optional<DeclaredUnits> units{};
  // What loadScene changed without refusing the file, one line each ("PATH: 3 of 12 triangles
  // are degenerate ... left out"), for the programs to print.
  std::vector<std::string> warnings{};
};

// "sponza-like" (the default), "sphere-plane", "crease", "thin", "gears".
std::span<const std::string_view> builtinSceneNames();
inline constexpr std::string_view kDefaultScene = "sponza-like";

Status makeBuiltinScene(std::string_view name, Scene& out);

// The entry point of the programs' --scene: a built-in scene's name goes to makeBuiltinScene;
// otherwise nameOrPath is a file (src/load_scene.cpp):
//   .scene                   a scene file (scene_file.h, docs/scene-format.md)
//   .gltf .glb .obj .ply     a mesh file (mesh_file.h) in the file's units (Scene::units), with the
//                            view "default" (default_view.h) first, then a glTF's cameras in node
//                            order (mesh_file.h)
// Errors: the built-in scenes' "unknown built-in scene" for a name that is no file either,
// UnsupportedFormat for another extension, and the file readers' errors, each naming the file.
// out is left untouched on error.
Status loadScene(std::string_view nameOrPath, Scene& out);

// World -> camera (right-handed, looking down -z), built in double.
glm::dmat4 viewMatrix(const View& view);
// viewMatrix as sao::Camera::view holds it (column-major); makeCamera sets it.
std::array<double, 16> viewArray(const View& view);

// The camera for a view at a size, with the depth conventions given (a finite far plane when
// farDistance is finite). An orthographic view always gets a finite far plane: farDistance when
// finite, else view.orthoFar (or its fallback).
Camera makeCamera(const View& view, std::uint32_t width, std::uint32_t height, double farDistance, ClipDepth clip,
                  bool reversedZ, std::uint32_t guardBand = 0);

// Sets view.orthoFar to just beyond the farthest corner of the mesh's bounding box along the view
// direction (at least twice the near distance), so that an orthographic depth keeps its linear
// precision for the scene. loadScene does this for every orthographic view of a scene file (a
// glTF camera keeps the zfar of its file).
void fitOrthoFar(View& view, const Mesh& mesh);
// The same from the mesh's bounding box (lo, hi), for callers that keep it.
void fitOrthoFar(View& view, glm::dvec3 lo, glm::dvec3 hi);

// A perspective view made orthographic with the same framing at its target: as tall as its field
// of view spans at the target distance (an orthographic view keeps its height). The rays being
// parallel, the eye only decides what the near plane cuts: it moves back along the view direction
// until the bounding box (lo, hi) lies beyond the near plane; the far plane is fitted to it.
View toOrthographic(View view, glm::dvec3 lo, glm::dvec3 hi);
View toOrthographic(const View& view, const Mesh& mesh);

}  // namespace sao::scenes
