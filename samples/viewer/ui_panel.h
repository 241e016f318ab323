// The viewer's ImGui panel: scene and camera, view mode, the generated settings, the reference,
// live per-pass timings and the plan.
#pragma once
#include <string>
#include <vector>

#include "camera_control.h"
#include "sao/samples/metrics.h"
#include "sao/scenes/scene.h"
#include "settings_panel.h"
#include "viewer_types.h"

namespace sao::viewer {

// What the panel edits, and the requests it raises for the app to carry out.
struct UiState {
  Settings settings;
  SettingsPanelState settingsPanel;
  ViewMode mode = ViewMode::Lit;
  int cszLevel = 1;
  float split = 0.5f;
  float errorScale = 0.5f;
  int scene = 0;  // index into scenes::builtinSceneNames(), or -1 for sceneFile
  std::string sceneFile;  // the mesh or scene file given with --scene
  int view = 0;   // index into the scene's views
  int referenceRays = 32;
  bool measureTime = true;
  bool showUi = true;
  // Where the panel was drawn this frame (fractions of the window's width; shown: visible and not
  // collapsed): the scene is framed for the rest (framing.h).
  bool panelShown = false;
  double panelX0 = 0, panelX1 = 0;
  ViewMode panelMode = ViewMode::Lit;  // the mode the panel last saw (opens the reference tab)
  // Where the timings and the plan end this frame, and the window's height (pixels, y down; -1: the
  // panel was not drawn): they must be readable without scrolling (sao-viewer prints both at exit).
  float topSectionsEndY = -1, displayHeight = 0;
  // Requests, cleared by the app once handled.
  bool sceneChanged = false, resetCamera = false, computeReference = false, screenshot = false;
};

// What the panel shows.
struct PanelInfo {
  std::string backend;
  double frameMs = 0;
  const FrameStats* stats = nullptr;
  std::uint64_t fullBytes = 0;  // a naive allocation, for comparison with the plan
  const scenes::Scene* scene = nullptr;
  std::string referenceStatus;
  bool haveMetrics = false;
  samples::ReferenceComparison metrics;
  std::string message;  // the last screenshot, a failed scene load, ...
  const std::vector<std::string>* scaleWarnings = nullptr;  // sao/samples/scale_warnings.h, this view
};

void drawPanel(UiState& state, const PanelInfo& info, CameraController& camera);

// Labels drawn over the scene, under the panel, for `frame` (its divider, its reference): the split
// view's "without AO | with AO", the split-resolution view's divisors and each half's AO time (from
// `stats`, the last frame's; null before the first); the values of the error view's colour bar.
void drawOverlay(const FrameDesc& frame, const UiState& state, const FrameStats* stats);

}  // namespace sao::viewer
