// Scenes: a world-space mesh and named camera views. Built-in scenes are generated in code,
// deterministically.
#pragma once
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "sao/camera.h"
#include "sao/scenes/mesh.h"
#include "sao/status.h"

namespace sao::scenes {

struct View {
  std::string name;
  glm::dvec3 eye{0, 1.6, 5};
  glm::dvec3 target{0, 1, 0};
  glm::dvec3 up{0, 1, 0};
  double fovyRadians = 1.0;
  double nearDistance = 0.1;
};

struct Scene {
  std::string name;
  Mesh mesh;
  std::vector<View> views;  // at least one
};

// "sponza-like" (the default), "sphere-plane", "crease", "thin", "gears".
std::span<const std::string_view> builtinSceneNames();
inline constexpr std::string_view kDefaultScene = "sponza-like";

Status makeBuiltinScene(std::string_view name, Scene& out);

// World -> camera (right-handed, looking down -z), built in double.
glm::dmat4 viewMatrix(const View& view);

// The camera for a view at a size, with the depth conventions given (a finite far plane when
// farDistance is finite).
Camera makeCamera(const View& view, std::uint32_t width, std::uint32_t height, double farDistance, ClipDepth clip,
                  bool reversedZ, std::uint32_t guardBand = 0);

}  // namespace sao::scenes
