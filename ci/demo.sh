#!/usr/bin/env bash
# One command on a fresh machine: install, build, run the main job on the default scene.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash ci/setup.sh
bash ci/build.sh
out="$root/out/demo"
# The main job: the built-in default scene at 1280x720 on the best backend that starts.
build/bin/sao-render --out "$out" --json
echo "Open $out/ao.png (ambient obscurance) and $out/lit.png / $out/lit_no_ao.png (lit with and without it)."
