#!/bin/sh
# sao-render --frames N --path P: N per-frame AO images, frames.csv with a row per frame (flicker
# from frame 1 on), the summary's frames line and the last frame as the usual outputs; the path
# options refused where they cannot apply (exit 2, one line).
set -e
render="$1"
out="$2"
rm -rf "$out"
mkdir -p "$out"
fail() { echo "render_frames: $*"; exit 1; }

"$render" --backend cpu --scene crease --size 64x36 --frames 4 --path strafe --out "$out/strafe" > "$out/stdout.txt"
for f in 0000 0001 0002 0003; do
  [ -s "$out/strafe/frames/ao_$f.png" ] || fail "frames/ao_$f.png missing"
done
[ ! -e "$out/strafe/frames/ao_0004.png" ] || fail "a fifth frame was written"
cmp -s "$out/strafe/ao.png" "$out/strafe/frames/ao_0003.png" || fail "ao.png is not the last frame's AO"
[ "$(wc -l < "$out/strafe/frames.csv")" -eq 5 ] || fail "frames.csv has not 1 + 4 lines"
head -1 "$out/strafe/frames.csv" | grep -q '^frame,eye_x' || fail "frames.csv header"
# Frame 0 has no flicker, frames 1..3 one in [0, 1] with compared pixels.
awk -F, 'NR == 2 && $9 != "" { exit 1 } NR > 2 && ($9 < 0 || $9 > 1 || $10 <= 0) { exit 1 }' "$out/strafe/frames.csv" ||
  fail "frames.csv flicker columns: $(cat "$out/strafe/frames.csv")"
grep -q '^frames: 4 along the strafe path; flicker' "$out/strafe/summary.txt" || fail "summary frames line"
grep -q 'frames/ao_0003.png' "$out/strafe/sao-render-outputs.txt" || fail "the manifest lists the frames"

# The orbit (default path) on another scene, with JSON.
"$render" --backend cpu --scene sphere-plane --size 48x27 --frames 2 --json --out "$out/orbit" > /dev/null
grep -q '"path": "orbit"' "$out/orbit/summary.json" || fail "summary.json frames.path"

# Refusals: one line on stderr, exit 2, no output folder.
for args in "--path dolly" "--frames 1" "--frames 2.5" "--frames 10001" "--frames 3 --path zigzag"; do
  set +e
  msg=$("$render" --backend cpu --scene crease --size 32x18 $args --out "$out/refused" 2>&1 >/dev/null)
  rc=$?
  set -e
  [ $rc -eq 2 ] || fail "'$args' exited $rc, not 2: $msg"
  [ "$(printf '%s\n' "$msg" | wc -l)" -eq 1 ] || fail "'$args' printed more than one line: $msg"
  [ ! -e "$out/refused" ] || fail "'$args' left an output folder"
done
# A depth file has one view: --frames is refused with it.
"$render" --backend cpu --scene crease --size 32x18 --save-depth "$out/depth.exr" --out "$out/depth_run" > /dev/null
set +e
msg=$("$render" --backend cpu --depth "$out/depth.exr" --frames 3 --out "$out/refused" 2>&1 >/dev/null)
rc=$?
set -e
[ $rc -eq 2 ] || fail "--frames with --depth exited $rc, not 2: $msg"
echo "$msg" | grep -q -- "--frames needs a scene" || fail "--frames with --depth: $msg"
[ ! -e "$out/refused" ] || fail "--frames with --depth left an output folder"
echo "render_frames: ok"
