// The run's summary: what ran, how long each pass took, the plan's memory, and the error against
// the reference when one was computed.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "sao/image.h"
#include "sao/plan.h"
#include "sao/samples/metrics.h"
#include "sao/samples/scale_warnings.h"
#include "run_timing.h"
#include "sao/settings.h"

namespace sao::render {

// sao-render --frames: the camera path's figures (frames.h).
struct FramesSummary {
  std::uint32_t frames = 0;
  std::string path;
  double meanFlicker = 0;       // mean |A_t - A_{t-1}| over frames 1..N-1, weighted by their compared pixels
  double comparedFraction = 0;  // compared pixels / pixels with geometry, frames 1..N-1
  double medianEffectMs = 0;    // the effect's total time per frame (one run each)
  std::string text() const;     // one summary line
};

}  // namespace sao::render

namespace sao::samples {

struct Summary {
  std::string backend, input;
  std::string projection;  // "perspective, fovy 60 degrees, ..." or "orthographic, view height 4 ..."
  Extent size;
  std::uint32_t guard = 0;
  Settings settings;
  Plan plan;
  render::RunTiming timing;  // median and spread over the measured runs
  double prepareSeconds = 0;
  std::optional<ReferenceComparison> metrics;
  std::uint32_t referenceRays = 0;
  std::string units;  // how the scene's units were chosen (scenes::UnitChoice::note)
  double metersToViewUnits = 1.0;
  std::optional<ScaleCheck> scale;  // the radius against the scene's scale, and its warnings
  std::vector<std::string> inputWarnings;  // from loading the input (e.g. degenerate triangles left out)
  std::optional<render::FramesSummary> frames;  // --frames

  std::string text() const;
  // Through nlohmann-json: any path is a valid string, and an undefined metric (NaN, see
  // sao/samples/metrics.h) is null, since JSON has no NaN.
  std::string json() const;
};

}  // namespace sao::samples
