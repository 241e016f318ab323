#!/bin/sh
# sao-bench --sections per_tap, quick (GL, 320x180, the main quick scene): per_tap.csv has its header
# (with each row's timing method, the same in every row)
# and one row per variant (the ladder (a)-(k) and ao_sample with normals read and rebuilt) and
# sample count (7, 16, 32, 48), every time > 0 with min <= median <= max, every mean A in (0, 1]
# (the section itself fails on a rung that writes NaN, all 0 or all 1); the summary gives the
# slopes, ao_sample's ratios and the mean A table; no other section ran; and the section is left
# out of the default run (--help's --sections text).
# usage: per_tap_smoke.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
die() { echo "per_tap smoke: $*" >&2; exit 1; }

"$bench" --quick --backends gl --sections per_tap --out "$out" >"$out.stdout" 2>"$out.stderr" ||
  die "sao-bench --quick --backends gl --sections per_tap failed: $(tail -2 "$out.stderr")"
grep -q "^per_tap: skipped" "$out.stdout" && die "the section skipped: $(grep '^per_tap: skipped' "$out.stdout")"
csv=$out/per_tap.csv
test -s "$csv" || die "missing per_tap.csv"
[ "$(head -1 "$csv")" = "variant,samples,width,height,runs,median_ms,min_ms,max_ms,mean_a,label,timing_method" ] ||
  die "unexpected header $(head -1 "$csv")"
# The ladder and ao_sample are timed alike (GL_TIME_ELAPSED where it sees the work, else glFinish and
# a clock, as on llvmpipe): one method in every row.
[ "$(awk -F, 'NR > 1 {print $NF}' "$csv" | sort -u | wc -l)" -eq 1 ] ||
  die "the rows were timed by different methods: $(awk -F, 'NR > 1 {print $1, $NF}' "$csv" | sort -u)"
awk -F, 'NR > 1 && $NF != "finish + steady clock" && $NF != "GPU timestamps" { bad = 1 } END { exit bad }' "$csv" ||
  die "a row's timing_method is not one of the two"
variants="a_fragment b_compute c_compute_2x2 d_compute_mip e_compute_rebuilt_n f_compute_imageload
  g_compute_uniform_taps h_compute_exact_spiral i_compute_uniform_spiral j_compute_all k_compute_turn_table
  ours_normals ours_rebuilt"
n=0
for v in $variants; do
  for s in 7 16 32 48; do
    [ "$(awk -F, -v v="$v" -v s="$s" '$1 == v && $2 == s' "$csv" | wc -l)" -eq 1 ] || die "expected one row $v at s=$s"
    n=$((n + 1))
  done
done
[ "$(awk 'NR > 1' "$csv" | wc -l)" -eq "$n" ] || die "expected $n rows, got $(awk 'NR > 1' "$csv" | wc -l)"
awk -F, 'NR > 1 && !($3 == 320 && $4 == 180 && $5 == 3) { bad = 1 } END { exit bad }' "$csv" ||
  die "a row is not 320x180 with 3 runs"
awk -F, 'NR > 1 && !($6 > 0 && $7 > 0 && $8 > 0 && $7 <= $6 && $6 <= $8) { bad = 1 } END { exit bad }' "$csv" ||
  die "a time is not > 0 or not min <= median <= max"
awk -F, 'NR > 1 && !($9 > 0 && $9 <= 1) { bad = 1 } END { exit bad }' "$csv" || die "a mean A is not in (0, 1]"
for line in "per_tap: time per tap of ao_sample and of minimal passes" "(a) fragment, texelFetch" \
            "ao_sample's time per tap: normals read" "ao_sample at s=7 over (a) at s=7" "mean A over the geometry"; do
  grep -qF "$line" "$out.stdout" || die "no '$line' in the summary"
done
[ "$(awk 'NR > 1' "$out/results.csv" | wc -l)" -eq 0 ] || die "--sections per_tap ran other sections"
"$bench" --help | tr '\n' ' ' | grep -q "default: all but [^:]*per_tap" ||
  die "--help does not leave per_tap out of the default run"
# The published tables (samples/bench/markdown_tables.py) read the file back: one row per variant.
tables=$(/usr/bin/python3 "$(dirname "$0")/../../samples/bench/markdown_tables.py" "$out") ||
  die "markdown_tables.py cannot read the run"
echo "$tables" | grep -q "^### Per-tap cost" || die "markdown_tables.py prints no per-tap table"
[ "$(echo "$tables" | grep -c '^| (')" -eq 11 ] || die "expected the 11 ladder rows (a)..(k) in the per-tap table"
echo "per_tap smoke: ok"
