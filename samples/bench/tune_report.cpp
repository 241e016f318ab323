#include "tune_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "sao/samples/output_files.h"
#include "scene_cache.h"
#include "svg_plot.h"
#include "tune_grid.h"

namespace sao::bench {
namespace {

std::string number(double v, const char* format = "%.4g") {
  char b[40];
  std::snprintf(b, sizeof b, format, v);
  return b;
}

// Mean over the scenes that have the figure (silhouette: NaN where a scene has no band).
double meanOf(const TuneRow& r, double SceneFigures::*field) {
  double sum = 0;
  int n = 0;
  for (const SceneFigures& s : r.scenes)
    if (!std::isnan(s.*field)) sum += s.*field, ++n;
  return n ? sum / n : NAN;
}

void writeFile(const std::string& path, const std::string& text) {
  if (Status s = samples::writeFileInPlace(path, text); !s) fail(s.message);
}

std::string frontCsv(const TuneResult& r) {
  const std::string rmse = "rmse_vs_" + r.objective;
  std::string o = "role,name,time_x_medium,total_ms,mean_" + rmse;
  for (const std::string& what : {rmse, std::string("blotch"), std::string("silhouette"), std::string("ms"), std::string("x_medium")})
    for (const std::string& s : r.scenes) o += "," + s + "_" + what;
  o += ",inputs";
  for (const std::string& s : kTunedSettings) o += "," + s;
  o += "\n";
  auto row = [&](const std::string& role, const std::string& name, const TunePoint& p) {
    o += role + "," + name + "," + number(p.timeX) + "," + number(p.row->totalMs()) + "," + number(p.meanRmse);
    for (double SceneFigures::*f : {&SceneFigures::rmse, &SceneFigures::blotch, &SceneFigures::silhouette, &SceneFigures::ms})
      for (const SceneFigures& s : p.row->scenes) o += "," + number(s.*f, "%.9g");  // as in tune.csv
    for (double x : p.sceneX) o += "," + number(x, "%.9g");
    o += "," + p.row->inputs;
    for (const std::string& s : kTunedSettings) o += "," + tunedSettingValue(p.row->settings, s);
    o += "\n";
  };
  auto chainName = [&](std::size_t i) -> std::string {
    for (std::size_t c = 0; c < r.chain.size(); ++c)
      if (r.chain[c] == i) return r.chainNames[c];
    return "";
  };
  for (std::size_t i : r.front) {
    const std::string name = chainName(i);
    row(name.empty() ? "front" : "front+tuned", name, r.grid[i]);
  }
  for (std::size_t c = 0; c < r.chain.size(); ++c)
    if (std::find(r.front.begin(), r.front.end(), r.chain[c]) == r.front.end()) row("tuned", r.chainNames[c], r.grid[r.chain[c]]);
  for (const TunePoint& p : r.references)
    row(p.row->kind == "baseline" ? "baseline" : p.row->kind == "unit" ? "untuned" : "current", p.row->name, p);
  return o;
}

std::string frontSvg(const TuneResult& r) {
  Chart c;
  c.title = "sao-bench --tune: " + r.backend + ", " + std::to_string(r.size.width) + "x" + std::to_string(r.size.height) +
            ", " + std::to_string(r.scenes.size()) + " scenes";
  c.xLabel = "time, x the untuned medium preset (sum over the scenes of the median totals)";
  c.yLabel = "RMSE vs (" + r.objective + "), mean over the scenes";
  c.logX = c.logY = true;
  Series all{"candidates (" + std::to_string(r.grid.size()) + ")", {}, {}, false, {}, "#7f7f7f", 0.25};
  for (const TunePoint& p : r.grid) all.x.push_back(p.timeX), all.y.push_back(p.meanRmse);
  Series front{"Pareto front", {}, {}, true, {}, "#1f77b4", 1};
  for (std::size_t i : r.front) front.x.push_back(r.grid[i].timeX), front.y.push_back(r.grid[i].meanRmse);
  Series tuned{"tuned presets", {}, {}, true, {}, "#d62728", 1};
  for (std::size_t k = 0; k < r.chain.size(); ++k) {
    tuned.x.push_back(r.grid[r.chain[k]].timeX), tuned.y.push_back(r.grid[r.chain[k]].meanRmse);
    tuned.pointLabels.push_back(r.chainNames[k]);
  }
  Series today{"today's presets", {}, {}, false, {}, "#2ca02c", 1};
  Series untuned{"untuned medium and defaults", {}, {}, false, {}, "#ff7f0e", 1};
  Series baseline{"AlchemyAO-style baseline", {}, {}, false, {}, "#9467bd", 1};
  for (const TunePoint& p : r.references) {
    Series& s = p.row->kind == "baseline" ? baseline : p.row->kind == "unit" ? untuned : today;
    s.x.push_back(p.timeX), s.y.push_back(p.meanRmse);
    s.pointLabels.push_back(p.row->kind == "baseline" ? "AlchemyAO-style"
                            : p.row->kind == "unit"   ? p.row->name
                                                      : p.row->name + " (today)");
  }
  c.series = {all, front, tuned, today, untuned, baseline};
  return renderSvg(c, 900, 560);
}

std::string presetsText(const TuneResult& r) {
  std::string o = "// Presets chosen by `sao-bench --tune` on " + r.backend + " at " + std::to_string(r.size.width) + "x" +
                  std::to_string(r.size.height) + " over";
  for (const std::string& s : r.scenes) o += " " + s;
  o += ": each step up is slower and has a lower RMSE vs (" + r.objective + ") on every scene. Time x the untuned medium preset,\n"
       "// RMSE vs (" + r.objective + ") mean over the scenes. Ready to paste into effect/sao.glsl; the settings' defaults there are the " +
       kTuneNames[kDefaultPreset] + " preset's.\n";
  for (std::size_t k = 0; k < r.chain.size(); ++k) {
    const TunePoint& p = r.grid[r.chain[k]];
    o += "// " + r.chainNames[k] + ": budget " + number(r.chainBudgets[k], "%g") + "x, measured " + number(p.timeX, "%.3g") +
         "x, RMSE vs (" + r.objective + ") " + number(p.meanRmse, "%.4f") + "\n";
  }
  for (std::size_t k = 0; k < r.chain.size(); ++k) {
    const Settings& s = r.grid[r.chain[k]].row->settings;
    char name[32];
    std::snprintf(name, sizeof name, "%-9s", r.chainNames[k].c_str());
    o += "#pragma sao preset " + std::string(name) + " " + settingsWords(s) + " \"" + describeSettings(s) + "\"\n";
  }
  return o;
}

void printTable(const TuneResult& r, const std::string& title, const std::vector<std::pair<std::string, const TunePoint*>>& rows) {
  std::printf("\n%s\n%-16s %9s", title.c_str(), "preset", "x unit");
  for (const std::string& s : r.scenes) std::printf(" %12.12s", s.c_str());
  std::printf(" %8s %8s %10s  settings\n", "mean", "blotch", "silhouette");
  for (const auto& [name, p] : rows) {
    std::printf("%-16s %9.3f", name.c_str(), p->timeX);
    for (const SceneFigures& s : p->row->scenes) std::printf(" %12.4f", s.rmse);
    std::printf(" %8.4f %8.4f %10.4f  %s%s\n", p->meanRmse, p->row->meanBlotch(),
                meanOf(*p->row, &SceneFigures::silhouette), settingsWords(p->row->settings).c_str(),
                p->row->inputs == "depth" ? "" : (" (" + p->row->inputs + ")").c_str());
  }
}

}  // namespace

std::vector<std::string> writeTuneOutputs(const std::string& dir, const TuneResult& r) {
  namespace fs = std::filesystem;
  writeFile((fs::path(dir) / "tune_front.csv").string(), frontCsv(r));
  writeFile((fs::path(dir) / "tune_front.svg").string(), frontSvg(r));
  writeFile((fs::path(dir) / "tune_presets.txt").string(), presetsText(r));
  return kTuneFiles;
}

void printTuneSummary(const TuneResult& r) {
  std::vector<std::pair<std::string, const TunePoint*>> tuned, today;
  for (std::size_t k = 0; k < r.chain.size(); ++k) tuned.emplace_back(r.chainNames[k], &r.grid[r.chain[k]]);
  for (const TunePoint& p : r.references) today.emplace_back(p.row->kind == "baseline" ? "AlchemyAO-style" : p.row->name, &p);
  std::printf("\nRMSE vs (%s) per scene; blotch (low-passed error) and silhouette (within 3 px of a depth edge) RMSE "
              "vs (c) are means over the scenes; time is x the untuned medium preset (%.3g ms summed over the scenes%s).",
              r.objective.c_str(), r.medium->totalMs(), r.drift.size() > 1 ? " in the first session" : "");
  printTable(r, "tuned presets (the chain; " + std::to_string(r.front.size()) + " of " + std::to_string(r.grid.size()) +
                    " candidates on the front)", tuned);
  printTable(r, "the untuned medium and defaults, today's presets and the AlchemyAO-style baseline (the untuned medium "
                "without the z hierarchy, supplied normals; its (c) is computed with the same normals)", today);
  for (std::size_t k = 0; k < r.chain.size(); ++k)
    if (r.chainNames[k] == kTuneNames[kDefaultPreset]) {
      const TunePoint& p = r.grid[r.chain[k]];
      std::printf("\nthe default preset (%s): blotch %.4f against the untuned defaults' %.4f (x%.2f; <= %.2f: %s), time "
                  "x%.3f of the untuned defaults' (<= 1: %s)\n",
                  r.chainNames[k].c_str(), p.row->meanBlotch(), r.references[1].row->meanBlotch(),
                  p.row->meanBlotch() / r.references[1].row->meanBlotch(), kDefaultBlotchShare,
                  p.row->meanBlotch() <= r.blotchLimit ? "met" : "NOT met", p.timeX / r.references[1].timeX,
                  p.timeX <= r.references[1].timeX ? "met" : "NOT met");
    }
  if (r.chain.size() >= 2) {
    const TuneRow& lo = *r.grid[r.chain.front()].row;
    const TuneRow& hi = *r.grid[r.chain.back()].row;
    const double timeSpan = hi.totalMs() / lo.totalMs(), rmseSpan = lo.meanRmse() / hi.meanRmse();
    double worstTime = INFINITY, worstRmse = INFINITY;
    for (std::size_t s = 0; s < r.scenes.size(); ++s) {
      worstTime = std::min(worstTime, hi.scenes[s].ms / lo.scenes[s].ms);
      worstRmse = std::min(worstRmse, lo.scenes[s].rmse / hi.scenes[s].rmse);
    }
    std::printf("\ntargets: %zu presets (>= 5: %s), monotone on every scene by construction; cheapest to most accurate: "
                "time x%.2f (>= 8: %s; the smallest per scene x%.2f), RMSE vs (%s) falls x%.2f (>= 3: %s; the smallest per "
                "scene x%.2f: %s)\n",
                r.chain.size(), r.chain.size() >= 5 ? "met" : "NOT met", timeSpan, timeSpan >= 8 ? "met" : "NOT met", worstTime,
                r.objective.c_str(), rmseSpan, rmseSpan >= 3 ? "met" : "NOT met", worstRmse, worstRmse >= 3 ? "met on every scene" : "not on every scene");
  } else {
    std::printf("\ntargets: NOT met: no chain of two or more presets steps up on every scene\n");
  }
  std::size_t anchors = 0;
  double driftMin = 1, driftMax = 1;
  std::string perSession;
  for (const SessionDrift& d : r.drift) {
    anchors += d.anchors, driftMin = std::min(driftMin, d.min), driftMax = std::max(driftMax, d.max);
    perSession += (perSession.empty() ? "" : "; ") + std::string("session ") + std::to_string(d.session) + ": " +
                  std::to_string(d.anchors) + " anchors, " + number(d.min, "%.2f") + "x to " + number(d.max, "%.2f") + "x";
  }
  std::printf("\nErrors are deterministic on a backend (a rerun gives the same figures); times are medians of the runs "
              "measured when each row was evaluated (a resumed run keeps the times in tune.csv), on a shared machine. "
              "Each time is divided by medium's, interpolated between the measurements of medium around it in the same "
              "session (the %zu anchors; their totals ranged over %.2fx to %.2fx their session's first one's: the "
              "machine's drift over a run). The front and the chain follow those times: points within ~10%% in time can "
              "swap places between runs, and a step must be slower on every scene.\n",
              anchors, driftMin, driftMax);
  if (r.drift.size() > 1)
    std::printf("tune.csv holds %zu sessions (the runs that added rows, its session column); each row is timed against "
                "its own session's anchors only (%s).\n",
                r.drift.size(), perSession.c_str());
}

}  // namespace sao::bench
