#!/bin/sh
# Orthographic cameras through sao-render:
#   - --ortho HEIGHT with --eye/--target on sphere-plane (looking down) and the crease (obliquely),
#     beside --fovy views of the same framing, with --reference: finite error figures, the ortho
#     RMSE vs the near-field reference within 1.5x the perspective one + 0.02, and the summary
#     names the projection;
#   - the same ortho view with the depth rasterised (the GL prepass) and ray-cast: the same AO
#     within one binary16 step;
#   - a .scene view `ortho H` (tests/scenes/data/boxes_ortho.scene) renders, and its saved depth
#     EXR carries the orthographic camera (rendered again from the file: the same AO);
#   - a depth file without a camera takes --ortho with a finite --far;
#   - bad --ortho values and combinations exit 2 with one line.
# Usage: render_ortho.sh SAO_RENDER AO_EXR_COMPARE SCENE_DATA_DIR WORK_DIR
set -u
render=$1 compare=$2 data=$3 work=$4
rm -rf "$work" && mkdir -p "$work" || exit 1
fail=0
problem() { echo "FAIL: $*"; fail=1; }

# run NAME ARGS...: renders into $work/NAME with --json (stdout and stderr in $work/NAME.log);
# scenes at 160x90 (a depth file has its own size).
run() {
  name=$1
  shift
  case " $* " in *" --depth "*) size="" ;; *) size="--size 160x90" ;; esac
  "$render" --backend cpu $size --json --out "$work/$name" "$@" > "$work/$name.log" 2>&1 ||
    { problem "$name: sao-render failed:"; cat "$work/$name.log"; }
}

# The raw RMSE vs the reference of a run, from summary.json ("nan" when missing).
rmse() {
  python3 -c 'import json, sys
r = json.load(open(sys.argv[1])).get("reference")
v = r["raw"]["rmse"] if r else None
print(v if isinstance(v, (int, float)) else "nan")' "$work/$1/summary.json"
}

# compare PERSPECTIVE ORTHO: both finite, ortho <= 1.5 x perspective + 0.02.
compare_rmse() {
  p=$(rmse "$1") o=$(rmse "$2")
  echo "$1: RMSE $p   $2: RMSE $o"
  python3 -c 'import math, sys
p, o = float(sys.argv[1]), float(sys.argv[2])
sys.exit(0 if math.isfinite(p) and math.isfinite(o) and o <= 1.5 * p + 0.02 else 1)' "$p" "$o" ||
    problem "$2: RMSE $o not finite or not within 1.5 x $p + 0.02"
}

ref="--reference --reference-rays 64"
# sphere-plane from above (its "top" view's eye and target; 0.9 rad = 51.566 degrees spans 6.79 at
# the target distance 7.018).
run sp_persp --scene sphere-plane --eye 0.01,7,0.5 --target 0,0,0 --fovy 51.566 $ref
run sp_ortho --scene sphere-plane --eye 0.01,7,0.5 --target 0,0,0 --ortho 6.79 $ref
compare_rmse sp_persp sp_ortho
# The crease obliquely, the eye far enough back that the view plane clears the floor.
run crease_persp --scene crease --eye 0,6,2 --target 0,0,-10 --fovy 30 $ref
run crease_ortho --scene crease --eye 0,6,2 --target 0,0,-10 --ortho 7.19 $ref
compare_rmse crease_persp crease_ortho

grep -q '^projection: orthographic, view height 6.79 (view units), near 0.1, far ' "$work/sp_ortho/summary.txt" ||
  problem "sp_ortho: summary.txt does not give the orthographic projection"
grep -q '^projection: perspective, fovy 51.566 degrees' "$work/sp_persp/summary.txt" ||
  problem "sp_persp: summary.txt does not give the perspective projection"
python3 -c 'import json, sys
s = json.load(open(sys.argv[1]))
assert s["projection"].startswith("orthographic"), s["projection"]
assert "finite far" in s["input"], s["input"]' "$work/sp_ortho/summary.json" || problem "sp_ortho: summary.json"

# Rasterised and ray-cast depth of the ortho view: the same AO (the depth agrees to float precision).
run crease_raster --scene crease --eye 0,6,2 --target 0,0,-10 --ortho 7.19 --depth-source raster
run crease_raytrace --scene crease --eye 0,6,2 --target 0,0,-10 --ortho 7.19 --depth-source raytrace
if grep -q "depth rasterised" "$work/crease_raster/summary.txt"; then
  "$compare" "$work/crease_raster/ao.exr" "$work/crease_raytrace/ao.exr" 1 || problem "raster and ray-cast ortho AO differ"
else
  echo "no rasterising prepass here: raster/ray-cast comparison skipped"
fi

# A scene file's ortho view, its depth saved with the camera and rendered again from the file.
run boxes_ortho --scene "$data/boxes_ortho.scene" --view 1 --save-depth "$work/boxes_ortho.exr"
grep -q "view 1 'top'" "$work/boxes_ortho/summary.txt" || problem "boxes_ortho: not view 1 'top'"
grep -q '^projection: orthographic, view height 3 ' "$work/boxes_ortho/summary.txt" ||
  problem "boxes_ortho: the scene file's view is not orthographic with height 3"
run boxes_ortho_file --depth "$work/boxes_ortho.exr"
grep -q '^projection: orthographic, view height 3 ' "$work/boxes_ortho_file/summary.txt" ||
  problem "the saved depth EXR lost the orthographic camera"
"$compare" "$work/boxes_ortho/ao.exr" "$work/boxes_ortho_file/ao.exr" 0 || problem "AO from the saved depth differs"

# Refusals: exit 2, one line naming the problem.
reject() {  # SUBSTRING ARGS...
  want=$1
  shift
  "$render" --backend cpu --out "$work/rejected" "$@" > "$work/reject.out" 2> "$work/reject.err"
  rc=$?
  echo "$* -> $rc: $(cat "$work/reject.err")"
  [ "$rc" -eq 2 ] && [ "$(wc -l < "$work/reject.err")" -eq 1 ] && grep -qF -e "$want" "$work/reject.err" &&
    [ ! -e "$work/rejected" ] || problem "want exit 2 and one line with '$want'"
}
view="--scene crease --eye 0,6,2 --target 0,0,-10"
reject "--ortho expects a view height > 0, got '0'" $view --ortho 0
reject "--ortho expects a view height > 0, got '-2'" $view --ortho=-2
reject "--ortho" $view --ortho abc
reject "--ortho" $view --ortho inf
reject "--ortho and --fovy exclude each other" $view --ortho 3 --fovy 40
reject "--ortho has no effect without --eye" --scene crease --ortho 3
# A depth file without a camera (an AO output) takes --ortho with a finite --far.
reject "--ortho/--near/--far: " --depth "$work/boxes_ortho/ao.exr" --ortho 3
run ao_as_depth --depth "$work/boxes_ortho/ao.exr" --ortho 3 --near 0.1 --far 50
grep -q '^projection: orthographic, view height 3 (view units), near 0.1, far 50' "$work/ao_as_depth/summary.txt" ||
  problem "--depth with --ortho: the projection is not orthographic"
exit $fail
