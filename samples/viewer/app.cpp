#include "app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>  // GImGui: whether the active item is a text field

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <optional>
#include <thread>
#include <vector>

#include "backend.h"
#include "camera_control.h"
#include "framing.h"
#include "reference.h"
#include "sao/samples/scale_warnings.h"
#include "screenshot.h"
#include "ui_panel.h"

namespace sao::viewer {
namespace {

// Owns the ImGui context (created before the backends' ImGui init, destroyed after their shutdown).
struct ImGuiContextOwner {
  ImGuiContextOwner() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
    ImGui::StyleColorsDark();
  }
  ~ImGuiContextOwner() { ImGui::DestroyContext(); }
};

class App {
 public:
  explicit App(const Options& options) : options_(options) {}
  int run();

 private:
  Status start();
  Status loadScene(int index);                          // a built-in scene
  // index -1: the file ui_.sceneFile. `requested`: --units, for the scene named on the command line.
  Status adoptScene(scenes::Scene&& scene, int index, std::optional<scenes::LengthUnit> requested = std::nullopt);
  double radiusInSceneUnits() const { return ui_.settings.radius * metersToViewUnits_; }
  void handleKeys();
  Status handleRequests(const FrameDesc& frame);
  FrameDesc buildFrame(glm::ivec2 size) const;
  void updateMetrics(const FrameDesc& frame);
  void checkScale(const FrameDesc& frame);
  PanelInfo panelInfo() const;

  Options options_;
  std::unique_ptr<Window> window_;
  std::unique_ptr<ImGuiContextOwner> imgui_;
  std::unique_ptr<Backend> backend_;  // destroyed before the ImGui context and the window
  scenes::Scene scene_;
  double metersToViewUnits_ = 1.0;  // the scene's units (scenes::chooseUnits)
  glm::dvec3 boundsMin_{0}, boundsMax_{0};
  CameraController camera_;
  UiState ui_;
  Reference reference_;
  FrameStats stats_;
  bool haveStats_ = false, haveMetrics_ = false, referenceRequested_ = false;
  samples::ReferenceComparison metrics_;
  Settings metricsSettings_;
  std::string message_;
  double frameMs_ = 0;
  bool textField_ = false;  // a text field of the panel has had the keys (printed, not yet given back)
  Camera lastCamera_;  // the last frame's (the panel's framing included)
  // The scale check (checkScale): what it last looked at, what the frame before looked like, and
  // its warnings (printed on stderr when they change).
  struct ScaleKey {
    Camera camera;
    Settings settings;
    std::uint64_t scene = 0;
    bool operator==(const ScaleKey&) const = default;
  };
  std::optional<ScaleKey> scaleChecked_, scalePrevious_;
  std::uint64_t sceneGeneration_ = 0;
  std::vector<std::string> scaleWarnings_, scalePrinted_;
};

Status App::start() {
  const Api api = options_.backend == "vulkan" ? Api::Vulkan : Api::OpenGL;
  const std::string title = "sao-viewer (" + options_.backend + ")";
  if (Status s = Window::create(api, options_.width, options_.height, title, window_); !s) return s;
  imgui_ = std::make_unique<ImGuiContextOwner>();
  BackendOptions bo;
  bo.vsync = options_.vsync;
  bo.validation = options_.validation;
  bo.standardDepth = options_.standardDepth;
  if (Status s = api == Api::Vulkan ? createVulkanBackend(*window_, bo, backend_) : createGlBackend(*window_, bo, backend_);
      !s)
    return s;
  window_->takeKeyCallback();  // in front of ImGui's, which the backend installed
  ui_.settings = options_.settings;
  ui_.mode = options_.mode;
  ui_.cszLevel = options_.zLevel;
  ui_.showUi = !options_.hideUi;
  ui_.referenceRays = int(options_.referenceRays);
  referenceRequested_ = options_.reference;
  const std::string name = options_.scene.empty() ? std::string(scenes::kDefaultScene) : options_.scene;
  const auto names = scenes::builtinSceneNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) {
    // A mesh or scene file (scenes::loadScene; its errors name the file and list the built-ins).
    scenes::Scene scene;
    if (Status s = scenes::loadScene(name, scene); !s) return s;
    for (const std::string& w : scene.warnings) std::fprintf(stderr, "sao-viewer: warning: %s\n", w.c_str());
    ui_.sceneFile = name;
    if (Status s = adoptScene(std::move(scene), -1, options_.units); !s) return s;
  } else {
    scenes::Scene scene;
    if (Status s = scenes::makeBuiltinScene(name, scene); !s) return s;
    if (Status s = adoptScene(std::move(scene), int(it - names.begin()), options_.units); !s) return s;
  }
  if (options_.view >= scene_.views.size())
    return Status::error(StatusCode::InvalidInput, "scene '" + name + "' has views 0.." +
                                                       std::to_string(scene_.views.size() - 1));
  ui_.view = int(options_.view);
  camera_.reset(scene_.views[options_.view]);
  if (options_.ortho) camera_.orthographic = true;
  return Status::success();
}

