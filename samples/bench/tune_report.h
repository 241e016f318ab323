// sao-bench --tune's outputs once the rows are in: tune_front.csv, tune_front.svg,
// tune_presets.txt and the tables on stdout. Everything here is computed from tune.csv's rows
// only, so a resumed run writes the same files.
#pragma once
#include <string>
#include <vector>

#include "tune_select.h"

namespace sao::bench {

struct TuneResult {
  std::vector<std::string> scenes;
  std::string backend, depth;
  Extent size{0, 0};
  const TuneRow* medium = nullptr;       // today's medium preset, the time unit
  std::vector<TunePoint> grid;           // every grid candidate
  std::vector<std::size_t> front;        // paretoFront(grid)
  std::vector<std::size_t> chain;        // chooseChain(grid, ...): the tuned presets, cheapest first
  std::vector<std::string> chainNames;   // their names (low, medium, ...)
  std::vector<double> chainBudgets;      // the budget each was chosen for (x medium)
  std::vector<TunePoint> references;     // today's presets, then the AlchemyAO-style baseline
  std::size_t anchors = 0;               // measurements of medium (the first is today's preset row)
  double driftMin = 1, driftMax = 1;     // their totals over the first's: the machine's drift
};

// The preset names by budget: low 0.25x, medium 0.5x ... reference 4x of today's medium.
inline const std::vector<double> kTuneBudgets = {0.25, 0.5, 1, 2, 4};
inline const std::vector<std::string> kTuneNames = {"low", "medium", "high", "ultra", "reference"};

// Files written, by name, in `dir`; a failure stops the tool (bench::fail).
std::vector<std::string> writeTuneOutputs(const std::string& dir, const TuneResult& r);

// The tables (tuned presets; today's presets and the baseline), the span targets and what the
// front depends on, on stdout.
void printTuneSummary(const TuneResult& r);

}  // namespace sao::bench
