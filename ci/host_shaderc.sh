# Sourced by ci/sanitize.sh and ci/fuzz.sh (with $root set): their trees generate shaders with the
# release build's sao-shaderc (SAO_HOST_SHADERC, see codegen/CMakeLists.txt), since an instrumented
# tool spends most of its time in the sanitizer's allocator. Builds it in build/ (or brings it up
# to date) and sets host_shaderc; use_host_shaderc DIR points a configured tree at it.
bash "$root/ci/build.sh" --target sao-shaderc
host_shaderc="$root/build/bin/sao-shaderc"
use_host_shaderc() {
  if grep -qxF "SAO_HOST_SHADERC:FILEPATH=$host_shaderc" "$1/CMakeCache.txt"; then return 0; fi
  cmake -S "$root" -B "$1" -DSAO_HOST_SHADERC="$host_shaderc" >"$1/configure.log" 2>&1 ||
    { cat "$1/configure.log"; return 1; }
}
