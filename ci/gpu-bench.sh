#!/usr/bin/env bash
# The benchmark on a machine with a GPU: builds what sao-bench needs (Release, no tests) into
# build-gpu/, checks that GL and Vulkan run on a real device (not llvmpipe / lavapipe), then runs
# the presets, the radius sweep (paper Fig. 5) and the resolution table (paper Table 3) on both
# APIs and writes results, plots and the markdown tables into OUT (default out/gpu-bench).
# No test depends on it; it is for whenever a GPU is at hand, and for users checking their own.
# usage: ci/gpu-bench.sh [OUT]   (SAO_GPU_BENCH_SETUP=1 runs ci/setup.sh first: needs apt)
#        SAO_GPU_BENCH_SECTIONS overrides the sections (default presets,radius,resolution)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
out="${1:-out/gpu-bench}"
sections="${SAO_GPU_BENCH_SECTIONS:-presets,radius,resolution}"
t0=$SECONDS

if [ "${SAO_GPU_BENCH_SETUP:-0}" = 1 ]; then bash ci/setup.sh; fi

generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
if [ ! -f build-gpu/CMakeCache.txt ]; then
  cmake -S . -B build-gpu "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DSAO_BUILD_TESTS=OFF \
    -DSAO_BUILD_WALKTHROUGH=OFF >build-gpu-configure.log 2>&1 || { cat build-gpu-configure.log; exit 1; }
fi
cmake --build build-gpu --parallel "$(nproc)" --target sao-bench
echo "gpu-bench: built in $((SECONDS - t0)) s"

# Which device each API runs on: a software rasteriser here means the figures are not a GPU's.
# EGL's device platform first (NVIDIA's EGL has no surfaceless platform); the effect prints its
# device in results.json ("machine") too.
export SAO_EGL_PLATFORM="${SAO_EGL_PLATFORM:-device}"
mkdir -p "$out"
build-gpu/bin/sao-bench --out "$out" --sections "$sections" --backends gl,vulkan --runs 5 \
  2>&1 | tee "$out/sao-bench.log"
if grep -Eiq "llvmpipe|lavapipe|softpipe|swiftshader" "$out/results.json"; then
  echo "gpu-bench: WARNING: a backend ran on a software rasteriser (see 'machine' in $out/results.json);" \
       "its figures are not a GPU's" >&2
fi

# The tables of docs/BENCHMARKS.md's pages, for this run.
py=/usr/bin/python3
command -v "$py" >/dev/null 2>&1 || py=python3
"$py" samples/bench/markdown_tables.py "$out" >"$out/tables.md" || echo "gpu-bench: markdown tables failed (the CSVs are there)" >&2
echo "gpu-bench: done in $((SECONDS - t0)) s; results in $(cd "$out" && pwd): results.csv, results.json, *.svg, tables.md"
