// The number of spiral turns tau for s taps (paper eq. 6-7).
#pragma once

namespace sao {

// The taps (alpha_i, frac(alpha_i * tau)) with alpha_i = (i + 0.5) / s form a rank-1 lattice on
// the unit torus; we pick the tau in [1, s) coprime to s whose lattice has the largest minimum
// distance between taps (ties: the smaller tau). Every such tau spreads the angles evenly; the best
// one also keeps taps at neighbouring radii far apart in angle. Derived here, not copied from a
// table, so it holds for any s. s = 1 gives 1.
int spiralTurns(int samples);

}  // namespace sao