Status App::loadScene(int index) {
  scenes::Scene scene;
  if (Status s = scenes::makeBuiltinScene(scenes::builtinSceneNames()[std::size_t(index)], scene); !s) return s;
  return adoptScene(std::move(scene), index);
}

Status App::adoptScene(scenes::Scene&& scene, int index, std::optional<scenes::LengthUnit> requested) {
  scene_ = std::move(scene);
  ++sceneGeneration_;
  const scenes::UnitChoice units = scenes::chooseUnits(scene_.mesh, scene_.units, requested);
  metersToViewUnits_ = units.metersToViewUnits;
  std::printf("sao-viewer: units %s\n", units.note.c_str());
  boundsMin_ = glm::dvec3(std::numeric_limits<double>::max());
  boundsMax_ = -boundsMin_;
  for (const auto& p : scene_.mesh.positions) {
    boundsMin_ = glm::min(boundsMin_, glm::dvec3(p));
    boundsMax_ = glm::max(boundsMax_, glm::dvec3(p));
  }
  ui_.scene = index;
  ui_.view = 0;
  camera_.setSceneBounds(boundsMin_, boundsMax_);
  camera_.reset(scene_.views[0]);
  reference_.setScene(&scene_);
  haveMetrics_ = false;
  if (Status s = backend_->setReference(nullptr); !s) return s;
  return backend_->setMesh(scene_.mesh);
}

void App::handleKeys() {
  // A focused text field (Ctrl+click on a slider) or a dragged widget has the keys: ImGui gets
  // them from the same callback chain, the viewer leaves them alone. ImGui's flag dates from the
  // start of the last frame, the active item from its end: a field opened in the last frame keeps
  // the keys typed since (at a few frames a second, the next keys of a user who clicked then typed).
  const bool panelHasKeys = ImGui::GetIO().WantCaptureKeyboard || ImGui::IsAnyItemActive();
  if (textField_ && !panelHasKeys) {  // the keys are the viewer's again from now on
    textField_ = false;
    std::printf("sao-viewer: the text field let the keyboard go\n");
    std::fflush(stdout);
  }
  if (panelHasKeys) return;
  for (const int key : window_->keyPresses()) {  // every press since the last frame, in order
    switch (key) {
      case GLFW_KEY_ESCAPE: window_->requestClose(); break;
      case GLFW_KEY_F12: ui_.screenshot = true; break;
      case GLFW_KEY_R: ui_.computeReference = true; break;
      case GLFW_KEY_H: ui_.showUi = !ui_.showUi; break;
      case GLFW_KEY_HOME: ui_.resetCamera = true; break;
      case GLFW_KEY_O: camera_.orthographic = !camera_.orthographic; break;
      case GLFW_KEY_TAB:
        camera_.mode = camera_.mode == CameraController::Mode::Orbit ? CameraController::Mode::Fly
                                                                      : CameraController::Mode::Orbit;
        break;
      default:
        for (const auto& m : viewModes())
          if (key == GLFW_KEY_1 + static_cast<int>(m.mode)) {
            ui_.mode = m.mode;
            // Scripted sessions (tests/apps/viewer_keys.sh) check that every press took effect.
            std::printf("sao-viewer: view mode %.*s (key %d)\n", int(m.name.size()), m.name.data(),
                        1 + static_cast<int>(m.mode));
            std::fflush(stdout);
          }
    }
  }
}

