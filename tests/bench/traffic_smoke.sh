#!/bin/sh
# sao-bench --sections traffic, quick: traffic.csv has its header and one row per machine x
# point x curve (3 machines, 2 radii + 2 sizes, 5 curves) and per machine x preset (5), every SAO
# (z hierarchy) row and the default preset's (high) are their own ratio 1, on the paper-like GPU
# every full-resolution curve reads at least SAO's bytes per pixel from L2 at r = 1.5 m (this CPU's
# L1 holds the quick images whole, so not there), only the rows with thickness from width (the ultra
# curve, the ultra and reference presets) have width-pass bytes, each row its AO pixel count, and the
# summary names both paper-like machines and this CPU.
# usage: traffic_smoke.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
die() { echo "traffic smoke: $*" >&2; exit 1; }

"$bench" --quick --backends cpu --sections traffic --out "$out" >"$out.stdout" 2>"$out.stderr" ||
  die "sao-bench --quick --sections traffic failed: $(tail -2 "$out.stderr")"
csv=$out/traffic.csv
test -s "$csv" || die "missing traffic.csv"
[ "$(head -1 "$csv")" = "section,scene,machine,variant,width,height,radius_m,max_mip,reads_per_pixel,l1_hit_rate,l2_hit_rate,l2_bytes_per_pixel,memory_bytes_per_pixel,l2_bytes_vs_sao,memory_bytes_vs_sao,width_l2_bytes_per_pixel,width_memory_bytes_per_pixel,ao_pixels" ] ||
  die "unexpected header $(head -1 "$csv")"
[ "$(awk 'NR > 1' "$csv" | wc -l)" -eq 75 ] || die "expected 75 rows, got $(awk 'NR > 1' "$csv" | wc -l)"
awk -F, '($4 == "SAO (z hierarchy)" || $4 == "preset high") && ($14 != 1 || $15 != 1) { bad = 1 } END { exit bad }' "$csv" ||
  die "an SAO (z hierarchy) or default-preset row is not its own ratio 1"
awk -F, '$3 == "paper-like GTX 680" && $1 == "radius" && $7 == 1.5 && $4 != "SAO (z hierarchy)" && !($14 >= 1) { bad = 1 } END { exit bad }' "$csv" ||
  die "paper-like: a full-resolution curve reads fewer bytes from L2 than SAO at r = 1.5 m"
[ "$(awk -F, '$4 == "SAO (no hierarchy)" && $8 != 0' "$csv" | wc -l)" -eq 0 ] || die "a no-hierarchy row has max_mip > 0"
awk -F, 'NR > 1 && (($4 ~ /^ultra/ || $4 == "preset ultra" || $4 == "preset reference") != ($16 > 0)) { bad = 1 } END { exit bad }' "$csv" ||
  die "width-pass bytes on a row without thickness from width, or none on one with it"
awk -F, 'NR > 1 && !($18 > 0) { bad = 1 } END { exit bad }' "$csv" || die "a row without its AO pixel count"
[ "$(awk -F, '$1 == "presets"' "$csv" | wc -l)" -eq 15 ] || die "expected 15 presets rows"
for m in "paper-like GTX 680:" "paper-like GTX 680 with 48 KB L1:" "this CPU (llvmpipe-like):"; do
  grep -qF "traffic, $m" "$out.stdout" || die "the summary has no machine '$m'"
done
echo "traffic smoke: ok"
