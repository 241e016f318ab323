#!/bin/sh
# Symbol hygiene of a shared library (docs/ROBUSTNESS.md):
#  - every defined dynamic symbol is in the sao namespace (functions, vtables, typeinfo of sao::);
#  - no gl*, vk*, egl* symbol, defined or undefined: entry points come from the caller's loader;
#  - no DT_NEEDED on a GL, EGL, GLX, epoxy or Vulkan loader library.
# usage: check_exports.sh NM CXXFILT READELF LIBRARY
set -eu
nm=$1 cxxfilt=$2 readelf=$3 lib=$4
fail=0
defined=$("$nm" -D --defined-only "$lib" | awk 'NF >= 3 { print $3 }')
[ -n "$defined" ] || { echo "$lib: no defined dynamic symbols at all"; exit 1; }
n=$(echo "$defined" | wc -l)
outside=$(echo "$defined" | "$cxxfilt" | grep -Ev '^((vtable|typeinfo|typeinfo name|VTT|guard variable) for )?sao::' || true)
if [ -n "$outside" ]; then
  echo "$lib exports symbols outside the sao namespace:"
  echo "$outside" | sed 's/^/  /'
  fail=1
fi
api=$("$nm" -D "$lib" | awk '{ print $NF }' | sed 's/@.*//' | grep -E '^_?(gl|GL|vk|Vk|egl|EGL)[A-Z_]' || true)
if [ -n "$api" ]; then
  echo "$lib defines or imports graphics-API symbols (they must come from the caller's getProcAddress):"
  echo "$api" | sed 's/^/  /'
  fail=1
fi
needed=$("$readelf" -d "$lib" | grep NEEDED | grep -Ei 'lib(GL|GLX|EGL|OpenGL|GLES|epoxy|vulkan)[._]' || true)
if [ -n "$needed" ]; then
  echo "$lib links a graphics-API library:"
  echo "$needed" | sed 's/^/  /'
  fail=1
fi
[ $fail -eq 0 ] && echo "$lib: $n exported symbols, all in namespace sao; no gl*/vk*/egl* symbol; no GL/EGL/Vulkan library needed"
exit $fail