FrameDesc App::buildFrame(glm::ivec2 size) const {
  FrameDesc f;
  const scenes::View v = camera_.view();
  f.view = scenes::viewMatrix(v);
  // Camera-space depth range of the scene's bounding box: the csz view's grey ramp and, without
  // reversed-Z, the far plane.
  double zMin = std::numeric_limits<double>::max(), zMax = 0;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 corner(i & 1 ? boundsMax_.x : boundsMin_.x, i & 2 ? boundsMax_.y : boundsMin_.y,
                            i & 4 ? boundsMax_.z : boundsMin_.z);
    const double z = -(f.view * glm::dvec4(corner, 1.0)).z;
    zMin = std::min(zMin, z);
    zMax = std::max(zMax, z);
  }
  // The grey ramp starts at a third of the distance to the orbit target (log scale).
  f.zNear = std::max({zMin, v.nearDistance, glm::length(v.target - v.eye) / 3.0});
  f.zFar = std::max(zMax, f.zNear * 2);
  const double far = backend_->reversedZ() ? INFINITY : f.zFar * 1.5 + 1.0;
  f.camera = scenes::makeCamera(v, std::uint32_t(size.x), std::uint32_t(size.y), far, backend_->clipDepth(),
                                backend_->reversedZ());
  f.camera.metersToViewUnits = metersToViewUnits_;  // the depth is drawn in the scene's own units
  // What the camera frames for the window goes beside the panel (framing.h), the split views'
  // divider with it.
  const Strip strip = freeStrip(ui_.showUi && ui_.panelShown, ui_.panelX0, ui_.panelX1);
  frameInStrip(f.camera, strip);
  f.settings = ui_.settings;
  f.mode = ui_.mode;
  f.cszLevel = ui_.cszLevel;
  f.splitFraction = strip.x0 + ui_.split * (strip.x1 - strip.x0);
  f.errorScale = ui_.errorScale;
  f.measureTime = ui_.measureTime;
  f.referenceValid = reference_.matches(v, f.camera, radiusInSceneUnits());
  return f;
}

Status App::handleRequests(const FrameDesc& frame) {
  if (ui_.sceneChanged) {
    ui_.sceneChanged = false;
    if (Status s = loadScene(ui_.scene); !s) return s;
  }
  if (ui_.resetCamera) {
    ui_.resetCamera = false;
    camera_.reset(scene_.views[std::size_t(std::clamp(ui_.view, 0, int(scene_.views.size()) - 1))]);
  }
  if (ui_.computeReference || referenceRequested_) {
    ui_.computeReference = referenceRequested_ = false;
    std::printf("sao-viewer: tracing the reference (%d rays per pixel)...\n", ui_.referenceRays);
    std::fflush(stdout);
    if (Status s = reference_.compute(camera_.view(), frame.camera, radiusInSceneUnits(),
                                      std::uint32_t(ui_.referenceRays));
        !s)
      return s;
    std::printf("sao-viewer: reference done in %.2f s\n", reference_.seconds());
    haveMetrics_ = false;
    return backend_->setReference(&reference_.image());
  }
  return Status::success();
}

