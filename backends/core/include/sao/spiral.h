// The number of spiral turns tau for s taps (paper eq. 6-7), and the spiral's per-frame variation.
#pragma once
#include <cstdint>

namespace sao {

// How frame `frameIndex` moves every pixel's spiral, for an engine that accumulates frames (TAA,
// or its own temporal filter; G3D's temporallyVarySamples): a rotation of all taps (added to the
// per-pixel phase of eq. 8, in 2^-32 turns) and the taps' radial position alpha_i = (i + offset)/s.
// Frame 0 is the paper's spiral (rotation 0, offset 0.5): the output of frame 0 is that of an
// effect without frames. Frame k rotates by frac(k / golden ratio) turns (exact integer
// arithmetic: k times round(2^32 / golden ratio), modulo 2^32) and sets the offset to
// frac(0.5 + vdc(k)), vdc the van der Corput radical inverse (k's bits mirrored), a float in
// [0, 1). Any N consecutive frames then cover the disk's angles with gaps below 1.9/N and its radii
// with gaps below 3/N (the first 2^m frames: exactly 1/N).
struct FrameSpiral {
  std::uint32_t phase = 0;    // the block's frame_phase
  float alphaOffset = 0.5f;   // the block's frame_alpha_offset
};
FrameSpiral frameSpiral(std::uint32_t frameIndex);

// Eq. 6 for tap i of s with tau turns: alpha_i * tau turns mod 1, alpha_i = (2i + 1) / (2s), in
// units of 2^-32 turns: k = ((2i + 1) tau) mod 2s, then ((k << 23) / s) << 8 (exact integers; the
// low 8 bits are 0 because the shader keeps 24 bits of a turn). The parameter block's tap_turn0
// holds it for i = 0, so ao_sample adds the pixel's phase instead of dividing by s; later taps turn
// by tap_step, (cos, sin) of 2 pi tau / s.
std::uint32_t spiralTapTurn(int i, int samples, int tau);

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
