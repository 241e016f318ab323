#!/usr/bin/env bash
# Stage "install + consumer": installs the build tree's libraries and headers into a prefix, then
# configures, builds and runs (ctest) the consumer project tests/package against that prefix only
# (find_package(sao CONFIG) -> sao::core, sao::gl, sao::vulkan).
# usage: ci/package.sh [BUILD_DIR]   (default build; the prefix and consumer trees go beside it)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
build="${1:-build}"
prefix="$root/$build-install"
consumer="$root/$build-consumer"
generator=()
if command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi

rm -rf "$prefix" "$consumer"
cmake --install "$build" --prefix "$prefix" >/dev/null
echo "installed into $prefix:"
(cd "$prefix" && find . \( -type f -o -type l \) | sort | sed 's/^\.\//  /')

# The package must not point back into the source or build tree.
if grep -rn -e "$root/backends" -e "$root/$build" "$prefix/lib/cmake/sao"; then
  echo "ci/package.sh: the installed CMake package refers to the source or build tree (above)" >&2
  exit 1
fi

mkdir -p "$consumer"
cmake -S tests/package -B "$consumer" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_PREFIX_PATH="$prefix" >"$consumer/configure-output.log" 2>&1 || { cat "$consumer/configure-output.log"; exit 1; }
grep -E "^-- sao " "$consumer/configure-output.log" || true
cmake --build "$consumer" --parallel "$(nproc)"
ctest --test-dir "$consumer" --output-on-failure
