// sao-bench --sections calibrate: fits the appearance defaults (intensity, contrast, bias,
// epsilon) so that the medium preset matches reference (a), near-field AO, at the default radius.
// Renders a deterministic grid on every scene, keeps per scene the RMSE vs (a) and the best-fit
// occlusion scale, and picks the point of least mean RMSE whose scale is within 1 +- 0.1 on every
// scene. Then checks the fit at other radii and re-measures the winner and the defaults (error and
// time) at the confirmation size. Writes calibration.csv and prints the winner.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sao/samples/backend_runner.h"
#include "sao/status.h"
#include "scene_cache.h"

namespace sao::bench {

// The scale the fit must reach on every scene: |fitted_scale - 1| <= this.
inline constexpr double kCalibrationScaleTolerance = 0.1;

struct CalibrateOptions {
  std::string outDir;
  std::vector<std::string> scenes;
  Extent searchSize{640, 360};    // the grid
  Extent confirmSize{1280, 720};  // the winner and the defaults again, timed (skipped when equal)
  std::uint32_t rays = 256;       // reference (a) rays per pixel
  int runs = 5;                   // timed runs of the confirmation
  bool quick = false;             // a tiny grid, no radius check
};

// Runs on `backend` (the bench's first); the scenes come from `cache`.
Status calibrateSection(const CalibrateOptions& options, samples::BackendRunner& backend, SceneCache& cache);

}  // namespace sao::bench
