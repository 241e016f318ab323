#!/bin/sh
# sao-bench --set (presets section only): a setting applied on top of every preset, checked as
# sao-render checks it; the rows name it and run the variant it selects.
# usage: set_option.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
mkdir -p "$out"
die() { echo "set option: $*" >&2; exit 1; }
expect_refusal() {  # MESSAGE ARGS...: exit 2 with MESSAGE on stderr, nothing written
  msg=$1
  shift
  set +e
  "$bench" "$@" --out "$out/refused" >/dev/null 2>"$out/refused.err"
  rc=$?
  set -e
  [ $rc -eq 2 ] || die "sao-bench $*: exit $rc, expected 2"
  grep -qF -e "$msg" "$out/refused.err" || die "sao-bench $*: expected '$msg', got: $(cat "$out/refused.err")"
  [ ! -e "$out/refused" ] || die "sao-bench $*: wrote $out/refused"
}
expect_refusal "--set applies to the presets section only: add --sections presets (and no --tune)" --set estimator=1
expect_refusal "--set applies to the presets section only" --sections presets,samples --set estimator=1
expect_refusal "--set: setting 'estimator' = 3 is not one of its allowed values {0, 1}" --sections presets --set estimator=3
expect_refusal "--set thickness has no effect while estimator = 0" --sections presets --set thickness=0.2
"$bench" --quick --scenes sphere-plane --sections presets --backends cpu --set estimator=1 --set thickness=0.2 --out "$out/ok" >/dev/null 2>"$out/ok.err" ||
  die "--set estimator=1 --set thickness=0.2 failed: $(tail -3 "$out/ok.err")"
rows=$(awk -F, 'NR > 1 && $1 == "presets"' "$out/ok/results.csv" | wc -l)
[ "$rows" -eq 5 ] || die "expected 5 preset rows (1 scene x 5 presets), got $rows"
bad=$(awk -F, 'NR > 1 && $1 == "presets" && ($5 != "estimator=1 thickness=0.2" || $7 !~ /ESTIMATOR=1/)' "$out/ok/results.csv" | wc -l)
[ "$bad" -eq 0 ] || die "rows without the --set variant or ESTIMATOR=1: $(awk -F, 'NR > 1 { print $5 \" | \" $7 }' "$out/ok/results.csv" | head -3)"
# --screen-thickness: reference (d)'s thickness model (presets section only); width changes (d).
expect_refusal "--screen-thickness expects constant or width, got 'thick'" --sections presets --screen-thickness thick
expect_refusal "--screen-thickness sets reference (d) of the presets section" --screen-thickness width
"$bench" --quick --scenes sphere-plane --sections presets --backends cpu --set estimator=1 --set thickness=0.2 --screen-thickness width \
  --out "$out/width" >"$out/width.out" 2>"$out/width.err" ||
  die "--screen-thickness width failed: $(tail -3 "$out/width.err")"
grep -q "thickness from width" "$out/width.out" "$out/width.err" || die "--screen-thickness width: the report does not name it"
col=$(head -1 "$out/ok/results.csv" | tr ',' '\n' | grep -nx screen_rmse_raw | cut -d: -f1)
[ -n "$col" ] || die "no screen_rmse_raw column"
a=$(awk -F, -v c="$col" 'NR > 1 && $1 == "presets" { print $c }' "$out/ok/results.csv" | sort -u | tr '\n' ' ')
b=$(awk -F, -v c="$col" 'NR > 1 && $1 == "presets" { print $c }' "$out/width/results.csv" | sort -u | tr '\n' ' ')
[ -n "$b" ] && [ "$a" != "$b" ] || die "--screen-thickness width: reference (d)'s error columns unchanged ($a)"
# --maps-against: each row's error map against (a) or (d) instead of (c); d adds (d) - (a) once.
expect_refusal "--maps-against expects c, a or d, got 'b'" --sections presets --maps-against b
expect_refusal "--maps-against chooses the reference of the sections' error maps" --tune --maps-against d
"$bench" --quick --scenes sphere-plane --sections presets --backends cpu --set estimator=1 --set thickness=0.2 --maps-against d \
  --out "$out/maps_d" >/dev/null 2>"$out/maps_d.err" || die "--maps-against d failed: $(tail -3 "$out/maps_d.err")"
# Two references (d): low to high take thickness 0.2 m for every slab, ultra and reference from width.
for model in constant width; do
  n=$(ls "$out/maps_d/maps" | grep -c "_screen_sphere-plane_depth_$model\.png\$" || true)
  [ "$n" -eq 1 ] || die "--maps-against d: expected one (d) - (a) map with $model thickness, got $n: $(ls "$out/maps_d/maps")"
done
for m in $(ls "$out/ok/maps" | grep _presets_); do
  [ -f "$out/maps_d/maps/$m" ] || die "--maps-against d: no $m"
  ! cmp -s "$out/ok/maps/$m" "$out/maps_d/maps/$m" || die "--maps-against d: $m is the map against (c)"
done
echo "set option: ok"
