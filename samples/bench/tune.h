// sao-bench --tune: searches a fixed grid of the settings that trade time for error (samples, z
// hierarchy q', blur radius and stride, resolution_divisor) for the lowest error against reference
// (c), the converged estimator, or with --objective a against reference (a), over the built-in scenes, at time budgets relative to the medium
// preset measured in the same run; then chooses a chain of presets on that front. Resumable
// (tune.csv), deterministic in its errors; see docs/BENCHMARKS.md, "Tuning".
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "sao/plan.h"
#include "sao/scenes/scene.h"

namespace sao::bench {

struct TuneOptions {
  std::string out;
  std::string backends;     // comma-separated; the first that starts is used
  std::string depthSource;  // "raster" or "raytrace"
  std::optional<scenes::LengthUnit> units;
  Extent size{640, 360};
  std::uint32_t runs = 5, convergedTaps = 4096;
  // The error the front and the chain minimise: 0, reference (c) (the converged estimator: what the
  // knobs trade, the default); > 0, reference (a), ray-traced near-field AO with this many rays per
  // pixel (what users see: the model error included). The blotch, high-frequency and silhouette
  // figures stay against (c) either way: they measure the effect's own sampling artefacts.
  std::uint32_t objectiveRays = 0;
  bool quick = false;  // two small scenes and a tiny grid
};

// Writes tune.csv (appended as it goes), tune_front.csv, tune_front.svg and tune_presets.txt in
// options.out and prints the chosen presets. Returns the process exit status.
int runTune(const TuneOptions& options);

}  // namespace sao::bench
