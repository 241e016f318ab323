#include "spiral_section.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "sao/presets.h"
#include "sao/samples/metrics.h"
#include "sao/spiral.h"

namespace sao::bench {

namespace {

// tau and s - tau give mirror-image lattices: the same pattern reflected, not a different choice.
bool sameLattice(int s, int a, int b) { return a % s == b % s || (a + b) % s == 0; }

struct Row {
  std::string scene;
  int samples = 0, blurRadius = 0, tau = 0;
  const char* source = "";
  double rmse = NAN;
};

}  // namespace

Status spiralSection(const SpiralOptions& o, samples::BackendRunner& backend, SceneCache& cache) {
  const Settings medium = presetSettings(Preset::Medium);
  std::vector<Row> rows;
  std::vector<int> counts = o.sampleCounts;
  if (counts.empty())
    for (int s = 1; s <= 64; ++s) counts.push_back(s);
  for (int s : counts) {
    const int lattice = latticeSpiralTurns(s), g3d = spiralTurns(s);
    if (sameLattice(s, lattice, g3d)) continue;
    for (const std::string& name : o.scenes) {
      Prepared& p = cache.prepare(name, o.size.width, o.size.height);
      const Converged& c = convergedReference(p, medium, Extra::None, {o.convergedTaps, false, nullptr, nullptr});
      for (int blur : {0, int(medium.blur_radius)})
        for (const auto& [tau, source] : {std::pair{lattice, "lattice"}, std::pair{g3d, "g3d"}}) {
          std::fprintf(stderr, "\r\033[Kspiral: %s s %d blur %d tau %d (%s)", name.c_str(), s, blur, tau, source);
          std::fflush(stderr);
          Settings set = medium;
          set.samples = s;
          set.spiral_turns = tau;
          set.blur_radius = blur;
          samples::RunOutputs run;
          if (Status st = backend.run(set, p.camera, runInputs(p, Extra::None), false, false, run); !st) return st;
          rows.push_back({name, s, blur, tau, source, samples::compareToReference(run.ao, c.ao, p.mask).raw.rmse});
        }
    }
  }
  std::fprintf(stderr, "\n");

  const std::string path = (std::filesystem::path(o.outDir) / "spiral.csv").string();
  std::ofstream csv(path);
  if (!csv) return Status::error(StatusCode::IoError, "cannot write " + path);
  csv << "scene,samples,blur_radius,spiral_turns,source,converged_rmse_raw\n";
  for (const Row& r : rows)
    csv << r.scene << ',' << r.samples << ',' << r.blurRadius << ',' << r.tau << ',' << r.source << ','
        << r.rmse << '\n';
  if (!csv.flush()) return Status::error(StatusCode::IoError, "cannot write " + path);

  // Mean over the scenes per (samples, blur): the lattice against G3D's, and how often each is lower.
  std::printf("spiral turns, the lattice criterion vs G3D's table (shipped), RMSE vs (c) at %ux%u, mean over %zu scenes (spiral.csv):\n", o.size.width,
              o.size.height, o.scenes.size());
  std::printf("  %7s %4s %11s %9s %9s %9s\n", "samples", "blur", "tau lattice", "tau g3d", "lattice", "g3d");
  int latticeLower = 0, g3dLower = 0;
  double latticeSum = 0, g3dSum = 0;
  int groups = 0;
  // Per sample count, per scene, four rows: blur 0 lattice, blur 0 G3D, blur R lattice, blur R G3D.
  const std::size_t group = 4 * o.scenes.size();
  for (std::size_t first = 0; group > 0 && first + group <= rows.size(); first += group)
    for (std::size_t b = 0; b < 2; ++b) {
      double so = 0, sg = 0;
      for (std::size_t k = first + 2 * b; k < first + group; k += 4) {
        so += rows[k].rmse, sg += rows[k + 1].rmse;
        (rows[k].rmse <= rows[k + 1].rmse ? latticeLower : g3dLower)++;
      }
      const double n = double(o.scenes.size());
      latticeSum += so / n, g3dSum += sg / n, ++groups;
      const Row& r = rows[first + 2 * b];
      std::printf("  %7d %4d %11d %9d %9.5f %9.5f\n", r.samples, r.blurRadius, r.tau, rows[first + 2 * b + 1].tau, so / n,
                  sg / n);
    }
  std::printf("  lower RMSE: lattice in %d, G3D's in %d of %d (scene, samples, blur) cases; mean RMSE %.5f vs %.5f\n",
              latticeLower, g3dLower, latticeLower + g3dLower, groups ? latticeSum / groups : NAN, groups ? g3dSum / groups : NAN);
  return Status::success();
}

}  // namespace sao::bench
