#!/usr/bin/env bash
# The benchmark on a machine with a GPU: builds what sao-bench needs (Release, no tests) into
# build-gpu/, checks that GL and Vulkan run on a real device (not llvmpipe / lavapipe), then times
# the presets at 1920x1080, the radius sweep (paper Fig. 5) and the resolution table (paper Table 3)
# on both APIs and writes results, plots and the markdown tables into OUT (default out/gpu-bench).
# Each point is rendered back to back for 200 ms before its timed runs (--warmup-ms: the GPU's
# boost clock up). Timings only (sao-bench --time-only): the errors against the ray-traced references are the same
# computation on any machine (the backends agree with the CPU reference) and take minutes of CPU per
# scene; docs/BENCHMARKS.md has them. No test depends on it; it is for whenever a GPU is at hand,
# and for users checking their own.
#
# usage: ci/gpu-bench.sh [OUT]                      build here, then run
#        ci/gpu-bench.sh --bundle FILE              build here and pack sao-bench with the libraries
#                                                   it links (not glibc's, not the GL/Vulkan loaders)
#                                                   into FILE (.tar.xz), for a GPU machine without
#                                                   the build's packages
#        ci/gpu-bench.sh --from-bundle FILE [OUT]   run a bundle's sao-bench, no build
# SAO_GPU_BENCH_SETUP=1 runs ci/setup.sh first (needs apt); SAO_GPU_BENCH_SECTIONS overrides the
# sections (default presets,radius,resolution); SAO_GPU_BENCH_ARGS adds sao-bench options (--quick
# for a smoke run); SAO_EGL_PLATFORM (default device) picks GL's EGL
# platform.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
t0=$SECONDS

build() {
  if [ "${SAO_GPU_BENCH_SETUP:-0}" = 1 ]; then bash ci/setup.sh; fi
  local generator=()
  if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
  if [ ! -f build-gpu/CMakeCache.txt ]; then
    cmake -S . -B build-gpu "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DSAO_BUILD_TESTS=OFF \
      -DSAO_BUILD_WALKTHROUGH=OFF >build-gpu-configure.log 2>&1 || { cat build-gpu-configure.log; exit 1; }
  fi
  cmake --build build-gpu --parallel "$(nproc)" --target sao-bench
  echo "gpu-bench: built in $((SECONDS - t0)) s"
}

# The bundle: bin/sao-bench and lib/ with every library it links that is not glibc's, the C++
# runtime's or a GL/Vulkan loader (those come from the GPU machine, with its driver).
bundle() {
  local file="$1" dir
  dir="$(mktemp -d)"
  trap 'rm -rf "$dir"' RETURN
  mkdir -p "$dir/bundle/bin" "$dir/bundle/lib"
  cp build-gpu/bin/sao-bench "$dir/bundle/bin/"
  ldd build-gpu/bin/sao-bench | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' | while read -r name path; do
    case "$name" in
      libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*|libstdc++.so*|libgcc_s.so*) ;;
      libvulkan.so*|libEGL.so*|libGL.so*|libGLX.so*|libOpenGL.so*|libGLdispatch.so*) ;;
      *) cp -L "$path" "$dir/bundle/lib/$name" ;;
    esac
  done
  strip --strip-unneeded "$dir/bundle/bin/sao-bench" "$dir/bundle/lib/"*.so* 2>/dev/null || true
  mkdir -p "$(dirname "$file")"
  tar -C "$dir" -cJf "$file" bundle
  echo "gpu-bench: bundle $file ($(du -h "$file" | cut -f1)): $(ls "$dir/bundle/lib" | tr '\n' ' ')"
}

bench=build-gpu/bin/sao-bench
case "${1:-}" in
  --bundle)
    [ $# -eq 2 ] || { echo "usage: ci/gpu-bench.sh --bundle FILE" >&2; exit 2; }
    build
    bundle "$2"
    exit 0 ;;
  --from-bundle)
    [ $# -ge 2 ] && [ $# -le 3 ] || { echo "usage: ci/gpu-bench.sh --from-bundle FILE [OUT]" >&2; exit 2; }
    [ -f "$2" ] || { echo "gpu-bench: no bundle '$2'" >&2; exit 2; }
    unpacked="$(mktemp -d)"
    trap 'rm -rf "$unpacked"' EXIT
    tar -C "$unpacked" -xJf "$2"
    bench="$unpacked/bundle/bin/sao-bench"
    export LD_LIBRARY_PATH="$unpacked/bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
    shift 2 ;;
  -*)
    echo "usage: ci/gpu-bench.sh [OUT] | --bundle FILE | --from-bundle FILE [OUT]" >&2; exit 2 ;;
  *)
    build ;;
esac
out="${1:-out/gpu-bench}"
sections="${SAO_GPU_BENCH_SECTIONS:-presets,radius,resolution}"

# Which device each API runs on: a software rasteriser here means the figures are not a GPU's.
# EGL's device platform first (NVIDIA's EGL has no surfaceless platform); the effect prints its
# device in results.json ("machine") too.
export SAO_EGL_PLATFORM="${SAO_EGL_PLATFORM:-device}"
mkdir -p "$out"
# An NVIDIA GPU's clocks every 100 ms through the run: its boost falls while the benchmark's load
# is light (uploads, read-backs, scene set-up between short passes), and a row's time depends on it.
# results.csv's started_unix_s / ended_unix_s line the rows up with this log.
sampler=
if command -v nvidia-smi >/dev/null 2>&1; then
  nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,utilization.gpu,pstate,power.draw --format=csv,nounits \
    -lms 100 >"$out/gpu-clocks.csv" 2>/dev/null &
  sampler=$!
  trap 'kill $sampler 2>/dev/null || true; rm -rf "${unpacked:-}"' EXIT
fi
# --overwrite: the folder also holds this script's gpu-clocks.csv and sao-bench.log, which sao-bench
# did not write; its own files of an earlier run are replaced, these kept.
"$bench" --out "$out" --overwrite --sections "$sections" --backends gl,vulkan --runs 5 --size 1920x1080 --time-only --warmup-ms 200 \
  ${SAO_GPU_BENCH_ARGS:-} 2>&1 | tee "$out/sao-bench.log"
if [ -n "$sampler" ]; then kill "$sampler" 2>/dev/null || true; fi
if grep -Eiq "llvmpipe|lavapipe|softpipe|swiftshader" "$out/results.json"; then
  echo "gpu-bench: WARNING: a backend ran on a software rasteriser (see 'machine' in $out/results.json);" \
       "its figures are not a GPU's" >&2
fi

# The tables of docs/BENCHMARKS.md's pages, for this run.
py=/usr/bin/python3
command -v "$py" >/dev/null 2>&1 || py=python3
"$py" samples/bench/markdown_tables.py "$out" >"$out/tables.md" || echo "gpu-bench: markdown tables failed (the CSVs are there)" >&2
echo "gpu-bench: done in $((SECONDS - t0)) s; results in $(cd "$out" && pwd): results.csv, results.json, *.svg, tables.md${sampler:+, gpu-clocks.csv}"
