#!/bin/sh
# sao-render's depth convention warnings (samples/common/include/sao/samples/depth_convention.h),
# each on stderr ("sao-render: warning: "), in summary.txt and summary.json, exit status 0, and
# without the units/radius warnings a wrong convention would set off:
#   - no geometry: a camera whose near plane lies beyond the scene, a depth file all sky;
#   - LinearZ holding positive distances (--depth-distances);
#   - a reversed-Z file read as standard, a standard one read with --reversed-z, linear depth
#     normalised to [0, 1] read as window depth;
#   - no warning: every built-in scene as rendered, and camera-less files of two scenes in D16, D24
#     and D32F, perspective and orthographic, read with their right convention (both of them);
#   - --help describes them and what cannot be told.
# depth_convention_file (depth_convention_file.cpp) makes the files other tools would write.
# Usage: depth_convention_warnings.sh SAO_RENDER DEPTH_CONVENTION_FILE WORK_DIR
set -u
render=$1 convert=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
fail=0

# case NAME "WARNING TEXT|..." ARGS...: the warnings expected, '|'-separated, in that order (empty:
# none); each a fixed string its line contains, or parts " ... " apart that it contains in order.
case_() {
  run=$1 expected=$2; shift 2
  if ! "$render" --backend cpu --json --out "$work/$run" "$@" > /dev/null 2> "$work/$run.err"; then
    echo "FAIL: $run: exit status not 0:"; cat "$work/$run.err"; fail=1; return
  fi
  python3 - "$work/$run" "$expected" <<'EOF' || fail=1
import json, sys
out, expected = sys.argv[1], [w for w in sys.argv[2].split("|") if w]
prefix = "sao-render: warning: "
stderr = [l[len(prefix):] for l in open(out + ".err").read().splitlines() if l.startswith(prefix)]
text = [l[len("warning: "):] for l in open(out + "/summary.txt").read().splitlines() if l.startswith("warning: ")]
data = json.load(open(out + "/summary.json"))["warnings"]
def matches(e, w):
    at = 0
    for part in e.split(" ... "):
        at = w.find(part, at)
        if at < 0:
            return False
        at += len(part)
    return True
ok = len(stderr) == len(expected) and all(matches(e, w) for e, w in zip(expected, stderr)) and stderr == text == data
print(("ok: " if ok else "FAIL: ") + out + ": " + repr(stderr))
if not ok:
    print("  expected " + repr(expected) + "\n  summary.txt " + repr(text) + "\n  summary.json " + repr(data))
sys.exit(0 if ok else 1)
EOF
}

# file NAME SCENE_ARGS...: a scene's depth saved with its camera, as $work/NAME.exr.
file() {
  saved=$1; shift
  "$render" --backend cpu --size 160x90 --out "$work/$saved.run" --save-depth "$work/$saved.exr" "$@" > /dev/null 2>&1 ||
    { echo "FAIL: cannot save the depth of $*"; fail=1; }
}
# convert NAME MODE: $work/NAME.MODE.exr from $work/NAME.exr; prints its camera flags.
convert() { "$convert" "$work/$1.exr" "$work/$1.$2.exr" "$2" || { echo "FAIL: convert $1 $2" >&2; fail=1; }; }

no_geometry="no geometry: every one of the 14400 depth texels is sky"

# Zero geometry pixels always warn, naming the cause.
case_ near-beyond-scene "$no_geometry (all 0, the reversed-Z clear value), so the AO is 1 everywhere: nothing in view lies between the near plane (100 view units) and the far plane (inf): is the near plane (--near) beyond the scene" \
  --scene crease --size 160x90 --eye 0,3,-4 --target 0,0,-10 --near 100
file crease --scene crease
flags=$(convert crease sky)
# shellcheck disable=SC2086
case_ file-all-sky "$no_geometry (all 1, the standard clear value)" --depth "$work/crease.sky.exr" $flags
convert crease distances > /dev/null
case_ linearz-distances "$no_geometry, so the AO is 1 everywhere: all of them are positive ( ... ), which LinearZ reads as sky: LinearZ holds camera-space z, negative in front of the camera; positive distances along the view axis (e.g. a Blender Z pass) are read with --depth-distances" \
  --depth "$work/crease.distances.exr"

# The wrong convention named, and no units/radius warning.
flags=$(convert crease as-is)
# shellcheck disable=SC2086
case_ reversed-as-standard "the depth looks reversed-Z but is read as standard depth: ... give --reversed-z" \
  --depth "$work/crease.as-is.exr" $flags
flags=$(convert crease flipped)
# shellcheck disable=SC2086
case_ standard-as-reversed "the depth looks standard but is read as reversed-Z depth: ... leave out --reversed-z" \
  --depth "$work/crease.flipped.exr" $flags --reversed-z
file sphere-ortho --scene sphere-plane --eye 0,2,6 --target 0,0.5,0 --ortho 6
flags=$(convert sphere-ortho as-is)
# shellcheck disable=SC2086
case_ ortho-reversed-as-standard "the depth looks reversed-Z but is read as standard depth: ... texels are 0, reversed-Z depth's clear value (sky), and none is 1; give --reversed-z" \
  --depth "$work/sphere-ortho.as-is.exr" $flags
flags=$(convert crease linear01)
# shellcheck disable=SC2086
case_ linear-as-window "the depth looks linear in distance (normalised to [0, 1]?), not standard window depth" \
  --depth "$work/crease.linear01.exr" $flags

# No false alarm: every built-in scene as rendered (its scale warnings are none of these).
for scene in sponza-like sphere-plane crease thin gears; do
  "$render" --backend cpu --size 160x90 --out "$work/scene-$scene" --scene "$scene" > /dev/null 2> "$work/scene-$scene.err" ||
    { echo "FAIL: $scene"; fail=1; }
  if grep -E "depth looks|no geometry|texels are positive" "$work/scene-$scene.err"; then
    echo "FAIL: $scene: a depth convention warning"; fail=1
  else
    echo "ok: $scene as rendered"
  fi
done
# ... and camera-less files in each format, perspective and orthographic, each read with its own
# convention (the scene's reversed-Z with --reversed-z, its flipped copy without).
for scene in sphere-plane sponza-like; do
  for format in D16 D24 D32F; do
    for ortho in "" "--ortho 6"; do
      name=$scene-$format${ortho:+-ortho}
      # shellcheck disable=SC2086
      file "$name" --scene "$scene" --depth-format "$format" ${ortho:+--eye 0,2,6 --target 0,0.5,0 $ortho}
      flags=$(convert "$name" as-is)
      # shellcheck disable=SC2086
      case_ "$name-reversed" "" --depth "$work/$name.as-is.exr" $flags --reversed-z
      flags=$(convert "$name" flipped)
      # shellcheck disable=SC2086
      case_ "$name-standard" "" --depth "$work/$name.flipped.exr" $flags
    done
  done
done
# --help says what is warned about and what cannot be told.
if "$render" --help | grep -q "Depth values that do not fit the conventions they are read with are warned" &&
   "$render" --help | grep -q "Not detectable: the Z convention of orthographic depth without sky"; then
  echo "ok: --help"
else
  echo "FAIL: --help does not describe the depth convention warnings"; fail=1
fi
exit $fail
