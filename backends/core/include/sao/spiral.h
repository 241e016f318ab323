// The number of spiral turns tau for s taps (paper eq. 6-7).
#pragma once

namespace sao {

// tau for s taps, the one the effect uses when the setting spiral_turns is 0: G3D's
// minimum-discrepancy table for s = 1..99 (it covers the samples setting's range), else
// latticeSpiralTurns(s). The table replaced the lattice criterion below after
// `sao-bench --sections spiral` measured it lower in error against reference (c) in 229 of 340
// cases (every s in 1..64 where the two differ, five scenes, with and without blur; mean RMSE
// 0.02336 against 0.02360; docs/BENCHMARKS.md "Spiral turns").
int spiralTurns(int samples);

// The taps (alpha_i, frac(alpha_i * tau)) with alpha_i = (i + 0.5) / s form a rank-1 lattice on
// the unit torus; this is the tau in [1, s) coprime to s whose lattice has the largest minimum
// distance between taps (ties: the smaller tau). s = 1 gives 1.
int latticeSpiralTurns(int samples);

}  // namespace sao
