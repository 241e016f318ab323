#!/bin/sh
# Depth files as other tools write them, through sao-render (issue 39): a scene's depth is saved
# with its camera, rewritten by make_foreign_depth as another tool would write it, and run again:
# the same AO where the file says the same thing, otherwise a warning or a refusal naming the real
# cause. Each row prints what it ran and what it got.
#
#   depth_foreign_files.sh SAO_RENDER MAKE_FOREIGN_DEPTH AO_EXR_COMPARE WORK_DIR
set -u
abs() { echo "$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"; }  # the rows run in WORK_DIR
render=$(abs "$1") make=$(abs "$2") compare=$(abs "$3") work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail=0
bad() { echo "  FAIL: $*"; fail=1; }

# The original: a sphere on a plane, with sky, from a camera the options can state again.
camera="--fovy 60 --near 0.1"
"$render" --backend cpu --size 96x54 --scene sphere-plane --eye 0,3,6 --target 0,0,0 $camera \
  --save-depth depth.exr --out scene >/dev/null || exit 1
for mode in dwaa dwab parts blender m44f noversion crop distances linear-z standard-half standard-float \
            reversed-half reversed-b44; do
  "$make" "$mode" depth.exr "$mode.exr" || exit 1
done

# run NAME RC [ARGS...]: sao-render on NAME.exr into out_NAME; checks the exit status, leaves
# stderr in err_NAME.txt.
run() {
  name=$1 want_rc=$2
  shift 2
  rm -rf "out_$name"
  "$render" --backend cpu --depth "$name.exr" --out "out_$name" "$@" >/dev/null 2>"err_$name.txt"
  rc=$?
  echo "$name $* -> $rc: $(cat "err_$name.txt")"
  [ "$rc" -eq "$want_rc" ] || bad "exit status $rc, want $want_rc"
}
says() {  # NAME TEXT: stderr of NAME holds TEXT
  grep -qF -e "$2" "err_$1.txt" || bad "stderr lacks '$2'"
}
quiet() {  # NAME: nothing on stderr
  [ -s "err_$1.txt" ] && bad "stderr not empty"
  return 0
}

# 1, 2. DWA, the depth in the second part, Blender's layer names: the same file, the same AO.
for name in dwaa dwab parts blender; do
  run "$name" 0
  quiet "$name"
  cmp -s scene/ao.png "out_$name/ao.png" || bad "ao.png differs from the original's"
done
# 4. sao.projection as m44f: the matrix rounded to float, the AO within a binary16 step.
run m44f 0
quiet m44f
"$compare" scene/ao.exr out_m44f/ao.exr 1 || bad "AO of the m44f file differs"
# 3. The middle of the view as a crop in the whole display window: the view's size, a warning,
# the sky around it; the AO may differ outside the crop and within the radius of its edge (the
# sky there hides what occluded it), 96*54 - (48-16)*(27-16) = 4832 pixels, but not in its middle.
run crop 0
says crop "cropped inside the display window"
"$compare" scene/ao.exr out_crop/ao.exr 1 4832 || bad "the crop's AO is not the original's in its middle"
# 5. A distance pass without a camera (sky 1e10), with --depth-distances and the camera as options.
run distances 0 --depth-distances $camera --far 1e9
quiet distances
"$compare" scene/ao.exr out_distances/ao.exr 1 || bad "AO of the distance pass differs"
run distances 2 --depth-distances $camera --reversed-z
says distances "--reversed-z has no effect with --depth-distances"
run depth 2 --depth-distances
says depth "--depth-distances has no effect: 'depth.exr' carries its own camera"
run linear-z 1 --depth-distances $camera
says linear-z "texels are negative"
rm -rf out_none
"$render" --backend cpu --scene crease --depth-distances --out out_none >/dev/null 2>err_none.txt
[ $? -eq 2 ] || bad "--depth-distances without --depth: not exit 2"
says none "--depth-distances describes a --depth file: it has no effect without --depth"
# 6. Standard depth as HALF: warned with the step against the radius; not as FLOAT, not reversed-Z.
run standard-half 0 $camera --far 100
says standard-half "stores its depth as HALF (binary16), which cannot hold standard (not reversed-Z) depth"
says standard-half "% of the radius 1 m"
grep -qF "stores its depth as HALF" out_standard-half/summary.txt || bad "summary.txt lacks the HALF warning"
run standard-float 0 $camera --far 100
quiet standard-float
run reversed-half 0 $camera --reversed-z
quiet reversed-half
# 7. B44 noise on the sky: read as sky, said so; all 11 camera attributes but sao.version; UTF-16 OBJ.
run reversed-b44 0 $camera --reversed-z
says reversed-b44 "noise of its lossy B44 compression"
run noversion 2
says noversion "has sao.* attributes (sao.clipDepth, sao.depthFormat"
says noversion "but no sao.version, so they are not read as its camera: add the int attribute sao.version = 1"
run noversion 0 $camera --reversed-z
says noversion "has sao.* attributes but no sao.version: they are ignored"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > mesh.obj
{ printf '\377\376'; iconv -f UTF-8 -t UTF-16LE mesh.obj; } > utf16.obj  # iconv: libc-bin
iconv -f UTF-8 -t UTF-16LE mesh.obj > utf16-no-bom.obj
iconv -f UTF-8 -t UTF-32BE mesh.obj > utf32-no-bom.obj
obj() {  # NAME TEXT
  rm -rf out_obj
  "$render" --backend cpu --size 32x18 --scene "$1.obj" --out out_obj >/dev/null 2>err_obj.txt
  rc=$?
  echo "$1.obj -> $rc: $(cat err_obj.txt)"
  [ "$rc" -eq 1 ] || bad "exit status $rc, want 1"
  says obj "$2: save it as UTF-8 or ASCII text"
}
obj utf16 "is UTF-16 text (it starts with a UTF-16 byte-order mark)"
obj utf16-no-bom "is UTF-16 text (its first character is two bytes, one NUL)"
obj utf32-no-bom "is UTF-32 text (its first character is four bytes, three of them NUL)"
# --help names what cannot be detected.
"$render" --help > help.txt
for text in "--depth-distances" "NDC z (GL's [-1, 1]) stored instead of window" "a guard band the file was rendered"; do
  grep -qF -e "$text" help.txt || bad "--help lacks '$text'"
done
[ $fail -eq 0 ] && echo "all rows passed"
exit $fail
