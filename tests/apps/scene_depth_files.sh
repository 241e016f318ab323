#!/bin/sh
# The built-in scenes' depth buffers as files with their cameras (sao-render --save-depth, Embree
# primary rays: the same on every machine), for the engine-side executor example
# (samples/integration/vk_engine_executor.cpp) in the tree and against the installed package
# (ci/package.sh reuses them).
# usage: scene_depth_files.sh SAO_RENDER OUT_DIR
set -eu
render=$1
out=$2
rm -rf "$out"
mkdir -p "$out"
for scene in sponza-like sphere-plane crease thin gears; do
  "$render" --backend cpu --depth-source raytrace --scene "$scene" --size 320x180 --guard 8 \
    --save-depth "$out/$scene.exr" --out "$out/render-$scene" >/dev/null
  rm -rf "$out/render-$scene"
done
ls "$out"
