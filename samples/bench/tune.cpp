#include "tune.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

#include "measure.h"
#include "scene_cache.h"
#include "tune_csv.h"
#include "tune_grid.h"
#include "tune_report.h"
#include "tune_select.h"
#include "visibility_converged.h"
#include "sao/prepass/prepass.h"

namespace sao::bench {
namespace {

namespace fs = std::filesystem;

constexpr std::size_t kAnchorEvery = 10;  // grid points between two measurements of medium
// Frames averaged into the visibility estimator's own converged value (visibility_converged.h):
// 32 frames of the candidate's 2 or 4 slices, 64 or 128 slice directions a pixel.
constexpr std::uint32_t kVisibilityFrames = 32, kVisibilityFramesQuick = 4;

std::string duration(double seconds) {
  char b[32];
  const long s = long(std::lround(seconds));
  if (s >= 3600) std::snprintf(b, sizeof b, "%ldh%02ldm", s / 3600, s / 60 % 60);
  else std::snprintf(b, sizeof b, "%ldm%02lds", s / 60, s % 60);
  return b;
}

std::string label(const Candidate& c) {
  if (c.kind == "grid") return settingsWords(c.settings);
  return c.kind + " " + c.name;
}

// The chain: five presets, one per budget; where no chain of five steps up on every scene, the
// longest shorter one over budgets spread from the cheapest to the dearest.
void choose(TuneResult& r) {
  for (std::size_t k = kTuneBudgets.size(); k >= 1 && r.chain.empty(); --k) {
    std::vector<std::size_t> pick;  // budget indices
    for (std::size_t i = 0; i < k; ++i)
      pick.push_back(k == 1 ? 2 : (i * (kTuneBudgets.size() - 1) + (k - 1) / 2) / (k - 1));
    std::vector<double> budgets, maxBlotch;
    for (std::size_t i : pick) {
      budgets.push_back(kTuneBudgets[i]);
      maxBlotch.push_back(i == kDefaultPreset ? r.blotchLimit : INFINITY);
    }
    r.chain = chooseChain(r.grid, budgets, maxBlotch);
    if (r.chain.empty()) continue;
    if (k < kTuneBudgets.size())
      std::fprintf(stderr, "sao-bench: --tune: no chain of %zu presets steps up on every scene; choosing %zu\n",
                   kTuneBudgets.size(), k);
    for (std::size_t i : pick) r.chainNames.push_back(kTuneNames[i]), r.chainBudgets.push_back(kTuneBudgets[i]);
  }
}

}  // namespace

int runTune(const TuneOptions& o) {
  std::error_code ec;
  fs::create_directories(o.out, ec);
  if (ec) fail("cannot create '" + o.out + "': " + ec.message());

  std::unique_ptr<samples::BackendRunner> backend;
  std::stringstream list(o.backends);
  for (std::string name; !backend && std::getline(list, name, ',');)
    if (Status s = samples::createBackend(name, backend); !s) {
      std::fprintf(stderr, "sao-bench: --tune: skipping backend %s: %s\n", name.c_str(), s.message.c_str());
      backend.reset();
    }
  if (!backend) fail("--tune: none of the backends '" + o.backends + "' could start");
  const std::string backendName(backend->name());

  std::unique_ptr<prepass::Prepass> depthPrepass;
  if (o.depthSource == "raster")
    if (Status s = prepass::createPrepass("auto", depthPrepass); !s) fail(s.message + " (--depth-source raytrace works without one)");

  const std::vector<std::string> sceneNames = benchScenes(o.quick);
  TuneCsv csv;
  const std::string csvPath = (fs::path(o.out) / "tune.csv").string();
  if (Status s = csv.open(csvPath, sceneNames, o.objectiveRays); !s) fail("--tune: " + s.message);

  // The untuned rows first (the untuned medium is the time unit), today's presets, the baseline,
  // then the grid with the untuned medium again after every kAnchorEvery points and at the end (the anchors).
  std::vector<Candidate> candidates = tuneReferences();
  const std::size_t referenceCount = candidates.size();
  std::vector<std::size_t> anchors{0};  // tuneReferences() starts with the untuned medium
  std::size_t gridCount = 0;
  for (Candidate& c : tuneGrid(o.quick)) {
    candidates.push_back(std::move(c));
    if (++gridCount % kAnchorEvery == 0) anchors.push_back(candidates.size()), candidates.push_back(timeAnchor(candidates.size()));
  }
  if (gridCount % kAnchorEvery) anchors.push_back(candidates.size()), candidates.push_back(timeAnchor(candidates.size()));
  const std::uint32_t visibilityFrames = o.quick ? kVisibilityFramesQuick : kVisibilityFrames;
  auto templateRow = [&](const Candidate& c) {
    TuneRow r;
    r.kind = c.kind, r.name = c.name, r.backend = backendName, r.depth = o.depthSource, r.inputs = inputsName(c.extra);
    r.size = o.size, r.convergedTaps = o.convergedTaps, r.objectiveRays = o.objectiveRays, r.settings = c.settings;
    r.ownConvergedFrames = c.settings.estimator == 1 ? visibilityFrames : 0;
    r.runs = o.runs;
    return r;
  };
  std::vector<const Candidate*> todo;
  for (const Candidate& c : candidates)
    if (!csv.find(templateRow(c).key())) todo.push_back(&c);
  std::fprintf(stderr, "sao-bench: --tune on %s, %ux%u, %zu scenes: %zu candidates, %zu in %s, %zu to evaluate\n",
               backend->description().c_str(), o.size.width, o.size.height, sceneNames.size(), candidates.size(),
               candidates.size() - todo.size(), csvPath.c_str(), todo.size());

  SceneCache cache(depthPrepass.get(), o.units);
  const Settings appearance{};  // (c) depends on radius, intensity, bias, epsilon, contrast only: the defaults
  const auto start = std::chrono::steady_clock::now();
  double referenceSeconds = 0;  // time spent on (c), left out of the eta
  // The visibility estimator's own converged values, per scene, inputs and settings of the run.
  std::map<std::string, FloatImage> visibilityConverged;
  for (std::size_t k = 0; k < todo.size(); ++k) {
    const Candidate& c = *todo[k];
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - referenceSeconds;
    const std::string eta = k ? "eta " + duration(elapsed / double(k) * double(todo.size() - k)) : "eta ?";
    std::fprintf(stderr, "\r\033[K[%zu/%zu] %s  %s", k + 1, todo.size(), label(c).c_str(), eta.c_str());
    std::fflush(stderr);
    TuneRow row = templateRow(c);
    for (const std::string& scene : sceneNames) {
      Prepared& p = cache.prepare(scene, o.size.width, o.size.height);
      const bool fresh = !p.converged.count({obscuranceKey(appearance), c.extra});
      Converged& converged = convergedReference(p, appearance, c.extra, {o.convergedTaps, false, nullptr, nullptr});
      if (fresh) {
        referenceSeconds += converged.seconds;
        std::fprintf(stderr, "\r\033[Ksao-bench: reference (c) for %s (%s): %.1f s\n", scene.c_str(), inputsName(c.extra),
                     converged.seconds);
      }
      References refs;
      refs.converged = &converged.ao, refs.mask = &p.mask, refs.silhouette = &p.silhouette;
      if (c.settings.estimator == 1) {  // its own converged value (visibility_converged.h), not (d)
        const std::string key = scene + "|" + inputsName(c.extra) + "|" + settingsWords(convergedVisibilitySettings(c.settings));
        auto it = visibilityConverged.find(key);
        if (it == visibilityConverged.end()) {
          const auto visStart = std::chrono::steady_clock::now();
          FloatImage ao;
          if (Status st = convergedVisibility(*backend, c.settings, p.camera, runInputs(p, c.extra), visibilityFrames, ao); !st)
            fail("--tune: the visibility estimator's converged value on " + scene + ": " + st.message);
          const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - visStart).count();
          referenceSeconds += seconds;
          std::fprintf(stderr, "\r\033[Ksao-bench: converged visibility for %s (%s, %s, %u frames): %.1f s\n",
                       scene.c_str(), inputsName(c.extra), describeThickness(c.settings).c_str(), visibilityFrames,
                       seconds);
          it = visibilityConverged.emplace(key, std::move(ao)).first;
        }
        refs.converged = &it->second;
      }
      if (o.objectiveRays) {
        const bool freshAo = !p.references.count(c.settings.radius);
        const auto aoStart = std::chrono::steady_clock::now();
        refs.nearFieldAo = &nearFieldReference(p, c.settings.radius, o.objectiveRays);
        if (freshAo) {
          const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - aoStart).count();
          referenceSeconds += seconds;
          std::fprintf(stderr, "\r\033[Ksao-bench: reference (a) for %s, %u rays: %.1f s\n", scene.c_str(),
                       o.objectiveRays, seconds);
        }
      }
      Measurement m;
      if (Status s = measure(*backend, c.settings, p.camera, runInputs(p, c.extra), int(o.runs), refs, m); !s)
        fail("--tune: " + label(c) + " on " + scene + ": " + s.message);
      SceneFigures g;
      g.ms = m.totalMs;
      g.rmse = o.objectiveRays ? m.aoError->raw.rmse : m.convergedError->raw.rmse;
      g.blotch = m.convergedStructure->blotchRmse;
      g.highFrequency = m.convergedStructure->highFrequencyRmse;
      g.silhouette = m.convergedStructure->silhouetteRmse;
      row.scenes.push_back(g);
    }
    if (Status s = csv.append(row); !s) fail("--tune: " + s.message);
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr, "%s", todo.empty() ? "" : "\n");

  // Everything below comes from tune.csv's rows, whether measured now or read back.
  TuneResult r;
  r.scenes = sceneNames, r.backend = backendName, r.depth = o.depthSource, r.size = o.size;
  r.objective = o.objectiveRays ? "a" : "c";
  std::vector<const TuneRow*> rows;
  for (const Candidate& c : candidates) rows.push_back(csv.find(templateRow(c).key()));
  r.medium = rows[anchors.front()];
  r.driftMin = r.driftMax = 1;
  for (std::size_t a : anchors) {
    for (const SceneFigures& s : rows[a]->scenes)
      if (!(s.ms > 0)) fail("--tune: no time for " + label(candidates[a]) + " in " + csvPath);
    r.driftMin = std::min(r.driftMin, rows[a]->totalMs() / r.medium->totalMs());
    r.driftMax = std::max(r.driftMax, rows[a]->totalMs() / r.medium->totalMs());
  }
  r.anchors = anchors.size();
  // Medium's time on scene s at candidate i: linear in the candidate index between the anchors
  // around it (the order the candidates are evaluated in).
  auto mediumAt = [&](std::size_t i, std::size_t s) {
    const auto after = std::lower_bound(anchors.begin(), anchors.end(), i);
    if (after == anchors.end()) return rows[anchors.back()]->scenes[s].ms;
    if (*after == i || after == anchors.begin()) return rows[*after]->scenes[s].ms;
    const std::size_t a = *(after - 1), b = *after;
    const double w = double(i - a) / double(b - a);
    return (1 - w) * rows[a]->scenes[s].ms + w * rows[b]->scenes[s].ms;
  };
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].kind == "anchor") continue;
    TunePoint p{rows[i], 0, rows[i]->meanRmse(), {}};
    double unit = 0;
    for (std::size_t s = 0; s < sceneNames.size(); ++s) {
      unit += mediumAt(i, s);
      p.sceneX.push_back(rows[i]->scenes[s].ms / mediumAt(i, s));
    }
    p.timeX = rows[i]->totalMs() / unit;
    if (!(p.timeX > 0 && p.meanRmse > 0 && std::isfinite(p.meanRmse)))
      fail("--tune: " + label(candidates[i]) + " has no usable time or error in " + csvPath);
    (i < referenceCount ? r.references : r.grid).push_back(p);
  }
  r.front = paretoFront(r.grid);
  r.blotchLimit = kDefaultBlotchShare * rows[1]->meanBlotch();  // rows[1]: the untuned defaults
  choose(r);
  const std::vector<std::string> files = writeTuneOutputs(o.out, r);

  std::printf("sao-bench --tune: %s, %ux%u, %zu scenes, %zu candidates (%zu evaluated now in %s, the rest read from "
              "tune.csv), reference (c) with %u taps%s\n",
              backend->description().c_str(), o.size.width, o.size.height, sceneNames.size(), candidates.size(), todo.size(),
              duration(wall).c_str(), o.convergedTaps,
              o.objectiveRays ? (", the error vs reference (a) with " + std::to_string(o.objectiveRays) + " rays").c_str() : "");
  for (const TunePoint& p : r.grid)
    if (p.row->settings == r.medium->settings)  // the grid's copy of medium, timed against the anchors around it
      std::printf("the grid's copy of the untuned medium: %.3gx (1 but for noise)\n", p.timeX);
  printTuneSummary(r);
  std::string names;
  for (const std::string& f : files) names += (names.empty() ? "" : ",") + f;
  std::printf("wrote %s/{%s}\n", fs::absolute(o.out).lexically_normal().string().c_str(), names.c_str());
  return 0;
}

}  // namespace sao::bench
