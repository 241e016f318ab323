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
#include "tune_time.h"
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

// The candidates measured in this session: those with no row, and the time anchors just before and
// after each of them (in candidate order), since a row is timed against its own session's anchors
// only (tune_time.h). The untuned medium, the unit's reference row, is measured if it has no row.
std::vector<bool> toMeasure(const std::vector<std::vector<const TuneRow*>>& recorded, const std::vector<std::size_t>& anchors) {
  std::vector<bool> measure(recorded.size(), false);
  for (std::size_t i = 0; i < recorded.size(); ++i) {
    if (!recorded[i].empty() || std::binary_search(anchors.begin(), anchors.end(), i)) continue;
    measure[i] = true;
    const auto after = std::upper_bound(anchors.begin(), anchors.end(), i);  // anchors[0] = 0 < i
    measure[*(after - 1)] = true;
    if (after != anchors.end()) measure[*after] = true;
  }
  if (recorded[0].empty()) measure[0] = true;
  return measure;
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
    r.runs = o.runs, r.session = csv.session();
    return r;
  };
  auto isAnchor = [&](std::size_t i) { return std::binary_search(anchors.begin(), anchors.end(), i); };
  // tune.csv's rows by candidate: at most one for most, one per session for the time anchors (rows
  // of candidates not in today's list, such as presets since changed, are left out).
  std::map<std::string, std::size_t> candidateAt;  // TuneRow::columns() -> candidate index
  for (std::size_t i = 0; i < candidates.size(); ++i) candidateAt.emplace(templateRow(candidates[i]).columns(), i);
  auto recordedRows = [&] {
    std::vector<std::vector<const TuneRow*>> recorded(candidates.size());
    for (const TuneRow& row : csv.rows()) {
      const auto at = candidateAt.find(row.columns());
      if (at != candidateAt.end() && csv.find(row.key()) == &row) recorded[at->second].push_back(&row);
    }
    return recorded;
  };
  std::size_t inRecord = 0, anchorsNow = 0;
  std::vector<const Candidate*> todo;  // in candidate order, so that the anchors bracket what they time
  {
    const auto recorded = recordedRows();
    const std::vector<bool> measure = toMeasure(recorded, anchors);
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      inRecord += !recorded[i].empty();
      if (measure[i]) todo.push_back(&candidates[i]), anchorsNow += isAnchor(i);
    }
  }
  std::fprintf(stderr, "sao-bench: --tune on %s, %ux%u, %zu scenes: %zu candidates, %zu in %s, %zu to evaluate\n",
               backend->description().c_str(), o.size.width, o.size.height, sceneNames.size(), candidates.size(), inRecord,
               csvPath.c_str(), todo.size());
  if (!todo.empty() && csv.session() > 1)
    std::fprintf(stderr, "sao-bench: --tune: session %u of tune.csv: %zu of those are measurements of the untuned medium "
                 "(time anchors) around the %zu others, which are timed against this session's anchors only\n",
                 csv.session(), anchorsNow, todo.size() - anchorsNow);

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
  const auto recorded = recordedRows();  // again: rows_ has grown, and its earlier pointers are stale
  std::vector<TimedRow> timed;
  std::vector<const TuneRow*> timedRows;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (recorded[i].empty() && !isAnchor(i)) fail("--tune: no row for " + label(candidates[i]) + " in " + csvPath);
    for (const TuneRow* row : recorded[i]) {
      TimedRow t{label(candidates[i]), i, row->session, isAnchor(i), {}};
      for (const SceneFigures& s : row->scenes) t.ms.push_back(s.ms);
      timed.push_back(std::move(t));
      timedRows.push_back(row);
    }
  }
  std::vector<std::vector<double>> unitMs;  // per timed row and scene: medium's time from its session's anchors
  if (Status s = timeUnits(timed, unitMs); !s) fail("--tune: " + s.message + " (" + csvPath + ")");
  r.drift = anchorDrift(timed);
  // The untuned medium's reference row: its first session's (with more than one, each session's
  // copy is that session's anchor 0, 1x by definition).
  std::vector<const TuneRow*> firstRow(candidates.size(), nullptr);
  std::vector<TunePoint> points(candidates.size());
  for (std::size_t t = 0; t < timed.size(); ++t) {
    const std::size_t i = timed[t].candidate;
    const TuneRow* row = timedRows[t];
    if (candidates[i].kind == "anchor" || (firstRow[i] && firstRow[i]->session <= row->session)) continue;
    TunePoint p{row, 0, row->meanRmse(), {}};
    double unit = 0;
    for (std::size_t s = 0; s < sceneNames.size(); ++s) {
      unit += unitMs[t][s];
      p.sceneX.push_back(row->scenes[s].ms / unitMs[t][s]);
    }
    p.timeX = row->totalMs() / unit;
    if (!(p.timeX > 0 && p.meanRmse > 0 && std::isfinite(p.meanRmse)))
      fail("--tune: " + timed[t].label + " (session " + std::to_string(row->session) + ") has no usable time or error in " +
           csvPath);
    firstRow[i] = row;
    points[i] = std::move(p);
  }
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (firstRow[i]) (i < referenceCount ? r.references : r.grid).push_back(points[i]);
  r.medium = firstRow[0];
  r.front = paretoFront(r.grid);
  r.blotchLimit = kDefaultBlotchShare * firstRow[1]->meanBlotch();  // candidate 1: the untuned defaults
  choose(r);
  const std::vector<std::string> files = writeTuneOutputs(o.out, r);

  std::printf("sao-bench --tune: %s, %ux%u, %zu scenes, %zu candidates (%zu evaluated now in %s, the rest read from "
              "tune.csv), reference (c) with %u taps%s\n",
              backend->description().c_str(), o.size.width, o.size.height, sceneNames.size(), candidates.size(), todo.size(),
              duration(wall).c_str(), o.convergedTaps,
              o.objectiveRays ? (", the error vs reference (a) with " + std::to_string(o.objectiveRays) + " rays").c_str() : "");
  for (const TunePoint& p : r.grid)
    if (p.row->settings == r.medium->settings)  // the grid's copy of medium, timed against its session's anchors around it
      std::printf("the grid's copy of the untuned medium: %.3gx (1 but for noise)%s\n", p.timeX,
                  r.drift.size() > 1 ? (" (session " + std::to_string(p.row->session) + ")").c_str() : "");
  printTuneSummary(r);
  std::string names;
  for (const std::string& f : files) names += (names.empty() ? "" : ",") + f;
  std::printf("wrote %s/{%s}\n", fs::absolute(o.out).lexically_normal().string().c_str(), names.c_str());
  return 0;
}

}  // namespace sao::bench
