// sao-render --frames N --path P: the scene's view moved along a camera path (scenes::pathView),
// each frame's depth rendered and the effect run on it, every frame's AO written as
// frames/ao_NNNN.png and a line per frame in frames.csv: the eye, the effect's time and the flicker
// against the frame before (samples::reprojectedFlicker, mean |A_t - A_{t-1}| on the same surface).
// The frames keep the camera's projection, so the effect plans once.
#pragma once
#include <cstdint>
#include <functional>
#include <string>

#include "options.h"
#include "sao/raytrace/raytrace.h"
#include "sao/samples/backend_runner.h"
#include "sao/samples/output_files.h"
#include "sao/scenes/camera_path.h"
#include "summary.h"

namespace sao::render {

// Renders one view's depth, positions and normals with the run's depth source.
using DepthMaker = std::function<Status(const scenes::View& view, raytrace::Primary& out)>;

// Reserves frames.csv and frames/ao_NNNN.png in `out`, runs every frame and writes them. Each
// frame's camera carries its pose (Camera::view). Without the temporal setting the effect's frame
// index stays 0: the spiral is the same in every frame, so the flicker is the camera's motion's
// alone; with it the frame index counts up and the first frame starts the history.
// `last` receives the last frame's depth, positions and normals, so that the run's usual outputs
// (ao.png, lit.png, the reference) are made from it without rendering it again.
Status runFramePath(const Options& o, samples::BackendRunner& backend, const Settings& settings,
                    const scenes::View& base, const Camera& camera, const DepthMaker& makeDepth,
                    samples::OutputFolder& out, FramesSummary& summary, raytrace::Primary& last);

}  // namespace sao::render
