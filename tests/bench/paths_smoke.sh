#!/bin/sh
# sao-bench --sections paths, quick (4 frames at 96x54, two scenes, CPU reference): paths.csv has
# its header and one row per scene x path x temporal off/on (12), flicker in [0, 1), a compared
# share in (0, 1] equal with and without accumulation (the same views), times > 0, temporal
# accumulation lowers the flicker on every strafe (the history reaches the next frame), and the
# summary gives the verdict line. Not a test of the target: 4 frames are too few.
# usage: paths_smoke.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
die() { echo "paths smoke: $*" >&2; exit 1; }

"$bench" --quick --backends cpu --sections paths --out "$out" >"$out.stdout" 2>"$out.stderr" ||
  die "sao-bench --quick --sections paths failed: $(tail -2 "$out.stderr")"
csv=$out/paths.csv
test -s "$csv" || die "missing paths.csv"
[ "$(head -1 "$csv")" = "scene,path,temporal,frames,flicker,compared_fraction,median_effect_ms" ] ||
  die "unexpected header $(head -1 "$csv")"
[ "$(awk 'NR > 1' "$csv" | wc -l)" -eq 12 ] || die "expected 12 rows, got $(awk 'NR > 1' "$csv" | wc -l)"
awk -F, 'NR > 1 && !($4 == 4 && $5 >= 0 && $5 < 1 && $6 > 0 && $6 <= 1 && $7 > 0) { bad = 1 } END { exit bad }' "$csv" ||
  die "a row has frames, flicker, compared share or time out of range"
awk -F, 'NR > 1 { key = $1 "," $2; if (key in share && share[key] != $6) bad = 1; share[key] = $6 } END { exit bad }' "$csv" ||
  die "the compared share differs with and without accumulation: the views differ"
awk -F, 'NR > 1 && $2 == "strafe" { f[$1 "," $3] = $5 } END { for (k in f) { split(k, a, ","); if (a[2] == 1 && !(f[k] < f[a[1] ",0"])) bad = 1 } exit bad }' "$csv" ||
  die "temporal accumulation does not lower the flicker on a strafe: the history does not reach the next frame"
grep -q "temporal accumulation at most halves the flicker in [0-9]* of 6 (scene, path) cases" "$out.stdout" ||
  die "no verdict line in the summary"
echo "paths smoke: ok"
