// Types shared by the viewer's parts: the view modes, the composite's parameter block and what
// one frame asks of a backend and gets back.
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

#include "sao/camera.h"
#include "sao/plan.h"
#include "sao/settings.h"
#include "sao/status.h"
#include "sao/timing.h"

namespace sao::viewer {

// The order matches the constants in shaders/composite.frag.
enum class ViewMode : std::int32_t { Ao, Lit, LitNoAo, Split, RawAo, ZMip, Normals, Error, SplitResolution };

struct ViewModeInfo {
  ViewMode mode;
  std::string_view name;   // for --view-mode
  std::string_view label;  // for the panel
};
std::span<const ViewModeInfo> viewModes();
std::optional<ViewMode> findViewMode(std::string_view name);
std::string viewModeNames();  // "ao, lit, ..." for messages

// The std140 block of composite.frag (binding 0), the same for OpenGL and Vulkan.
struct CompositeParams {
  float projInfo[4];
  float depthModel[4];
  float worldUp[4];
  float display[4];
  std::int32_t modes[4];
  std::int32_t extra[4];
  std::int32_t projection[4];  // x: 1 for an orthographic camera (z and x, y linear in the texel)
  std::int32_t legend[4];      // the error view's colour bar: x0, y0, x1, y1 (errorLegend())
};
static_assert(sizeof(CompositeParams) == 128);

// The error view's colour bar, in framebuffer pixels from the bottom-left corner: [x0, x1) x
// [y0, y1), near the bottom-right corner (the panel is on the left). The composite fills it with
// the heat map's colours from 0 (bottom) to the error at full heat (top); the overlay labels it.
struct LegendRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
LegendRect errorLegend(int framebufferWidth, int framebufferHeight);

// What the viewer shows this frame, independent of the backend.
struct FrameDesc {
  Camera camera;               // the projection and conventions the prepass renders with
  glm::dmat4 view{1.0};        // world -> camera
  Settings settings;           // always valid (the panel only stores validated values)
  ViewMode mode = ViewMode::Lit;
  int cszLevel = 0;
  double splitFraction = 0.5;  // split view: x of the divider, share of the width
  double errorScale = 0.5;     // |AO - reference| shown at full heat
  double zNear = 0.1, zFar = 100;  // distances mapped to white and black in the csz view
  bool referenceValid = false;     // the backend's reference image belongs to this view
  bool measureTime = true;
  // Counts frames up: the effect's Inputs::frameIndex, so that with the temporal setting the frames
  // sample different taps and accumulate while the camera moves (the camera carries its pose).
  std::uint32_t frameIndex = 0;
  std::string screenshotPath;      // non-empty: save the window (with the panel) after this frame
};

// The split-resolution view: the AO at resolution_divisor 1 left of the divider, at a reduced
// divisor right of it. The backend runs a second effect with `compareSettings(frame.settings)`
// only in that mode; the panel's own divisor picks the reduced one (2 when it is 1).
Settings compareSettings(const Settings& settings);
int reducedDivisor(const Settings& settings);  // the right half's divisor

// The second effect of the split-resolution view (FrameStats::compare).
struct CompareStats {
  bool active = false;   // the mode was on and the second effect ran (or tried to)
  Status effect;
  Timings timings;
  std::string timingNote;
};

struct FrameStats {
  Status effect;         // what the effect said this frame
  Plan plan;             // of the last successful run
  Timings timings;       // per-pass times, method None when not measured or not ready
  std::string timingNote;
  CompareStats compare;  // split-resolution view only
};

// The composite's block for a frame. `topDown`: the framebuffer's row 0 is the top of the window
// (Vulkan); `rawAo` / `cszLevels` describe the intermediates the backend could bind.
CompositeParams makeCompositeParams(const FrameDesc& frame, bool topDown, bool rawAo, std::uint32_t cszLevels);

}  // namespace sao::viewer
