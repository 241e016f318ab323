// sao-viewer's command line (sao/cli, CLI11).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "sao/scenes/units.h"
#include "viewer_types.h"

namespace sao::viewer {

struct Options {
  std::string backend = "gl";
  std::string scene;  // empty: the default built-in scene
  std::uint32_t view = 0;
  std::optional<scenes::LengthUnit> units;  // --units: the --scene's unit (scenes::chooseUnits)
  int width = 1280, height = 720;  // the window
  ViewMode mode = ViewMode::Lit;
  int zLevel = 1;
  bool reference = false;
  std::uint32_t referenceRays = 32;
  std::string screenshot;  // with --frames: save after the last frame and exit
  std::uint32_t frames = 0;  // 0: run until the window closes
  double orbitStepDegrees = 0;  // the orbit camera turns this much every frame (a scripted moving camera)
  std::uint32_t minFrameMs = 0;  // --min-frame-ms: hold every frame this long (a slow machine, for tests)
  bool hideUi = false, standardDepth = false, validation = false, vsync = true;
  bool ortho = false;  // --ortho: start with the orthographic camera
  bool overwrite = false;  // --overwrite: --screenshot may replace an existing file
  Settings settings;  // from --preset and --set, validated
};

// Parses argv; prints --help and exits 0, or prints a one-line error and exits 2 (bad options,
// unknown presets, settings out of range).
Options parseOptions(int argc, char** argv);

}  // namespace sao::viewer
