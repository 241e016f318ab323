// sao-bench --tune's outputs once the rows are in: tune_front.csv, tune_front.svg,
// tune_presets.txt and the tables on stdout. Everything here is computed from tune.csv's rows
// only, so a resumed run writes the same files.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "tune_select.h"
#include "tune_time.h"

namespace sao::bench {

struct TuneResult {
  std::vector<std::string> scenes;
  std::string backend, depth;
  Extent size{0, 0};
  std::string objective = "c";           // the reference the error is measured against: "c" or "a" (TuneOptions)
  const TuneRow* medium = nullptr;       // the untuned medium (tune_grid.h), the time unit: its first session's row
  std::vector<TunePoint> grid;           // every grid candidate
  std::vector<std::size_t> front;        // paretoFront(grid)
  std::vector<std::size_t> chain;        // chooseChain(grid, ...): the tuned presets, cheapest first
  std::vector<std::string> chainNames;   // their names (low, medium, ...)
  std::vector<double> chainBudgets;      // the budget each was chosen for (x medium)
  std::vector<TunePoint> references;     // the untuned rows, today's presets, the AlchemyAO-style baseline
  double blotchLimit = INFINITY;         // the default preset's: kDefaultBlotchShare x the untuned defaults' mean
  // Per session of tune.csv, its measurements of medium (the anchors) and their totals over that
  // session's first in candidate order: the machine's drift over each run.
  std::vector<SessionDrift> drift;
};

// The preset names by budget, x the untuned medium: low 0.2x (issue 16 asks for <= 0.25x; 0.2 leaves
// room for this machine's ~10 % timing noise), medium 0.5x, high 1x, ultra 2x, reference 4x.
inline const std::vector<double> kTuneBudgets = {0.2, 0.5, 1, 2, 4};
inline const std::vector<std::string> kTuneNames = {"low", "medium", "high", "ultra", "reference"};
// The preset the settings' defaults equal ("high": what the untuned defaults cost), and the share of
// the untuned defaults' mean blotch it may have: what a user gets without choosing must show at most
// half the blotches it showed before, at no more cost.
inline constexpr std::size_t kDefaultPreset = 2;
inline constexpr double kDefaultBlotchShare = 0.5;

// The files --tune writes in its folder (the folder's manifest lists them before the run starts).
inline const std::vector<std::string> kTuneFiles = {"tune.csv", "tune_front.csv", "tune_front.svg",
                                                    "tune_presets.txt"};

// Writes the files after tune.csv (each renamed into place when complete) in `dir` and returns
// kTuneFiles; a failure stops the tool (bench::fail).
std::vector<std::string> writeTuneOutputs(const std::string& dir, const TuneResult& r);

// The tables (tuned presets; today's presets and the baseline), the span targets and what the
// front depends on, on stdout.
void printTuneSummary(const TuneResult& r);

}  // namespace sao::bench
