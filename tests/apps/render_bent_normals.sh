#!/bin/sh
# sao-render writes the bent normal (the setting bent_normals, visibility estimator, direct path):
# bent_normal.exr (camera space, X Y Z) and bent_normal.png (0.5 + 0.5 b), listed among its outputs,
# on every backend, the backends agreeing with the CPU reference (bent normal within 8 binary16
# steps or 1e-5: a component near 0 is the difference of larger terms, its rounding absolute; A
# within 1 step); a run without the setting writes neither file.
#
#   render_bent_normals.sh SAO_RENDER AO_EXR_COMPARE WORK_DIR
set -eu
render=$1 compare=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
bent="--set estimator=1 --set bent_normals=true --set blur_radius=0 --resolution-divisor 1"
for scene in crease gears; do
  for backend in cpu gl vulkan; do
    out="$work/$scene-$backend"
    # shellcheck disable=SC2086  # $bent is a list of options
    "$render" --backend "$backend" --scene "$scene" --size 200x120 $bent --out "$out" >/dev/null
    for file in bent_normal.exr bent_normal.png; do
      test -s "$out/$file" || { echo "$out/$file missing"; exit 1; }
      grep -qx "$file" "$out/sao-render-outputs.txt" || { echo "$file not listed in $out"; exit 1; }
    done
    grep -q "^passes: linear_z ao_sample_output$" "$out/summary.txt" || { echo "not the direct path: $out"; exit 1; }
  done
  for backend in gl vulkan; do
    "$compare" "$work/$scene-cpu/bent_normal.exr" "$work/$scene-$backend/bent_normal.exr" 8 0 1e-5
    "$compare" "$work/$scene-cpu/ao.exr" "$work/$scene-$backend/ao.exr" 1
  done
done
"$render" --backend cpu --scene crease --size 200x120 --set estimator=1 --out "$work/without" >/dev/null
if ls "$work/without" | grep -q bent_normal; then echo "bent_normal written without the setting"; exit 1; fi
echo "bent normals written and agreeing on cpu, gl and vulkan"
