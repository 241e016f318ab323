// The machines the traffic section models: a GPU like the paper's GTX 680, and this CPU as
// llvmpipe uses it (each core an "SM" running one work group at a time, 8-lane vectors, linear
// texel rows), with its cache sizes read from the system.
#pragma once
#include <string>

#include "traffic_model.h"

namespace sao::bench {

// GTX 680 (Kepler GK104) as the paper's measurements saw it: 8 SMX, 16 KB L1 each (fully
// associative here), 512 KB shared L2 (16-way), 128-byte lines, 2D-tiled textures, warps of 32,
// 16 work groups of 64 resident per SMX, warps interleaved per instruction. l1Bytes: another L1
// size, to see how far the figures depend on it.
Machine paperLikeMachine(std::uint64_t l1Bytes = 16 * 1024);

// This CPU: cores from std::thread::hardware_concurrency, L1d and L2 from
// /sys/devices/system/cpu/cpu0/cache (else sysconf); `source` says which, for the report.
Machine thisCpuMachine(std::string& source);

// "16 KB L1 (fully assoc.) x 8, 512 KB L2 shared, 128 B lines, tiled 8x4 r32f"
std::string describe(const Machine& m);

}  // namespace sao::bench
