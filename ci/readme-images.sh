#!/usr/bin/env bash
# Remakes the images README.md shows, with the project's own commands (run after ci/build.sh):
# the AO and lit images of every built-in scene from sao-render, and a viewer screenshot when the
# viewer is built (it needs Xvfb).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bin="${SAO_BUILD_DIR:-build}/bin"
out=docs/images
mkdir -p "$out"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for scene in sponza-like sphere-plane crease thin gears; do
  "$bin/sao-render" --scene "$scene" --size 640x360 --preset high --out "$tmp/$scene" >/dev/null
  cp "$tmp/$scene/ao.png" "$out/$scene-ao.png"
  cp "$tmp/$scene/lit.png" "$out/$scene-lit.png"
done
cp "$tmp/sponza-like/lit_no_ao.png" "$out/sponza-like-lit-no-ao.png"
if [ -x "$bin/sao-viewer" ] && command -v xvfb-run >/dev/null; then
  xvfb-run -a -s "-screen 0 1280x800x24" "$bin/sao-viewer" --backend gl --size 1280x720 --view-mode split \
    --frames 5 --screenshot "$out/viewer.png" --overwrite >/dev/null
fi
echo "README images written to $out"
ls "$out"
