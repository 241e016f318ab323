#!/bin/sh
# sao-render refuses bad input (docs/ROBUSTNESS.md): for each row of the table below, the exit
# status (2 bad option, 1 failed run), nothing on stdout, exactly one line on stderr that starts
# with "sao-render: " and names the problem, and no output folder left behind.
#
#   render_rejects.sh SAO_RENDER WORK_DIR
#
# Rows run in WORK_DIR with relative paths, so WORK_DIR may hold spaces.
set -u
render=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")  # absolute: the rows run in WORK_DIR
work=$2
rm -rf "$work" && mkdir -p "$work/adir" "$work/dir.exr" "$work/theirs" && cd "$work" || exit 1
echo mine > theirs/notes.txt  # a folder sao-render did not write

# Depth files: a good one with its camera, then broken ones made from it.
"$render" --backend cpu --size 32x18 --scene crease --save-depth good.exr --out setup >/dev/null || exit 1
head -c 300 good.exr > truncated.exr
printf 'not an exr' > text.exr
: > empty.exr
mkfifo fifo.exr || exit 1
# Meshes (docs/ROBUSTNESS.md 4.8): only collinear triangles; a glTF 1.0 asset.
printf 'v 0 0 0\nv 1 1 1\nv 2 2 2\nv 3 3 3\nf 1 2 3\nf 2 3 4\n' > collinear.obj
printf '{"asset": {"version": "1.0"}, "meshes": {}}' > gltf1.gltf
# An earlier output whose summary.txt was replaced by a folder.
"$render" --backend cpu --size 32x18 --scene crease --out earlier >/dev/null && rm earlier/summary.txt &&
  mkdir earlier/summary.txt || exit 1
# The --reference row below must fail for --reference alone: the same run without it succeeds.
"$render" --backend cpu --depth good.exr --out control >/dev/null && test -s control/ao.png || {
  echo "control run on good.exr failed"; exit 1; }

fail=0
check() {  # RC SUBSTRING ARGS...
  want_rc=$1 want=$2
  shift 2
  rm -rf out
  # Rows name their own --backend when they test it; the last one given wins.
  "$render" --backend cpu --out out "$@" >stdout.txt 2>stderr.txt
  rc=$?
  err=$(cat stderr.txt)
  echo "$* -> $rc: $err"
  problem=""
  [ "$rc" -eq "$want_rc" ] || problem="exit status $rc, want $want_rc"
  [ -s stdout.txt ] && problem="$problem; wrote to stdout"
  [ "$(wc -l < stderr.txt)" -eq 1 ] || problem="$problem; stderr is not one line"
  case $err in "sao-render: "*) ;; *) problem="$problem; stderr does not start with 'sao-render: '" ;; esac
  printf '%s\n' "$err" | grep -qF -e "$want" || problem="$problem; stderr lacks '$want'"
  [ -e out ] && problem="$problem; the output folder was created"
  [ -z "$problem" ] || { echo "  FAIL:$problem"; fail=1; }
}

