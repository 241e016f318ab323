#include "paths_section.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "sao/raytrace/raytrace.h"
#include "sao/samples/flicker.h"
#include "sao/scenes/camera_path.h"

namespace sao::bench {

namespace {

struct PathRow {
  std::string scene, path;
  bool temporal = false;
  double flicker = 0, compared = 0, medianMs = 0;
};

// One path run: every frame's depth ray-cast from the path's view, the effect on it, the flicker
// against the frame before.
Status runPath(const PathsOptions& o, samples::BackendRunner& backend, Prepared& p, scenes::PathKind kind,
               bool temporal, PathRow& row) {
  Settings settings = presetSettings(o.preset);
  settings.temporal = temporal;
  raytrace::Primary previous;
  FloatImage previousAo;
  glm::dmat4 previousView{1.0};
  std::vector<double> times;
  samples::FlickerTotal total;
  for (std::uint32_t f = 0; f < o.frames; ++f) {
    const scenes::View view = scenes::pathView(p.scene.views[0], kind, f, o.frames);
    // The scene is in its own units, the view units: the depth is cast with a factor of 1.
    Camera depthCamera = p.camera;
    depthCamera.metersToViewUnits = 1.0;
    raytrace::Primary primary;
    if (Status s = raytrace::castPrimary(*p.rays, view, depthCamera, DepthFormat::D32F, primary); !s) return s;
    Camera camera = p.camera;
    camera.view = scenes::viewArray(view);
    samples::RunInputs in{&primary.depth, nullptr, nullptr};
    in.frameIndex = temporal ? f : 0;
    in.resetHistory = f == 0;
    samples::RunOutputs run;
    if (Status s = backend.run(settings, camera, in, true, false, run); !s) return s;
    times.push_back(run.timings.totalMilliseconds());
    const glm::dmat4 worldToCamera = scenes::viewMatrix(view);
    if (f > 0)
      total.add(samples::reprojectedFlicker({&previousAo, &previous.position, previousView},
                                            {&run.ao, &primary.position, worldToCamera}, camera));
    previous = std::move(primary);
    previousAo = std::move(run.ao);
    previousView = worldToCamera;
  }
  std::sort(times.begin(), times.end());
  row.flicker = total.mean();
  row.compared = total.comparedFraction();
  row.medianMs = times[times.size() / 2];
  return Status::success();
}

}  // namespace

Status pathsSection(const PathsOptions& o, samples::BackendRunner& backend, SceneCache& cache) {
  if (o.frames < 2) return Status::error(StatusCode::InvalidInput, "paths: a path needs at least 2 frames");
  std::vector<PathRow> rows;
  for (const std::string& name : o.scenes) {
    Prepared& p = cache.prepare(name, o.size.width, o.size.height);
    for (const std::string_view pathName : scenes::pathNames()) {
      const scenes::PathKind kind = *scenes::parsePathKind(pathName);
      for (bool temporal : {false, true}) {
        std::fprintf(stderr, "\r\033[Kpaths: %s %.*s temporal=%d", name.c_str(), int(pathName.size()), pathName.data(),
                     int(temporal));
        std::fflush(stderr);
        PathRow r{name, std::string(pathName), temporal};
        if (Status s = runPath(o, backend, p, kind, temporal, r); !s) return s;
        rows.push_back(r);
      }
    }
  }
  std::fprintf(stderr, "\n");

  const std::string path = (std::filesystem::path(o.outDir) / "paths.csv").string();
  std::ofstream csv(path);
  if (!csv) return Status::error(StatusCode::IoError, "cannot write " + path);
  csv << "scene,path,temporal,frames,flicker,compared_fraction,median_effect_ms\n";
  for (const PathRow& r : rows)
    csv << r.scene << ',' << r.path << ',' << (r.temporal ? 1 : 0) << ',' << o.frames << ',' << r.flicker << ','
        << r.compared << ',' << r.medianMs << '\n';
  if (!csv.flush()) return Status::error(StatusCode::IoError, "cannot write " + path);

  std::printf("camera paths, %u frames at %ux%u on %.*s (paths.csv): flicker without -> with temporal accumulation\n",
              o.frames, o.size.width, o.size.height, int(backend.name().size()), backend.name().data());
  int halved = 0, pairs = 0;
  for (std::size_t i = 0; i + 1 < rows.size(); i += 2) {
    const PathRow& off = rows[i];
    const PathRow& on = rows[i + 1];
    const double ratio = off.flicker > 0 ? on.flicker / off.flicker : 0.0;
    std::printf("  %-14s %-7s %.5f -> %.5f (%.2fx), %.1f %% compared, %.2f -> %.2f ms\n", off.scene.c_str(),
                off.path.c_str(), off.flicker, on.flicker, ratio, 100.0 * on.compared, off.medianMs, on.medianMs);
    ++pairs;
    halved += on.flicker <= 0.5 * off.flicker;
  }
  std::printf("  temporal accumulation at most halves the flicker in %d of %d (scene, path) cases\n", halved, pairs);
  return Status::success();
}

}  // namespace sao::bench
