#!/usr/bin/env bash
# Configures and builds into build/ (Release with assertions kept by tests' own checks). Debug
# information is line tables only (-g1): stack traces keep file:line, at about 30 % less compile
# time than -g (measured on a codegen and a test source: 4.7 -> 2.7 s, 2.6 -> 1.9 s).
# usage: ci/build.sh [--target T...] [cmake configure args...]: --target builds only those targets.
set -euo pipefail
targets=()
if [ "${1:-}" = "--target" ]; then
  shift
  targets=(--target)
  while [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; do targets+=("$1"); shift; done
fi
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" "$@"
fi
cmake --build build --parallel "$(nproc)" "${targets[@]}"
