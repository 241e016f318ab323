#!/bin/sh
# Scene units through sao-render (docs/scene-format.md "Units"): the same scene at scales 1e-3, 1
# and 1e3 with matching units gives the same AO within one binary16 step (ao.exr), at full
# resolution and at the defaults' half resolution. Half resolution used to differ on up to 14 of
# the 14400 pixels (by up to 74 steps): the upsample's fallback took the single texel nearest in z,
# and a receding floor's row of texels has one z, so the last bit of z picked the texel; the
# fallback now shares the pixel among the texels near the nearest z (docs/effect-math.md 6.4).
# The runs use rg32f intermediates (half_intermediates=false): the arithmetic is unit-invariant to a
# binary16 step. The default rg16f keys (z in metres, binary16) can round a key of one unit system
# to the next binary16 value where the other does not (the float z of the two differ in the last
# bits), which moves A by more than a step on a few pixels; that path's bound across units, 1/255,
# is stability.WorldScale.HalfIntermediatesKeepTheirKeysInAnyUnit's (docs/effect-math.md 6.5).
# Usage: render_units.sh SAO_RENDER AO_EXR_COMPARE BOX_OBJ WORK_DIR
set -u
render=$1 compare=$2 box=$3 work=$4
rm -rf "$work" && mkdir -p "$work" || exit 1
fail=0

# scene FILE SCALE UNITS: the boxes scene, every length times SCALE.
scene() {
  awk -v s="$2" -v u="$3" -v box="$box" 'BEGIN {
    printf "mesh \"%s\"\ntransform scale 10 0.1 10 translate -5 -0.1 -5 scale %s\n", box, s
    printf "mesh \"%s\"\ntransform translate -0.5 0 -0.5 rotate-y 30 scale %s\n", box, s
    printf "units %s\n", u
    printf "view front eye 0 %.17g %.17g target 0 %.17g 0 fovy 50 near %.17g\n", 1.5 * s, 4 * s, 0.4 * s, 0.05 * s
  }' > "$1"
}

# run NAME SCENE: renders into $work/NAME at full resolution and $work/NAME-half at the defaults'
# half resolution (stderr in $work/NAME.err).
run() {
  if ! "$render" --backend cpu --size 160x90 --scene "$2" --set resolution_divisor=1 --set half_intermediates=false \
         --out "$work/$1" > /dev/null 2> "$work/$1.err" ||
     ! "$render" --backend cpu --size 160x90 --scene "$2" --set half_intermediates=false --out "$work/$1-half" > /dev/null \
         2>> "$work/$1.err"; then
    echo "FAIL: $1: sao-render failed:"; cat "$work/$1.err"; fail=1
  fi
}

same() {
  if ! "$compare" "$work/$1/ao.exr" "$work/$2/ao.exr" 1; then echo "FAIL: $1 vs $2"; fail=1; else echo "ok: $1 vs $2"; fi
  if ! "$compare" "$work/$1-half/ao.exr" "$work/$2-half/ao.exr" 1; then echo "FAIL: $1 vs $2 (half resolution)"; fail=1
  else echo "ok: $1 vs $2 (half resolution)"; fi
}

scene "$work/m.scene" 1 m
scene "$work/mm.scene" 1000 mm
run m "$work/m.scene"
run mm "$work/mm.scene"
same m mm
for s in 0.001 1 1000; do
  scene "$work/auto-$s.scene" "$s" auto
  run "auto-$s" "$work/auto-$s.scene"
done
same auto-1 auto-0.001
same auto-1 auto-1000
# The scale auto chose, on stderr and in the summary (the bounding-box diagonal of the scene at
# scale 1 is 14.18 units: 1 m = 2.84 units there).
for s in 0.001 1 1000; do
  grep -q "^sao-render: units auto (.*): bounding-box diagonal .* units taken as .* m, 1 m = .* units" "$work/auto-$s.err" ||
    { echo "FAIL: auto-$s: no auto scale on stderr:"; cat "$work/auto-$s.err"; fail=1; }
  grep -q "^units: auto (" "$work/auto-$s/summary.txt" || { echo "FAIL: auto-$s: no auto scale in summary.txt"; fail=1; }
done
grep -q "1 m = 1000 units" "$work/mm/summary.txt" || { echo "FAIL: mm: summary.txt does not give the factor"; fail=1; }
# A unit that changes nothing at scale 1 must change the AO: the test can tell units apart.
"$render" --backend cpu --size 160x90 --scene "$work/m.scene" --set resolution_divisor=1 --set half_intermediates=false --units mm \
  --out "$work/mm-at-1" > /dev/null 2>&1
if "$compare" "$work/m/ao.exr" "$work/mm-at-1/ao.exr" 1 > /dev/null; then
  echo "FAIL: --units mm on the scene at scale 1 gives the AO of metres"; fail=1
fi

# Bad --units: exit 2 and one line naming the problem.
check() {
  expect=$1; shift
  out=$("$render" --backend cpu --out "$work/bad" "$@" 2>&1); rc=$?
  lines=$(printf '%s\n' "$out" | wc -l)
  if [ $rc -ne 2 ] || [ "$lines" -ne 1 ] || ! printf '%s' "$out" | grep -qF -e "$expect"; then
    echo "FAIL: $* -> $rc: $out"; fail=1
  fi
  [ ! -e "$work/bad" ] || { echo "FAIL: $* left an output folder"; fail=1; }
}
check "--units expects m, cm, mm, in, ft or auto, got 'km'" --units km
check "--units expects m, cm, mm, in, ft or auto, got 'MM'" --scene crease --units MM
"$render" --backend cpu --size 32x18 --scene crease --save-depth "$work/d.exr" --out "$work/d" > /dev/null 2>&1
check "--units auto needs a scene's bounding box" --depth "$work/d.exr" --units auto
check "--units has no effect" --depth "$work/d.exr" --units mm
exit $fail
