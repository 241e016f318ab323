// sao-render's command line (sao/cli, CLI11). `sao-render --help` lists the options.
#pragma once
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <string>

#include <glm/glm.hpp>

#include "sao/image.h"
#include "sao/plan.h"
#include "sao/scenes/camera_path.h"
#include "sao/scenes/scene.h"
#include "sao/settings.h"

namespace sao::render {

struct Options {
  std::string out = "out/render", backend = "auto", scene = std::string(scenes::kDefaultScene), depthPath, dumpDir,
              saveDepth, depthSource = "auto";
  std::uint32_t view = 0, guard = 0, referenceRays = 256;
  Extent size{1280, 720};
  std::string clip = "zero-one";
  DepthFormat depthFormat = DepthFormat::D32F;
  double fovyDegrees = 60, nearDistance = 0.1, far = INFINITY;
  std::optional<glm::dvec3> eye, target;
  std::optional<double> orthoHeight;  // --ortho: an orthographic camera this tall (view units), not --fovy
  bool reversedZ = false, cameraFlags = false, reference = false, json = false;
  bool overwrite = false;  // --overwrite (sao/samples/output_files.h)

  bool depthDistances = false;  // --depth-distances: the camera-less --depth file holds view-axis distances
  Settings settings;  // from --preset and --set, validated
  std::uint32_t runs = 1;
  std::uint32_t frames = 1;                          // --frames: a camera path of this many frames
  scenes::PathKind path = scenes::PathKind::Orbit;  // --path
  double progressSeconds = 2;
  std::optional<scenes::LengthUnit> units;  // --units
  std::set<std::string> given;              // the options on the command line
  bool has(const char* option) const { return given.count(option) > 0; }
};

// Parses argv: --help prints the help and exits 0; a bad option, or one that would have no
// effect in its combination, prints one line and exits 2.
Options parseOptions(int argc, char** argv);

}  // namespace sao::render
