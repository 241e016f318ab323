#include "sao/spiral.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <numeric>

namespace sao {

namespace {

// G3D Innovation Engine (BSD licence): its SAO shader's minimum-discrepancy spiral turns,
// index s (entry 0 unused). Every entry is coprime to s and below it (tests/core).
constexpr std::array<int, 100> kG3dMinimumDiscrepancyTurns = {
    1,  1,  1,  2,  3,  2,  5,  2,  3,  2,  3,  3,  5,  5,  3,  4,  7,  5,  5,  7,  9,  8,  5,  5,  7,
    7,  7,  8,  5,  8,  11, 12, 7,  10, 13, 8,  11, 8,  7,  14, 11, 11, 13, 12, 13, 19, 17, 13, 11, 18,
    19, 11, 11, 14, 17, 21, 15, 16, 17, 18, 13, 17, 11, 17, 19, 18, 25, 18, 19, 19, 29, 21, 19, 27, 31,
    29, 21, 18, 17, 29, 31, 31, 23, 18, 25, 26, 25, 23, 19, 34, 19, 27, 21, 25, 39, 29, 17, 21, 27, 29};

}  // namespace

int spiralTurns(int s) {
  if (s >= 1 && std::size_t(s) < kG3dMinimumDiscrepancyTurns.size()) return kG3dMinimumDiscrepancyTurns[std::size_t(s)];
  return latticeSpiralTurns(s);
}

int latticeSpiralTurns(int s) {
  if (s <= 2) return 1;
  int best = 1;
  double bestDistance = -1;
  for (int tau = 1; tau < s; ++tau) {
    if (std::gcd(tau, s) != 1) continue;
    // Lattice points differ by k/s in alpha and frac(k*tau/s) in angle; check every k.
    double minDistance = 1e9;
    for (int k = 1; k < s; ++k) {
      const double dx = std::fmin(double(k) / s, 1.0 - double(k) / s);
      const double a = double((k * tau) % s) / s;
      const double dy = std::fmin(a, 1.0 - a);
      minDistance = std::fmin(minDistance, std::hypot(dx, dy));
    }
    if (minDistance > bestDistance + 1e-12) {
      bestDistance = minDistance;
      best = tau;
    }
  }
  return best;
}

}  // namespace sao
