#!/usr/bin/env bash
# Stage "fuzz": builds the libFuzzer targets (tests/fuzz) with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer into build-fuzz/ and runs each from the committed seed corpus
# (tests/fuzz/corpus/<target>, tests/fuzz/regressions/<target>, plus the codegen test sources for
# the parser). Prints executions per target (also to build-fuzz/fuzz_summary.txt).
#
# By default the run is deterministic, so that CI's verdict depends on the commit alone: each
# target runs a fixed number of inputs (-runs, sized to about half a minute each on a 2-core machine)
# from a fixed -seed, a fresh working corpus, address-space randomisation off, -timeout far above
# any honest input and fixed memory limits: the same commit runs the same inputs on every machine. A crash, a sanitizer report, a leak, a broken invariant, an input over the timeout or an
# out-of-memory fails the stage and prints the input (hex) and its path under
# build-fuzz/artifacts/<target>/ - fix the bug and commit the input to
# tests/fuzz/regressions/<target>/, where the ctest test fuzz.replay.<target> replays it.
#
# usage: ci/fuzz.sh                    deterministic (CI)
#        ci/fuzz.sh --explore SECONDS  exploratory: SECONDS a target, a time-based seed, a 10 s timeout
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
explore=""
case "${1:-}" in
  "") ;;
  --explore)
    explore="${2:-}"
    if ! [[ "$explore" =~ ^[1-9][0-9]*$ ]]; then echo "ci/fuzz.sh: --explore needs a number of seconds" >&2; exit 2; fi ;;
  *) echo "usage: ci/fuzz.sh [--explore SECONDS]" >&2; exit 2 ;;
esac
# Inputs a target runs in the deterministic mode (about half a minute each here, a regression check;
# exploration is --explore; see docs/ROBUSTNESS.md).
declare -A runs=([settings]=200000 [exr_depth]=100000 [codegen_parser]=4000 [scene_file]=175000)
build="${SAO_FUZZ_BUILD_DIR:-build-fuzz}"
targets=(settings exr_depth codegen_parser scene_file)

cxx="$(command -v clang++-14 || command -v clang++ || true)"
cc="$(command -v clang-14 || command -v clang || true)"
if [ -z "$cxx" ]; then echo "ci/fuzz.sh: clang++ not found (ci/setup.sh installs clang-14)" >&2; exit 1; fi
symbolizer="$(command -v llvm-symbolizer-14 || command -v llvm-symbolizer || true)"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi

# -fno-sanitize=vptr: glslang (Debian) is built without RTTI, the vptr check needs its typeinfo.
flags="-O1 -g1 -fno-omit-frame-pointer -fsanitize=address,undefined,fuzzer-no-link -fno-sanitize=vptr -fno-sanitize-recover=all"
source ci/host_shaderc.sh  # the effect's generation: 140 s of the 2 cores here with the instrumented tool
if [ ! -f "$build/CMakeCache.txt" ]; then
  mkdir -p "$build"
  cmake -S . -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=None \
    -DCMAKE_C_COMPILER="$cc" -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DSAO_BUILD_FUZZERS=ON -DSAO_BUILD_TESTS=OFF -DSAO_BUILD_SAMPLES=OFF -DSAO_BUILD_GL=OFF -DSAO_BUILD_VULKAN=OFF \
    -DSAO_HOST_SHADERC="$host_shaderc" \
    >"$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
fi
use_host_shaderc "$build"
cmake --build "$build" --parallel "$(nproc)" --target "${targets[@]/#/fuzz_}"

export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
if [ -n "$symbolizer" ]; then export ASAN_SYMBOLIZER_PATH="$symbolizer"; fi

