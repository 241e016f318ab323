#include "frames_section.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "sao/samples/metrics.h"

namespace sao::bench {

namespace {

struct Row {
  std::string scene, preset;
  int samples = 0, samples4x = 0;
  double oneFrame = NAN, meanOfFrames = NAN, fourTimesTaps = NAN, temporal = NAN;
};

std::string_view presetName(Preset preset) {
  for (const PresetInfo& p : presets())
    if (p.preset == preset) return p.name;
  return "?";
}

}  // namespace

Status framesSection(const FramesOptions& o, samples::BackendRunner& backend, SceneCache& cache) {
  std::vector<Row> rows;
  for (const std::string& name : o.scenes) {
    Prepared& p = cache.prepare(name, o.size.width, o.size.height);
    for (Preset preset : o.presets) {
      const Settings set = presetSettings(preset);
      const Converged& c = convergedReference(p, set, Extra::None, {o.convergedTaps, false, nullptr, nullptr});
      Row r{name, std::string(presetName(preset)), set.samples, std::min(4 * set.samples, 64)};
      auto error = [&](const FloatImage& ao) { return samples::compareToReference(ao, c.ao, p.mask).raw.rmse; };
      FloatImage mean;
      for (std::uint32_t k = 0; k < o.frames; ++k) {
        std::fprintf(stderr, "\r\033[Kframes: %s %s frame %u", name.c_str(), r.preset.c_str(), k);
        std::fflush(stderr);
        samples::RunInputs in = runInputs(p, Extra::None);
        in.frameIndex = k;
        samples::RunOutputs run;
        if (Status st = backend.run(set, p.camera, in, false, false, run); !st) return st;
        if (k == 0) {
          r.oneFrame = error(run.ao);
          mean = FloatImage(run.ao.extent, run.ao.channels);
        }
        for (std::size_t i = 0; i < mean.data.size(); ++i) mean.data[i] += run.ao.data[i] / float(o.frames);
      }
      r.meanOfFrames = error(mean);
      // The effect's own temporal accumulation (the temporal setting, its default hysteresis) over
      // the same frames: what an engine gets without averaging frames itself.
      Settings accumulating = set;
      accumulating.temporal = true;
      for (std::uint32_t k = 0; k < o.frames; ++k) {
        samples::RunInputs in = runInputs(p, Extra::None);
        in.frameIndex = k;
        in.resetHistory = k == 0;
        samples::RunOutputs run;
        if (Status st = backend.run(accumulating, p.camera, in, false, false, run); !st) return st;
        if (k + 1 == o.frames) r.temporal = error(run.ao);
      }
      Settings more = set;
      more.samples = r.samples4x;
      samples::RunOutputs run;
      if (Status st = backend.run(more, p.camera, runInputs(p, Extra::None), false, false, run); !st) return st;
      r.fourTimesTaps = error(run.ao);
      rows.push_back(r);
    }
  }
  std::fprintf(stderr, "\n");

  const std::string path = (std::filesystem::path(o.outDir) / "frames.csv").string();
  std::ofstream csv(path);
  if (!csv) return Status::error(StatusCode::IoError, "cannot write " + path);
  csv << "scene,preset,samples,frames,converged_rmse_one_frame,converged_rmse_mean_of_frames,samples_4x,"
         "converged_rmse_4x_taps,converged_rmse_temporal\n";
  for (const Row& r : rows)
    csv << r.scene << ',' << r.preset << ',' << r.samples << ',' << o.frames << ',' << r.oneFrame << ','
        << r.meanOfFrames << ',' << r.samples4x << ',' << r.fourTimesTaps << ',' << r.temporal << '\n';
  if (!csv.flush()) return Status::error(StatusCode::IoError, "cannot write " + path);

  std::printf("frames of a static camera (Inputs::frameIndex 0..%u averaged), RMSE vs (c) at %ux%u (frames.csv):\n",
              o.frames - 1, o.size.width, o.size.height);
  std::printf("  %-14s %-9s %7s %9s %9s %9s %12s\n", "scene", "preset", "samples", "1 frame", "mean", "temporal",
              "1 frame, 4x");
  int atOrBelow = 0, temporalAtOrBelow = 0;
  for (const Row& r : rows) {
    std::printf("  %-14s %-9s %7d %9.5f %9.5f %9.5f %9.5f (%d)\n", r.scene.c_str(), r.preset.c_str(), r.samples,
                r.oneFrame, r.meanOfFrames, r.temporal, r.fourTimesTaps, r.samples4x);
    atOrBelow += r.meanOfFrames <= r.fourTimesTaps;
    temporalAtOrBelow += r.temporal <= r.fourTimesTaps;
  }
  std::printf("  the mean of %u frames is at or below one frame with 4x the taps in %d of %zu (scene, preset) cases\n",
              o.frames, atOrBelow, rows.size());
  std::printf("  temporal accumulation (%u frames) is at or below one frame with 4x the taps in %d of %zu cases\n",
              o.frames, temporalAtOrBelow, rows.size());
  return Status::success();
}

}  // namespace sao::bench
