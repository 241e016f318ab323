#include "sao/spiral.h"

#include <algorithm>
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

std::uint32_t spiralTapTurn(int i, int s, int tau) {
  const std::uint32_t k = (std::uint32_t(2 * i + 1) * std::uint32_t(tau)) % std::uint32_t(2 * s);
  return ((k << 23u) / std::uint32_t(s)) << 8u;
}

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

FrameSpiral frameSpiral(std::uint32_t k) {
  constexpr std::uint32_t goldenStep = 2654435769u;  // round(2^32 / golden ratio)
  FrameSpiral f;
  f.phase = k * goldenStep;  // modulo 2^32: a turn
  // The van der Corput radical inverse of k (its bits mirrored), exact in double.
  std::uint32_t r = k;
  r = (r << 16) | (r >> 16);
  r = ((r & 0x00FF00FFu) << 8) | ((r & 0xFF00FF00u) >> 8);
  r = ((r & 0x0F0F0F0Fu) << 4) | ((r & 0xF0F0F0F0u) >> 4);
  r = ((r & 0x33333333u) << 2) | ((r & 0xCCCCCCCCu) >> 2);
  r = ((r & 0x55555555u) << 1) | ((r & 0xAAAAAAAAu) >> 1);
  const double offset = 0.5 + double(r) / 4294967296.0;
  // frac, as a float below 1 (a value within half a float ulp of 1 would round up to 1).
  f.alphaOffset = std::min(static_cast<float>(offset - std::floor(offset)), std::nextafter(1.0f, 0.0f));
  return f;
}

}  // namespace sao
