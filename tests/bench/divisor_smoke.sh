#!/bin/sh
# sao-bench --sections divisor, quick (the high preset at resolution_divisor 1 and 2, two scenes,
# CPU reference): results.csv has one error row per scene and divisor (section "divisor", with
# its RMSE vs (c), silhouette error and error map) and one time row per divisor ("divisor_time");
# every row's resolution_divisor column is the divisor its variant names; every row ran the blur,
# the half-resolution rows the upsample and not the output pass, the full-resolution rows the
# opposite; the half-resolution plan holds fewer bytes; and the section is not part of the default run.
# usage: divisor_smoke.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
die() { echo "divisor smoke: $*" >&2; exit 1; }

"$bench" --quick --backends cpu --sections divisor --out "$out" >"$out.stdout" 2>"$out.stderr" ||
  die "sao-bench --quick --sections divisor failed: $(tail -2 "$out.stderr")"
csv=$out/results.csv
test -s "$csv" || die "missing results.csv"
col() { head -1 "$csv" | tr ',' '\n' | grep -nx "$1" | cut -d: -f1; }
for c in resolution_divisor blur_ms output_ms upsample_ms plan_bytes converged_rmse_raw converged_silhouette_rmse error_map; do
  test -n "$(col $c)" || die "results.csv has no column $c"
done
[ "$(awk -F, '$1 == "divisor"' "$csv" | wc -l)" -eq 4 ] || die "expected 4 divisor rows (2 scenes x 2 divisors)"
[ "$(awk -F, '$1 == "divisor_time"' "$csv" | wc -l)" -eq 2 ] || die "expected 2 divisor_time rows"
[ "$(awk -F, 'NR > 1 && !($1 ~ /^divisor/)' "$csv" | wc -l)" -eq 0 ] || die "--sections divisor ran other sections"
awk -F, -v v="$(col variant)" -v d="$(col resolution_divisor)" -v p="$(col preset)" \
    -v up="$(col upsample_ms)" -v blur="$(col blur_ms)" -v o="$(col output_ms)" '
  NR > 1 { n++
    if ($v != "divisor=" $d || $p != "high" || !($blur > 0)) bad = 1
    if ($d == 2 && !($up > 0 && $o == 0)) bad = 1
    if ($d == 1 && !($up == 0 && $o > 0)) bad = 1 }
  END { exit bad || n != 6 }' "$csv" || die "a row's divisor, preset or passes are not what its variant says: $(cat "$csv")"
# The error rows: RMSE vs (c) in (0, 0.2), a silhouette error (sphere-plane) or n/a (crease), a PNG map.
awk -F, -v r="$(col converged_rmse_raw)" -v s="$(col converged_silhouette_rmse)" '
  $1 == "divisor" { if (!($r > 0 && $r < 0.2)) bad = 1
    if ($2 == "sphere-plane" && !($s > 0 && $s < 0.3)) bad = 1
    if ($2 == "crease" && $s != "n/a") bad = 1 }
  END { exit bad }' "$csv" || die "an error row's RMSE vs (c) or silhouette error is out of range"
m=$(col error_map)
for f in $(awk -F, -v m="$m" '$1 == "divisor" {print $m}' "$csv"); do
  [ "$(head -c 4 "$out/$f" | tail -c 3)" = "PNG" ] || die "$f is missing or not a PNG"
done
# Half resolution plans its reduced images: fewer bytes than full resolution, on every scene.
awk -F, -v d="$(col resolution_divisor)" -v b="$(col plan_bytes)" '
  $1 == "divisor" { bytes[$2 "," $d] = $b }
  END { n = 0; for (k in bytes) if (k ~ /,1$/) { h = k; sub(/,1$/, ",2", h); if (!(bytes[h] < bytes[k])) exit 1; n++ }
        exit n != 2 }' "$csv" || die "the half-resolution plan is not smaller than the full-resolution one"
echo "divisor smoke: ok"