# libFuzzer's comparison tracing feeds operand values into its mutations, and some operands are
# addresses: with address-space randomisation the same seed would explore differently on every
# run. setarch -R turns it off for the fuzzer, so a run is reproducible input for input.
no_aslr=()
if [ -z "$explore" ]; then
  if setarch "$(uname -m)" -R true 2>/dev/null; then
    no_aslr=(setarch "$(uname -m)" -R)
  else
    echo "ci/fuzz.sh: warning: cannot turn off address-space randomisation (setarch -R); runs are not reproducible input for input" >&2
  fi
fi

summary=()
status=0
for t in "${targets[@]}"; do
  work="$build/corpus/$t"
  artifacts="$build/artifacts/$t"
  rm -rf "$work" "$artifacts"
  mkdir -p "$work" "$artifacts"
  seeds=("tests/fuzz/corpus/$t" "tests/fuzz/regressions/$t")
  if [ "$t" = codegen_parser ]; then
    extra="$build/seeds/$t"
    rm -rf "$extra"
    mkdir -p "$extra"
    cp effect/sao.glsl tests/codegen/mini/mini.glsl "$extra/"
    cp tests/codegen/malformed/*.glsl "$extra/"
    seeds+=("$extra")
  fi
  if [ -n "$explore" ]; then
    budget=(-max_total_time="$explore" -timeout=10)
    what="${explore} s"
  else
    budget=(-runs="${runs[$t]}" -seed=1 -timeout=120 -reload=0)
    what="${runs[$t]} runs, seed 1"
  fi
  echo "== fuzz_$t: $what from ${seeds[*]}"
  log="$build/fuzz_$t.log"
  start=$SECONDS
  set +e
  "${no_aslr[@]}" "$build/bin/fuzz_$t" "${budget[@]}" -rss_limit_mb=2560 -malloc_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix="$artifacts/" "$work" "${seeds[@]}" >"$log" 2>&1
  rc=$?
  set -e
  took=$((SECONDS - start))
  execs=$(grep -E '^stat::number_of_executed_units' "$log" | awk '{print $2}' | tail -1)
  rate=$(grep -E '^stat::average_exec_per_sec' "$log" | awk '{print $2}' | tail -1)
  cov=$(grep -E '^#[0-9]+' "$log" | tail -1 | grep -oE 'cov: [0-9]+' | awk '{print $2}')
  units=$(find "$work" -type f | wc -l)
  if [ $rc -ne 0 ]; then
    status=1
    echo "fuzz_$t FAILED (exit $rc); the input is in $artifacts:"
    ls -l "$artifacts"
    grep -E 'ERROR|SUMMARY|invariant broken|runtime error' "$log" | head -20 || true
    for a in "$artifacts"/*; do
      [ -f "$a" ] || continue
      echo "-- $a ($(stat -c %s "$a") bytes), first 4 KiB:"
      head -c 4096 "$a" | od -A d -t x1 | head -64
    done
    echo "(full log: $log)"
  fi
  summary+=("$(printf '%-16s %5s s %12s execs %8s execs/s %6s edges %6s corpus  %s' "$t" "$took" "${execs:-?}" \
    "${rate:-?}" "${cov:-?}" "$units" "$([ $rc -eq 0 ] && echo ok || echo FAILED)")")
done
# A crashed target leaves its scratch folder (fuzz_support.h) behind: remove those of dead processes.
for d in /dev/shm/sao_fuzz_* "${TMPDIR:-/tmp}"/sao_fuzz_*; do
  [ -d "$d" ] || continue
  kill -0 "${d##*_}" 2>/dev/null || rm -rf "$d"
done
# Kept in $build/fuzz_summary.txt too, for the figures in docs/ROBUSTNESS.md.
{
  mode="deterministic: fixed runs, seed 1"
  if [ -n "$explore" ]; then mode="exploratory: $explore s a target"; fi
  echo "== fuzz summary (clang $("$cxx" -dumpversion), address + undefined, libFuzzer; $mode)"
  printf '%s\n' "${summary[@]}"
} | tee "$build/fuzz_summary.txt"
exit $status
