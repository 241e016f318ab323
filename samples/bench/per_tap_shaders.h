// The ladder of minimal AO passes of sao-bench --sections per_tap (per_tap_section.h): one GLSL
// source, each rung a set of switches on top of the minimal pass, so that the difference between
// two rungs is the one feature they differ in. Every rung computes the same estimator (SAO paper
// eq. 1: v = Q - C, sum of max(0, v.n + z_C*bias) / (v.v + epsilon) over the taps with v.v < r^2,
// A = max(0, 1 - (2 sigma r / s) sum)^k) from the effect's own csz.
#pragma once
#include <string>
#include <vector>

namespace sao::bench {

struct LadderStep {
  const char* name;             // the CSV's variant column
  const char* label;            // what it adds, for the summary
  bool fragment = false;        // fragment shader (full-screen triangle) instead of 8x8 compute
  bool quad2x2 = false;         // the effect's 2x2 bilateral reconstruction through shared memory
  bool zMips = false;           // per-tap csz MIP level (eq. 9-10) from the whole chain
  bool rebuiltNormals = false;  // normals rebuilt from csz (sao_reconstruct_normal) instead of read
  bool imageLoad = false;       // z read with imageLoad from an r32f image instead of texelFetch
  bool uniformTaps = false;     // tap count, turns and 1/s from uniforms (the effect's) instead of constants
  bool exactSpiral = false;     // the effect's fixed-point spiral and hash (sao_spiral.glsl) instead of G3D's float one
  bool turnTable = false;       // with exactSpiral: each tap's turn from a uniform table the host fills (no division)
};

// (a) .. (k): (a) the minimal fragment pass, (b) the same as compute, (c)-(h) (b) plus one feature,
// (i) (g) and (h) together, (j) (b) plus every feature of ao_sample with supplied normals (2x2, MIP,
// uniform taps, exact spiral), (k) (i) with the spiral's per-tap turns from a table.
const std::vector<LadderStep>& ladderSteps();

// The turns of sao_spiral_phase for taps 0..samples-1 (2^-32 turns), what turnTable reads.
std::vector<unsigned> spiralTurnTable(int samples, int spiralTurns);

// The full-screen triangle for the fragment rung.
extern const char* const kLadderVertexShader;
// The rung's fragment or compute shader for `samples` taps and `spiralTurns` turns (the constants
// of the rungs without uniformTaps).
std::string ladderShader(const LadderStep& step, int samples, int spiralTurns);

}  // namespace sao::bench