check 2 "unknown backend 'nosuch'" --backend nosuch
check 2 "unknown preset 'nosuch'" --preset nosuch
check 2 "--depth-format expects D16, D24 or D32F, got 'nosuch'" --depth-format nosuch
check 2 "unknown option '--nosuch'" --nosuch
check 2 "--size needs a value" --size
check 2 "--size width expects a whole number in [1, 16384], got '0'" --size 0x0
check 2 "--size height expects a whole number in [1, 16384], got '0'" --size 64x0
check 2 "--size expects WxH, got 'abc'" --size abc
check 2 "--size expects WxH, got '64'" --size 64
check 2 "--size needs a value" --size=
# Every value is checked, also one that a later one would replace.
check 2 "--size expects WxH, got 'abc'" --size abc --size 64x36
check 2 "--runs expects a whole number in [1, 1000], got '2.5'" --runs 2.5
check 2 "--reference-rays expects a whole number in [1, 65536], got '0'" --reference --reference-rays 0
check 2 "--eye expects X,Y,Z, got '1,2'" --eye 1,2 --target 0,0,-1
check 2 "--json takes no value (or true or false), got 'x'" --json=x
check 2 "unexpected argument 'stray'" stray
check 2 "got '20000'" --size 20000x20000
check 2 "got '99999999999'" --size 99999999999x2
check 2 "--guard expects a whole number in [0, 4096], got '5000'" --guard 5000
check 2 "--view 999 is out of range: scene 'sponza-like' has views 0.." --view 999
check 2 "--view 3 is out of range: scene 'crease' has views 0..0" --scene crease --view 3
check 2 "--view expects a whole number in [0, 1000], got '-1'" --view -1
check 2 "--clip expects gl or zero-one, got 'nosuch'" --clip nosuch
check 2 "--far expects a finite number, got 'abc'" --far abc
check 2 "expected name=value, got 'noequals'" --set noequals
check 2 "setting 'radius' is NaN" --set radius=nan
check 2 "setting 'samples' is +inf" --set samples=1e400
check 2 "unknown setting 'unknown'" --set unknown=1
check 2 "setting 'radius' = 1000 is outside its range [0.01, 100] m" --set radius=1000
check 2 "setting 'resolution_divisor' = 3 is not one of its allowed values {1, 2, 4}" --resolution-divisor 3
check 2 "setting 'resolution_divisor' = 3 is not one of its allowed values {1, 2, 4}" --set resolution_divisor=3
check 2 "setting 'epsilon' = 0.0100001 is outside its range [1e-06, 0.01] m^2" --set epsilon=0.01 --set epsilon=0.0100001
check 2 "--reference needs a scene, not a --depth file" --depth good.exr --reference
# Camera flags for a depth file without a camera (setup/ao.exr, 32x18): the real cause, not a
# "non-finite element", "set reversedZ = true" or a 4294967216-pixel viewport.
check 2 "--fovy/--near/--far: far distance 0.1 equals the near distance 0.1" --depth setup/ao.exr --near 0.1 --far 0.1
check 2 "--fovy/--near/--far: far distance 0.5 is nearer than the near distance 1" --depth setup/ao.exr --near 1 --far 0.5
check 2 "--guard 200 leaves no viewport inside the 32x18 depth file: at most 8" --depth setup/ao.exr --fovy 60 --guard 200
# Options that would have no effect in their combination.
check 2 "--depth needs a value, got an empty string" --depth ""
check 2 "--out needs a value, got an empty string" --out ""
check 2 "--scene needs a value, got an empty string" --scene ""
check 2 "--scene and --depth are two inputs" --depth good.exr --scene crease
check 2 "--size has no effect with --depth" --depth good.exr --size 64x36
check 2 "--eye has no effect with --depth" --depth good.exr --eye 0,3,-4 --target 0,0,-10
check 2 "--view has no effect with --depth" --depth good.exr --view 0
check 2 "--depth-format has no effect with --depth" --depth good.exr --depth-format D16
check 2 "--depth-source has no effect with --depth" --depth good.exr --depth-source raytrace
check 2 "--fovy has no effect: 'good.exr' carries its own camera" --depth good.exr --fovy 40
check 2 "--near has no effect: 'good.exr' carries its own camera" --depth good.exr --near 1
check 2 "--far has no effect: 'good.exr' carries its own camera" --depth good.exr --far 100
check 2 "--clip has no effect: 'good.exr' carries its own camera" --depth good.exr --clip gl
check 2 "--reversed-z has no effect: 'good.exr' carries its own camera" --depth good.exr --reversed-z
check 2 "--ortho has no effect: 'good.exr' carries its own camera" --depth good.exr --ortho 3
check 2 "--guard has no effect: 'good.exr' carries its own camera" --depth good.exr --guard 2
check 2 "--units has no effect: 'good.exr' carries its own camera" --depth good.exr --units cm
check 2 "--fovy has no effect without --eye" --scene crease --fovy 40
check 2 "--near has no effect without --eye" --scene crease --near 0.5
check 2 "--far is for a --depth file without a camera" --scene crease --far 100
check 2 "--clip is for a --depth file without a camera" --scene crease --clip gl
check 2 "--reversed-z is for a --depth file without a camera" --scene crease --reversed-z
check 2 "--far is for a --depth file without a camera" --scene crease --eye 0,3,-4 --target 0,0,-10 --far 100
check 2 "--view has no effect with --eye/--target" --scene crease --view 0 --eye 0,3,-4 --target 0,0,-10
check 2 "--reference-rays has no effect without --reference" --scene crease --reference-rays 8
check 2 "--runs expects a whole number in [1, 1000], got '0'" --runs 0
check 2 "--progress expects seconds in [0, 3600]" --progress -1
check 2 "--progress expects a finite number, got 'soon'" --progress soon
# Output paths, checked before anything is rendered (and the folders they would make removed).
check 2 "two outputs would be written to" --scene crease --dump-passes out/ao.png
check 2 "lies inside --dump-passes 'out'" --scene crease --out out/sub --dump-passes out
check 1 "its folder" --scene crease --save-depth missing/depth.exr
check 1 "--save-depth 'adir' is a folder" --scene crease --save-depth adir
check 1 "--dump-passes '/proc/x': cannot create a folder beside it" --scene crease --dump-passes /proc/x
check 1 "--out 'good.exr' exists and is not a folder" --scene crease --out good.exr
check 1 "is not empty and not an earlier sao-render output" --scene crease --out theirs
check 1 "holds 'summary.txt', which is not one of the files" --scene crease --out earlier
check 1 "unknown built-in scene 'nope'" --scene nope
check 1 "/nonexistent.glb: no such file" --scene /nonexistent.glb
check 1 "adir: is a directory" --scene adir
check 1 "collinear.obj: all its 2 triangles are degenerate" --scene collinear.obj
check 1 "gltf1.gltf: glTF 1.0 is not supported (glTF 2.0 only)" --scene gltf1.gltf
check 1 "/nonexistent/depth.exr: no such file" --depth /nonexistent/depth.exr
check 1 "missing.exr: no such file" --depth missing.exr
check 1 "directory" --depth dir.exr
check 1 "not an OpenEXR" --depth text.exr
check 1 "not an OpenEXR" --depth empty.exr
check 1 "corrupt header" --depth truncated.exr
check 1 "not a regular file" --depth fifo.exr
# A --set setting that the final settings make inert (gen::kInertRules), after the preset, every
# --set and --resolution-divisor; refused before anything is rendered.
check 2 "--set fade_start has no effect while fade_end = 0 (no distance fade" --scene crease --set fade_start=2
check 2 "also set fade_end > 0, or drop fade_start" --scene crease --set fade_end=4 --set fade_start=2 --set fade_end=0
check 2 "--set temporal_depth_tolerance has no effect while temporal = false" --scene crease --set temporal_depth_tolerance=0.1
check 2 "--set blur_stride has no effect while blur_radius = 0 (no bilateral blur" --scene crease --preset low --set blur_radius=0 --set blur_stride=2
# bent_normals: refused by the effect's rules (exit 2, before any work); on the direct path sao-render
# writes it (an rgba16f output: render_bent_normals.sh).
check 2 "setting 'bent_normals' = true is refused while estimator = 0 (the alchemy estimator (eq. 1) has no slices of unoccluded rays to average): also set estimator > 0, or drop bent_normals" --scene crease --set bent_normals=true
check 2 "also set blur_radius = 0, resolution_divisor = 1 and temporal = false, or drop bent_normals" --scene crease --set bent_normals=true --set estimator=1
check 2 "--set blur_edge_sharpness has no effect while blur_radius = 0" --scene crease --set blur_edge_sharpness=5 --set blur_radius=0
check 2 "--set mip_switch_log2 has no effect while use_z_hierarchy = false" --scene crease --set use_z_hierarchy=false --set mip_switch_log2=2
check 2 "--set half_intermediates has no effect while blur_radius = 0, resolution_divisor = 1 and temporal = false" --scene crease --set blur_radius=0 --set half_intermediates=false --resolution-divisor 1

# --help is no error: usage on stdout, exit 0, nothing on stderr.
"$render" --help >stdout.txt 2>stderr.txt
rc=$?
if [ "$rc" -ne 0 ] || [ -s stderr.txt ] || [ "$(head -n 1 stdout.txt)" != "usage: sao-render [options]" ] ||
   ! grep -qF -e "--backend NAME" stdout.txt; then
  echo "--help -> $rc: want exit 0, usage on stdout, empty stderr"; fail=1
fi
[ "$(cat theirs/notes.txt)" = mine ] && [ -d earlier/summary.txt ] || { echo "a refused run changed a folder"; fail=1; }
exit $fail
