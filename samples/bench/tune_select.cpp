#include "tune_select.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace sao::bench {

std::vector<std::size_t> paretoFront(const std::vector<TunePoint>& points) {
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (points[a].timeX != points[b].timeX) return points[a].timeX < points[b].timeX;
    return points[a].meanRmse < points[b].meanRmse;
  });
  std::vector<std::size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i : order)
    if (points[i].meanRmse < best) {
      best = points[i].meanRmse;
      front.push_back(i);
    }
  return front;
}

bool stepsUp(const TunePoint& a, const TunePoint& b) {
  if (a.row->scenes.size() != b.row->scenes.size() || a.sceneX.size() != a.row->scenes.size() ||
      b.sceneX.size() != b.row->scenes.size())
    return false;
  for (std::size_t s = 0; s < a.sceneX.size(); ++s)
    if (!(b.sceneX[s] > a.sceneX[s] && b.row->scenes[s].rmse < a.row->scenes[s].rmse)) return false;
  return true;
}

std::vector<std::size_t> chooseChain(const std::vector<TunePoint>& points, const std::vector<double>& budgets,
                                     const std::vector<double>& maxBlotch) {
  const std::size_t n = points.size(), k = budgets.size();
  if (k == 0 || n < k || (!maxBlotch.empty() && maxBlotch.size() != k)) return {};
  auto allowed = [&](std::size_t budget, const TunePoint& p) { return maxBlotch.empty() || p.row->meanBlotch() <= maxBlotch[budget]; };
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return points[a].timeX < points[b].timeX; });
  auto cost = [&](std::size_t budget, const TunePoint& p) {
    const double b = budgets[budget];
    const double outside = std::max(0.0, std::log2(p.timeX / b)) + std::max(0.0, std::log2(0.5 * b / p.timeX));
    return std::log(p.meanRmse) + kOutsidePenalty * outside;
  };
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> f(k, std::vector<double>(n, inf));
  std::vector<std::vector<std::size_t>> from(k, std::vector<std::size_t>(n, n));
  for (std::size_t j = 0; j < n; ++j)
    if (std::isfinite(std::log(points[order[j]].meanRmse)) && allowed(0, points[order[j]])) f[0][j] = cost(0, points[order[j]]);
  for (std::size_t i = 1; i < k; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      if (!allowed(i, points[order[j]])) continue;
      double best = inf;
      for (std::size_t m = 0; m < j; ++m)  // sorted by time: only earlier points can step up to j
        if (f[i - 1][m] < best && stepsUp(points[order[m]], points[order[j]])) {
          best = f[i - 1][m];
          from[i][j] = m;
        }
      if (best < inf) f[i][j] = best + cost(i, points[order[j]]);
    }
  std::size_t end = n;
  for (std::size_t j = 0; j < n; ++j)
    if (f[k - 1][j] < inf && (end == n || f[k - 1][j] < f[k - 1][end])) end = j;
  if (end == n) return {};
  std::vector<std::size_t> chain(k);
  for (std::size_t i = k; i-- > 0;) {
    chain[i] = order[end];
    end = from[i][end];
  }
  return chain;
}

}  // namespace sao::bench
