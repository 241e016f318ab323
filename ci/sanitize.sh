#!/usr/bin/env bash
# Stage "sanitizers": the project (all but tests/walkthrough) and its tests built with AddressSanitizer (+ leak
# checking) and UndefinedBehaviorSanitizer (gcc) into build-asan/, then every ctest test run with
# halt_on_error. Leaks inside Mesa (llvmpipe, lavapipe, LLVM), the Vulkan loader and validation
# layer, and a few other system libraries are suppressed by tests/sanitizers/lsan.supp (each entry
# says why); a leak whose stack holds no such library - ours - fails the test.
# usage: ci/sanitize.sh [ctest args...]   (SAO_ASAN_BUILD_DIR overrides the build folder)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
build="${SAO_ASAN_BUILD_DIR:-build-asan}"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi

# -fno-sanitize=vptr: glslang (Debian's static libraries, used by sao-shaderc) is built without RTTI,
# and the vptr check needs the typeinfo of its classes. float-cast-overflow is not part of gcc's
# "undefined" group: asked for explicitly (double -> int/float conversions of extreme values).
sanitizers="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize=vptr -fno-sanitize-recover=all"
# -g1: line tables only, all a sanitizer report needs (file:line per frame), and a faster build.
flags="-O1 -g1 -fno-omit-frame-pointer $sanitizers"
# The instrumented sao-shaderc still runs over the whole effect, in
# Shaderc.OutputIsDeterministicAndHoldsNoAbsolutePaths.
source ci/host_shaderc.sh
if [ ! -f "$build/CMakeCache.txt" ]; then
  mkdir -p "$build"
  cmake -S . -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="$sanitizers" -DCMAKE_SHARED_LINKER_FLAGS="$sanitizers" \
    -DSAO_BUILD_WALKTHROUGH=OFF -DSAO_HOST_SHADERC="$host_shaderc" \
    >"$build/configure.log" 2>&1 || { cat "$build/configure.log"; exit 1; }
fi
use_host_shaderc "$build"

# intercept_tls_get_addr=0: gcc 12's runtime takes a dynamic TLS block (of a dlopen()ed library: Mesa's
# drivers, the Vulkan layers) for a pre-2.25 glibc one when its address happens to end in the old header's size,
# reads garbage bounds, and LeakSanitizer's tracer dies at exit ("Tracer caught signal 11") with no
# leak found: a flake that failed apps_render_progress once (google/sanitizers#1322, fixed in gcc
# 14 / LLVM 17). Dynamic TLS blocks are then not scanned for pointers; sao's thread_local data lives in
# static TLS (libraries loaded at startup), which is still scanned.
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=1:intercept_tls_get_addr=0"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
symbolizer="$(command -v llvm-symbolizer-14 || command -v llvm-symbolizer || true)"
if [ -n "$symbolizer" ]; then export ASAN_SYMBOLIZER_PATH="$symbolizer"; fi
# Instrumented tests can tell (SAO_SANITIZED) that RSS is meaningless under the allocator's quarantine.
export SAO_SANITIZED=1

cmake --build "$build" --parallel "$(nproc)"

# Libraries dlopen()ed by Mesa and the Vulkan loader stay loaded until exit (see keep_loaded.c), so
# that leak reports name their module. The preload is not instrumented; ASan, linked into every
# test program, does not come first in the library list then, which is fine for this one function.
cc -shared -fPIC -O2 -o "$build/libsao_keep_loaded.so" tests/sanitizers/keep_loaded.c
export LD_PRELOAD="$root/$build/libsao_keep_loaded.so${LD_PRELOAD:+:$LD_PRELOAD}"
export ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"
ctest --test-dir "$build" --output-on-failure --timeout 900 -j "$(nproc)" "$@"
