#!/usr/bin/env bash
# One command on a fresh machine: install, build, run the main job on the default scene.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash ci/setup.sh
bash ci/build.sh
out="$root/out/demo"
if [ -x build/bin/sao-render ]; then
  build/bin/sao-render --out "$out"
else
  # The renderer does not exist yet: run the codegen on the real effect and show what it made.
  rm -rf "$out" && mkdir -p "$out"
  build/bin/sao-shaderc effect/sao.glsl -o "$out"
  echo "sao-render is not built yet; ran the codegen instead."
  echo "Generated shaders and C++ glue: $out"
  ls "$out"
fi
