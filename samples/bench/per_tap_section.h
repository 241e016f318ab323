// sao-bench --sections per_tap: where ao_sample's per-tap cost goes on this GL driver (issue
// [bandwidth]: on llvmpipe ao_sample at 7 taps costs 2.2-3.3x a minimal fragment SAO pass).
// On the main scene, at s = 7, 16, 32, 48 taps: the gl backend's ao_sample time (medium preset,
// no blur, full resolution, where the pass is ao_sample_output: ao_sample storing A into the
// output; normals supplied and rebuilt), and beside it a ladder of minimal passes
// of our own (per_tap_shaders.h) reading the effect's own csz chain: (a) a fragment pass with
// texelFetch, (b) the same as compute, then (b) plus ao_sample's features, one each and combined.
// The time per tap is the least-squares slope of the median time against s (ns per pixel per tap),
// the fixed cost its intercept. Writes per_tap.csv, prints the slopes and their ratios to (a) and (b), and the
// mean A of the rungs beside the effect's (a rung whose output is all 0, all 1 or NaN over the
// geometry is a broken shader: the section fails). GL only; asked for by name only.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sao/samples/backend_runner.h"
#include "sao/status.h"
#include "scene_cache.h"

namespace sao::bench {

struct PerTapOptions {
  std::string outDir;
  std::string scene;
  Extent size{1920, 1080};
  int runs = 3;
  std::vector<int> sampleCounts{7, 16, 32, 48};
};

// `gl`: the gl backend if the run started it, else null (the section starts one, or prints why it
// skips: not built into this sao-bench, or it does not start).
Status perTapSection(const PerTapOptions& options, samples::BackendRunner* gl, SceneCache& cache);

}  // namespace sao::bench
