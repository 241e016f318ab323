// sao-bench --sections frames: what a static camera's frames buy when the engine accumulates them
// (Inputs::frameIndex, sao::frameSpiral; issue [temporal]): for the low, medium and high presets on
// every bench scene, the error against reference (c) of one frame (frame 0), of the mean of N
// frames (frame indices 0..N-1, each at the preset's own cost), and of one frame with 4x the taps
// (at most 64). [temporal]'s static target: after 16 frames, at or below one frame with 4x the taps.
// The mean is a plain average (an engine's exponential history converges to the same, more
// slowly); no reprojection is needed for a camera that holds still. Writes frames.csv and prints
// the means over the scenes and the verdict. Asked for by name only (--sections frames).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sao/presets.h"
#include "sao/samples/backend_runner.h"
#include "sao/status.h"
#include "scene_cache.h"

namespace sao::bench {

struct FramesOptions {
  std::string outDir;
  std::vector<std::string> scenes;
  Extent size{640, 360};
  std::uint32_t convergedTaps = 4096;
  std::uint32_t frames = 16;
  std::vector<Preset> presets{Preset::Low, Preset::Medium, Preset::High};
};

Status framesSection(const FramesOptions& options, samples::BackendRunner& backend, SceneCache& cache);

}  // namespace sao::bench
