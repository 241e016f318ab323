// sao-bench --sections spiral: the two spiral-turn choices (sao/spiral.h, docs/effect-math.md 2.4),
// our lattice criterion (latticeSpiralTurns) against G3D's minimum-discrepancy table (spiralTurns,
// the one shipped since this comparison), by error against reference (c), the converged estimator.
// For every sample count of the list where the two choices give different tap lattices (not the
// same tau, nor its mirror image s - tau), runs the medium settings with that sample count and
// each tau on every bench scene, without blur (the pattern's own error) and with medium's blur.
// Writes spiral.csv and prints the mean RMSE per sample count and the overall verdict. About 5
// minutes at 640x360 here: asked for by name only (--sections spiral).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sao/samples/backend_runner.h"
#include "sao/status.h"
#include "scene_cache.h"

namespace sao::bench {

struct SpiralOptions {
  std::string outDir;
  std::vector<std::string> scenes;
  Extent size{640, 360};
  std::uint32_t convergedTaps = 4096;
  std::vector<int> sampleCounts;  // empty: every s of the samples setting's range, 1..64
};

Status spiralSection(const SpiralOptions& options, samples::BackendRunner& backend, SceneCache& cache);

}  // namespace sao::bench
