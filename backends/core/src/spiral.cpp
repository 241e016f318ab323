#include "sao/spiral.h"

#include <cmath>
#include <numeric>

namespace sao {

int spiralTurns(int s) {
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