void App::updateMetrics(const FrameDesc& frame) {
  if (frame.mode != ViewMode::Error || !frame.referenceValid || !stats_.effect.ok()) return;
  if (haveMetrics_ && metricsSettings_ == frame.settings) return;
  FloatImage ao;
  if (Status s = backend_->readAo(ao); !s) {
    message_ = "cannot read the AO back: " + s.message;
    return;
  }
  metrics_ = reference_.compare(ao);
  metricsSettings_ = frame.settings;
  haveMetrics_ = true;
  std::printf("sao-viewer: error vs reference: RMSE %.4f, bias %+.4f\n", metrics_.raw.rmse, metrics_.raw.meanBias);
}

// sao-render's scale warnings (sao/samples/scale_warnings.h) for the view on screen: the AO read
// back and the depth ray cast for the frame's camera. On the first frame, then whenever the scene,
// the settings or the camera changed and held still for a frame (not while the camera moves).
void App::checkScale(const FrameDesc& frame) {
  if (!stats_.effect.ok()) return;
  const ScaleKey key{frame.camera, frame.settings, sceneGeneration_};
  const bool settled = !scaleChecked_ || (scalePrevious_ && *scalePrevious_ == key);
  scalePrevious_ = key;
  if ((scaleChecked_ && *scaleChecked_ == key) || !settled) return;
  scaleChecked_ = key;
  FloatImage ao;
  DepthImage depth;
  samples::ScaleCheck check;
  Status s = backend_->readAo(ao);
  if (s) s = reference_.castDepth(camera_.view(), frame.camera, depth);
  if (s) s = samples::checkScale(frame.settings, frame.camera, depth, ao, check);
  if (!s) {
    message_ = "scale check: " + s.message;
    return;
  }
  scaleWarnings_ = std::move(check.warnings);
  if (scaleWarnings_ == scalePrinted_) return;  // said already (the camera moved, nothing new)
  for (const std::string& w : scaleWarnings_) std::fprintf(stderr, "sao-viewer: warning: %s\n", w.c_str());
  scalePrinted_ = scaleWarnings_;
}

PanelInfo App::panelInfo() const {
  PanelInfo p;
  p.backend = backend_->description();
  p.frameMs = frameMs_;
  p.stats = haveStats_ ? &stats_ : nullptr;
  if (haveStats_) {
    Camera c = scenes::makeCamera(camera_.view(), stats_.plan.aoExtent.width, stats_.plan.aoExtent.height, INFINITY,
                                  ClipDepth::ZeroToOne, true);
    if (c.width > 0) p.fullBytes = fullAllocationBytes(c, {});
  }
  p.scene = &scene_;
  const scenes::View v = camera_.view();
  if (!reference_.available()) {
    p.referenceStatus = "no reference yet: press R (blocks for a few seconds)";
  } else {
    const Camera& c = lastCamera_;
    char text[160];
    if (reference_.matches(v, c, radiusInSceneUnits()))
      std::snprintf(text, sizeof text, "reference of this view: %u rays per pixel, %.2f s", reference_.rays(),
                    reference_.seconds());
    else
      std::snprintf(text, sizeof text, "the reference is stale (camera, size or radius changed): press R");
    p.referenceStatus = text;
    p.haveMetrics = haveMetrics_ && ui_.mode == ViewMode::Error && reference_.matches(v, c, radiusInSceneUnits());
  }
  p.metrics = metrics_;
  p.message = message_;
  p.scaleWarnings = &scaleWarnings_;
  return p;
}

