#!/bin/sh
# sao-bench --sections spiral, quick (s = 16 on two scenes, CPU reference): spiral.csv has its
# header and four rows per scene (blur 0 and the medium blur, each with the lattice criterion's tau 3 and G3D's 7),
# the taus are those, the RMSE are finite, and the two taus give different errors somewhere (the
# spiral_turns setting reaches the shader), and the summary gives the verdict line.
# usage: spiral_smoke.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
die() { echo "spiral smoke: $*" >&2; exit 1; }

"$bench" --quick --backends cpu --sections spiral --out "$out" >"$out.stdout" 2>"$out.stderr" ||
  die "sao-bench --quick --sections spiral failed: $(tail -2 "$out.stderr")"
csv=$out/spiral.csv
test -s "$csv" || die "missing spiral.csv"
[ "$(head -1 "$csv")" = "scene,samples,blur_radius,spiral_turns,source,converged_rmse_raw" ] ||
  die "unexpected header $(head -1 "$csv")"
[ "$(awk 'NR > 1' "$csv" | wc -l)" -eq 8 ] || die "expected 8 rows, got $(awk 'NR > 1' "$csv" | wc -l)"
awk -F, 'NR > 1 && !(($5 == "lattice" && $4 == 3) || ($5 == "g3d" && $4 == 7)) { bad = 1 } END { exit bad }' "$csv" ||
  die "a row's spiral_turns is not the lattice's (3) or G3D's (7) for s = 16"
awk -F, 'NR > 1 && !($6 > 0 && $6 < 1) { bad = 1 } END { exit bad }' "$csv" || die "an RMSE is not in (0, 1)"
awk -F, 'NR > 1 && $5 == "lattice" { e[$1 "," $3] = $6 } NR > 1 && $5 == "g3d" && e[$1 "," $3] != $6 { d = 1 } END { exit !d }' "$csv" ||
  die "every row has the same error with tau 3 and tau 7: spiral_turns does not reach the shader"
grep -q "lower RMSE: lattice in [0-9]*, G3D's in [0-9]* of 4 (" "$out.stdout" || die "no verdict line in the summary"
echo "spiral smoke: ok"
