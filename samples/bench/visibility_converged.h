// sao-bench --tune: the visibility estimator's own converged value, what its z hierarchy,
// resolution, blur and single frame trade, as reference (c) is for the paper's estimator. Reference
// (d) is its definition's limit, not its sampling's: the estimator's joins, 32 bits a slice and
// per-tap thickness differ from (d)'s march by a smooth bias (sponza-like 0.039 RMSE at the high
// preset's sampling) that a blotch figure against (d) counted as blotchiness. The estimator's value
// also moves with its taps on a slice side, so the converged value keeps the candidate's samples
// and slices: a blotch figure against 64 taps counted that move too (0.017-0.034 at 16-32 taps).
#pragma once
#include <cstdint>

#include "sao/camera.h"
#include "sao/image.h"
#include "sao/samples/backend_runner.h"
#include "sao/settings.h"
#include "sao/status.h"

namespace sao::bench {

// The candidate's visibility settings (estimator 1; its samples, slices, thickness, thickness
// model, radius and appearance) with every tap at level 0 (no z hierarchy: (c) has none either),
// full resolution, no blur, no temporal accumulation, averaged over `frames` frames (frame indices
// 0 .. frames - 1: each turns the slices and moves the radial jitter) into `out` (1 channel).
Status convergedVisibility(samples::BackendRunner& backend, const Settings& candidate, const Camera& camera,
                           const samples::RunInputs& inputs, std::uint32_t frames, FloatImage& out);

// The settings of one frame of it (frame index aside).
Settings convergedVisibilitySettings(const Settings& candidate);

}  // namespace sao::bench
