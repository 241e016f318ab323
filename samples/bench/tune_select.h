// sao-bench --tune: the Pareto front of the candidates and the chain of presets chosen on it.
#pragma once
#include <cstddef>
#include <vector>

#include "tune_csv.h"

namespace sao::bench {

// A candidate as the selection sees it: its row, its time relative to the medium preset (per
// scene, and the sum over the scenes of the median totals over medium's sum; medium's time
// interpolated between the anchors measured before and after the candidate) and its mean RMSE vs (c).
struct TunePoint {
  const TuneRow* row = nullptr;
  double timeX = 0, meanRmse = 0;
  std::vector<double> sceneX;
};

// Indices of the points no other point beats in both time and mean RMSE (ties: the first), by time.
std::vector<std::size_t> paretoFront(const std::vector<TunePoint>& points);

// `a` before `b` in a preset chain: on every scene `b` takes longer (sceneX) and has a lower RMSE vs (c).
bool stepsUp(const TunePoint& a, const TunePoint& b);

// One preset per budget (times the medium preset's time), each step up stepping up on every scene
// (stepsUp), minimising the sum over the chain of log(mean RMSE) + kOutsidePenalty x the octaves
// by which the point's time lies outside its budget's window (budget/2, budget]: within the window
// the lowest error wins, outside it the nearest time. Dynamic programme over the points sorted by
// time, O(budgets x points^2 x scenes); ties go to the earlier point (grid order). `maxBlotch`
// (empty, or one per budget; infinity for none) excludes points whose row's meanBlotch() exceeds it from
// that budget's place. Empty when no chain of that length exists.
inline constexpr double kOutsidePenalty = 10;
std::vector<std::size_t> chooseChain(const std::vector<TunePoint>& points, const std::vector<double>& budgets,
                                     const std::vector<double>& maxBlotch = {});

}  // namespace sao::bench
