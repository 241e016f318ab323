#!/usr/bin/env bash
# Stage "install + consumer": installs the build tree's libraries and headers into a prefix, then
# configures, builds and runs (ctest) the consumer project tests/package against that prefix only,
# once per component (find_package(sao CONFIG COMPONENTS <c>) -> sao::core, sao::io, sao::gl,
# sao::vulkan) with the other components' dependencies made unfindable
# (CMAKE_DISABLE_FIND_PACKAGE_<Pkg>), and checks that a component whose dependency is missing is
# refused with a message naming it.
# usage: ci/package.sh [BUILD_DIR]   (default build; the prefix and consumer trees go beside it:
#        BUILD_DIR-install/, BUILD_DIR-consumer/<component>/, BUILD_DIR-consumer/refused-*/)
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
(cd "$prefix" && find . \( -type f -o -type l \) -not -path './share/sao/shaders/*' | sort | sed 's/^\.\//  /')
echo "  share/sao/shaders/: $(find "$prefix/share/sao/shaders" -name '*.spv' | wc -l) SPIR-V and" \
     "$(find "$prefix/share/sao/shaders" -name '*.glsl' | wc -l) GLSL files, sao_passes.json"
test -s "$prefix/share/sao/shaders/sao_passes.json" || { echo "ci/package.sh: no sao_passes.json installed" >&2; exit 1; }

# The package must not point back into the source or build tree.
if grep -rn -e "$root/backends" -e "$root/$build" "$prefix/lib/cmake/sao"; then
  echo "ci/package.sh: the installed CMake package refers to the source or build tree (above)" >&2
  exit 1
fi

# File I/O lives in sao::io only: sao::core and the backends neither call OpenEXR or stb nor
# link them.
for lib in "$prefix"/lib/libsao_core.a "$prefix"/lib/libsao_effect.a "$prefix"/lib/libsao_gl.so \
           "$prefix"/lib/libsao_vulkan.so; do
  [ -e "$lib" ] || continue
  if nm -u -C "$lib" 2>/dev/null | grep -E "Imf_|Imf::|Imath|exr_|stbi_" | head -5 | grep .; then
    echo "ci/package.sh: $(basename "$lib") refers to OpenEXR or stb (above); that is sao::io's job" >&2
    exit 1
  fi
  if [[ "$lib" == *.so ]] && readelf -d "$lib" | grep -E "NEEDED.*(OpenEXR|Imath|Iex|stb)"; then
    echo "ci/package.sh: $(basename "$lib") links OpenEXR or stb (above)" >&2
    exit 1
  fi
done

# What each component needs found, beyond sao (the package for the library, the consumer program
# for its own use: EGL for gl and gles, the loader for vulkan); every other component's list is disabled.
declare -A needs=([core]="" [io]="OpenEXR Imath PkgConfig" [cpu]="" [gl]="OpenGL" [gles]="OpenGL" [vulkan]="Vulkan")
components=$(sed -n 's/^set(sao_AVAILABLE_COMPONENTS \(.*\))$/\1/p' "$prefix/lib/cmake/sao/saoConfig.cmake" |
  tr ';' ' ')
echo "components: $components"
disabled_for() {  # the -DCMAKE_DISABLE_FIND_PACKAGE_<Pkg>=ON of every component but $1 (not $1's own: gl and gles share OpenGL)
  local c pkg
  for c in "${!needs[@]}"; do
    [ "$c" = "$1" ] && continue
    for pkg in ${needs[$c]}; do
      [[ " ${needs[$1]} " == *" $pkg "* ]] || echo "-DCMAKE_DISABLE_FIND_PACKAGE_$pkg=ON"
    done
  done | sort -u
}

for c in $components; do
  dir="$consumer/$c"
  mkdir -p "$dir"
  mapfile -t disabled < <(disabled_for "$c")
  echo "== consumer '$c' (${disabled[*]:-nothing disabled})"
  cmake -S tests/package -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_PREFIX_PATH="$prefix" -DSAO_CONSUMER_COMPONENTS="$c" "${disabled[@]}" \
    >"$dir/configure-output.log" 2>&1 || { cat "$dir/configure-output.log"; exit 1; }
  grep -E "^-- sao " "$dir/configure-output.log" || true
  cmake --build "$dir" --parallel "$(nproc)"
  ctest --test-dir "$dir" --output-on-failure
done

# An engine's own renderer: the engine-side executor example against the installed sao::core,
# sao::io and sao::cpu and the Vulkan loader (no sao::vulkan, OpenGL unfindable), on the built-in
# scenes' depth files the build tree's fixture wrote (the release stage runs it).
depth="$root/$build/tests/apps/scene_depth"
if [ "$(ls "$depth"/*.exr 2>/dev/null | wc -l)" -lt 5 ]; then
  echo "ci/package.sh: no scene depth files in $depth: run ctest --test-dir $build -R apps_scene_depth_files" >&2
  exit 1
fi
dir="$consumer/engine"
mkdir -p "$dir"
echo "== consumer 'engine' (io cpu + the Vulkan loader; -DCMAKE_DISABLE_FIND_PACKAGE_OpenGL=ON)"
cmake -S tests/package -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_PREFIX_PATH="$prefix" "-DSAO_CONSUMER_COMPONENTS=io;cpu" -DSAO_CONSUMER_SCENE_DEPTH="$depth" \
  -DCMAKE_DISABLE_FIND_PACKAGE_OpenGL=ON >"$dir/configure-output.log" 2>&1 || { cat "$dir/configure-output.log"; exit 1; }
cmake --build "$dir" --parallel "$(nproc)"
ctest --test-dir "$dir" --output-on-failure
ctest --test-dir "$dir" -R example_vulkan_engine -V | grep -E "p99.9|validation:"

# A component whose own dependency is unfindable is refused with a message naming what is missing
# (stb is found through pkg-config), and so is a component the package does not have.
# component:package made unfindable:what the message must say
for refusal in "io:OpenEXR:component 'io' needs OpenEXR" "io:PkgConfig:component 'io' needs stb" \
               "vulkan:Vulkan:component 'vulkan' needs Vulkan" "metal::no component 'metal'"; do
  IFS=: read -r c pkg expected <<<"$refusal"
  [[ "$c" == metal || " $components " == *" $c "* ]] || continue
  dir="$consumer/refused-$c${pkg:+-$pkg}"
  disable=()
  [ -n "$pkg" ] && disable=("-DCMAKE_DISABLE_FIND_PACKAGE_$pkg=ON")
  mkdir -p "$dir"
  if cmake -S tests/package -B "$dir" "${generator[@]}" -DCMAKE_PREFIX_PATH="$prefix" \
       -DSAO_CONSUMER_COMPONENTS="$c" "${disable[@]}" >"$dir/configure-output.log" 2>&1; then
    echo "ci/package.sh: COMPONENTS $c was found${pkg:+ with $pkg disabled}" >&2
    exit 1
  fi
  if ! grep -q "$expected" "$dir/configure-output.log"; then
    cat "$dir/configure-output.log"
    echo "ci/package.sh: COMPONENTS $c ${pkg:+without $pkg }failed without saying \"$expected\"" >&2
    exit 1
  fi
  echo "== COMPONENTS $c${pkg:+ with $pkg disabled}: refused, \"$expected\""
done