int App::run() {
  if (Status s = start(); !s) {
    std::fprintf(stderr, "sao-viewer: %s: %s\n", toString(s.code), s.message.c_str());
    return 1;
  }
  std::printf("sao-viewer: %s\n", backend_->description().c_str());
  double last = glfwGetTime();
  std::uint32_t frames = 0;
  while (!window_->shouldClose()) {
    const auto frameStart = std::chrono::steady_clock::now();
    window_->pollEvents();
    const glm::ivec2 fb = window_->framebufferSize();
    if (fb.x <= 0 || fb.y <= 0) {
      window_->waitEvents();
      continue;
    }
    const double now = glfwGetTime(), dt = now - last;
    last = now;
    frameMs_ = frameMs_ == 0 ? dt * 1000 : frameMs_ * 0.9 + dt * 100;
    handleKeys();
    const ImGuiIO& io = ImGui::GetIO();
    camera_.update(io.WantCaptureMouse ? Input{} : window_->input(), *window_, !io.WantCaptureKeyboard, dt);
    if (options_.orbitStepDegrees != 0) camera_.orbitBy(options_.orbitStepDegrees * std::numbers::pi / 180.0);
    backend_->newImGuiFrame();
    ImGui::NewFrame();
    ui_.panelShown = false;  // drawPanel says where it is
    if (ui_.showUi) drawPanel(ui_, panelInfo(), camera_);
    drawOverlay(buildFrame(fb), ui_, haveStats_ ? &stats_ : nullptr);
    // A text field opened in this frame (Ctrl+click on a slider) has the keys typed from now on
    // (handleKeys); scripted sessions (tests/apps/viewer_keys.sh) wait for this line to type.
    if (!textField_ && GImGui->ActiveId != 0 && GImGui->ActiveId == GImGui->InputTextState.ID) {
      textField_ = true;
      std::printf("sao-viewer: a text field has the keyboard\n");
      std::fflush(stdout);
    }
    ImGui::Render();
    if (Status s = handleRequests(buildFrame(fb)); !s) {
      message_ = s.message;
      std::fprintf(stderr, "sao-viewer: %s\n", s.message.c_str());
    }
    FrameDesc frame = buildFrame(fb);
    frame.frameIndex = frames;
    const bool lastFrame = options_.frames > 0 && frames + 1 >= options_.frames;
    if (lastFrame && !options_.screenshot.empty()) frame.screenshotPath = options_.screenshot;
    if (ui_.screenshot) {
      ui_.screenshot = false;
      if (frame.screenshotPath.empty()) frame.screenshotPath = defaultScreenshotName();
    }
    if (Status s = backend_->renderFrame(frame, stats_); !s) {
      std::fprintf(stderr, "sao-viewer: %s: %s\n", toString(s.code), s.message.c_str());
      return 1;
    }
    haveStats_ = true;
    lastCamera_ = frame.camera;
    if (!frame.screenshotPath.empty()) {
      message_ = "saved " + frame.screenshotPath;
      std::printf("sao-viewer: screenshot %s\n", frame.screenshotPath.c_str());
      std::fflush(stdout);  // scripted sessions wait for it
    }
    updateMetrics(frame);
    checkScale(frame);
    if (++frames >= options_.frames && options_.frames > 0) break;
    // --min-frame-ms: a slow machine; keys pressed and released meanwhile wait in GLFW's queue.
    if (options_.minFrameMs > 0)
      std::this_thread::sleep_until(frameStart + std::chrono::milliseconds(options_.minFrameMs));
  }
  std::printf("sao-viewer: %u frames; effect: %s\n", frames, stats_.effect.ok() ? "ok" : stats_.effect.message.c_str());
  if (ui_.showUi && ui_.panelShown && ui_.topSectionsEndY >= 0)
    std::printf("sao-viewer: panel: the timings and the plan end at y %.0f of %.0f\n", ui_.topSectionsEndY,
                ui_.displayHeight);
  if (stats_.timings.method != TimingMethod::None)
    std::printf("sao-viewer: last frame %.3f ms in the effect (%s)\n", stats_.timings.totalMilliseconds(),
                toString(stats_.timings.method));
  if (!stats_.effect.ok()) return 1;
  if (const std::size_t n = backend_->validationErrors(); n > 0) {
    std::fprintf(stderr, "sao-viewer: the graphics API reported %zu error(s)\n", n);
    return 3;
  }
  return 0;
}

}  // namespace

int runViewer(const Options& options) { return App(options).run(); }

}  // namespace sao::viewer
