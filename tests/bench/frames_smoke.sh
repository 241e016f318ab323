#!/bin/sh
# sao-bench --sections frames, quick (medium preset, 4 frames, two scenes, CPU reference): frames.csv
# has its header and one row per scene, the errors are in (0, 1), the mean of the frames has a
# lower error than its first frame on every scene (the frame index reaches the shader and the
# frames' taps differ), so does the effect's own temporal accumulation (the history reaches the
# next frame), and the summary gives both verdict lines.
# usage: frames_smoke.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
die() { echo "frames smoke: $*" >&2; exit 1; }

"$bench" --quick --backends cpu --sections frames --out "$out" >"$out.stdout" 2>"$out.stderr" ||
  die "sao-bench --quick --sections frames failed: $(tail -2 "$out.stderr")"
csv=$out/frames.csv
test -s "$csv" || die "missing frames.csv"
[ "$(head -1 "$csv")" = "scene,preset,samples,frames,converged_rmse_one_frame,converged_rmse_mean_of_frames,samples_4x,converged_rmse_4x_taps,converged_rmse_temporal" ] ||
  die "unexpected header $(head -1 "$csv")"
[ "$(awk 'NR > 1' "$csv" | wc -l)" -eq 2 ] || die "expected 2 rows, got $(awk 'NR > 1' "$csv" | wc -l)"
awk -F, 'NR > 1 && !($2 == "medium" && $4 == 4 && $7 == (4 * $3 < 64 ? 4 * $3 : 64)) { bad = 1 } END { exit bad }' "$csv" ||
  die "a row is not medium, 4 frames, 4x the taps (at most 64)"
awk -F, 'NR > 1 && !($5 > 0 && $5 < 1 && $6 > 0 && $6 < 1 && $8 > 0 && $8 < 1 && $9 > 0 && $9 < 1) { bad = 1 } END { exit bad }' "$csv" ||
  die "an RMSE is not in (0, 1)"
awk -F, 'NR > 1 && !($6 < $5) { bad = 1 } END { exit bad }' "$csv" ||
  die "the mean of the frames is not below one frame's error: the frame index does not reach the shader"
awk -F, 'NR > 1 && !($9 < $5) { bad = 1 } END { exit bad }' "$csv" ||
  die "temporal accumulation is not below one frame's error: the history does not reach the next frame"
grep -q "temporal accumulation (4 frames) is at or below one frame with 4x the taps in [0-9]* of 2 cases" "$out.stdout" ||
  die "no temporal verdict line in the summary"
grep -q "the mean of 4 frames is at or below one frame with 4x the taps in [0-9]* of 2 (" "$out.stdout" ||
  die "no verdict line in the summary"
echo "frames smoke: ok"
