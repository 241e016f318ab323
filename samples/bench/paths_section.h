// sao-bench --sections paths: what the camera paths (sao/scenes/camera_path.h) do to the AO, with
// and without the effect's temporal accumulation: for every bench scene and every path (orbit,
// dolly, strafe), N frames with the temporal setting off (frame index 0 in every frame, the same
// spiral) and on (the frame index counting up, the history starting at the path's first frame),
// each frame's depth ray-cast from the path's view. Reports the flicker (samples::reprojectedFlicker:
// mean |A_t - A_t-1| on the same surface after reprojection), the share of geometry pixels compared
// and the median effect time per frame; writes paths.csv and prints the on/off flicker ratios and
// the verdict against [temporal]'s target (at most half). Asked for by name only (--sections paths).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "sao/presets.h"
#include "sao/samples/backend_runner.h"
#include "sao/status.h"
#include "scene_cache.h"

namespace sao::bench {

struct PathsOptions {
  std::string outDir;
  std::vector<std::string> scenes;
  Extent size{320, 180};
  std::uint32_t frames = 60;
  Preset preset = Preset::Medium;
};

Status pathsSection(const PathsOptions& options, samples::BackendRunner& backend, SceneCache& cache);

}  // namespace sao::bench
