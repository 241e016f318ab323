#include "frames.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <vector>

#include "sao/io.h"
#include "sao/samples/flicker.h"
#include "sao/scenes/scene.h"

namespace sao::render {

std::string FramesSummary::text() const {
  char line[256];
  std::snprintf(line, sizeof line,
                "frames: %u along the %s path; flicker (mean |A_t - A_t-1| on the same surface after reprojection) "
                "%.5f over %.1f %% of the geometry pixels; effect %.3f ms per frame (median)\n",
                frames, path.c_str(), meanFlicker, 100.0 * comparedFraction,
                medianEffectMs);
  return line;
}

Status runFramePath(const Options& o, samples::BackendRunner& backend, const Settings& settings,
                    const scenes::View& base, const Camera& camera, const DepthMaker& makeDepth,
                    samples::OutputFolder& out, FramesSummary& summary, raytrace::Primary& last) {
  summary = FramesSummary{};
  summary.frames = o.frames;
  summary.path = std::string(scenes::toString(o.path));
  std::string csvPath;
  if (Status s = out.file("frames.csv", csvPath); !s) return s;
  std::ofstream csv(csvPath, std::ios::binary);
  csv << "frame,eye_x,eye_y,eye_z,target_x,target_y,target_z,effect_ms,flicker,compared_pixels,geometry_pixels\n";
  raytrace::Primary previous;
  FloatImage previousAo;
  glm::dmat4 previousView{1.0};
  std::vector<double> times;
  samples::FlickerTotal total;
  for (std::uint32_t f = 0; f < o.frames; ++f) {
    const scenes::View view = scenes::pathView(base, o.path, f, o.frames);
    raytrace::Primary primary;
    if (Status s = makeDepth(view, primary); !s) return s;
    // The frame's pose (temporal accumulation reprojects its history through it) and, with
    // temporal accumulation, the frame's spiral: frames then sample different taps.
    const glm::dmat4 worldToCamera = scenes::viewMatrix(view);
    Camera frameCamera = camera;
    frameCamera.view = scenes::viewArray(view);
    samples::RunInputs inputs{&primary.depth, nullptr, nullptr};
    inputs.frameIndex = settings.temporal ? f : 0;
    inputs.resetHistory = f == 0;  // the path starts a history of its own
    samples::RunOutputs result;
    if (Status s = backend.run(settings, frameCamera, inputs, true, false, result); !s) return s;
    times.push_back(result.timings.totalMilliseconds());
    char name[32];
    std::snprintf(name, sizeof name, "frames/ao_%04u.png", f);
    std::string png;
    if (Status s = out.file(name, png); !s) return s;
    if (Status s = writeAoPng(png, result.ao); !s) return s;
    samples::Flicker flicker;
    if (f > 0) {
      flicker = samples::reprojectedFlicker({&previousAo, &previous.position, previousView},
                                            {&result.ao, &primary.position, worldToCamera}, camera);
      total.add(flicker);
    }
    char row[512];
    std::snprintf(row, sizeof row, "%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.4f,%s,%llu,%llu\n", f, view.eye.x, view.eye.y,
                  view.eye.z, view.target.x, view.target.y, view.target.z, times.back(),
                  f > 0 ? std::to_string(flicker.meanAbsDifference).c_str() : "", (unsigned long long)flicker.compared,
                  (unsigned long long)flicker.geometry);
    csv << row;
    previous = std::move(primary);
    previousAo = std::move(result.ao);
    previousView = worldToCamera;
  }
  csv.close();
  if (!csv) return Status::error(StatusCode::IoError, "cannot write '" + csvPath + "'");
  std::sort(times.begin(), times.end());
  summary.medianEffectMs = times[times.size() / 2];
  summary.meanFlicker = total.mean();
  summary.comparedFraction = total.comparedFraction();
  last = std::move(previous);
  return Status::success();
}

}  // namespace sao::render
