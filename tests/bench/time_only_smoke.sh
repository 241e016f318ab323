#!/bin/sh
# sao-bench --time-only (what ci/gpu-bench.sh runs on a GPU machine), quick, CPU backend: the
# presets are timed on both scenes with every error column empty and no error maps (no reference
# was computed), and the options that only shape references, or the sections that measure error
# alone, are refused with a message naming them.
# usage: time_only_smoke.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
die() { echo "time-only smoke: $*" >&2; exit 1; }

"$bench" --quick --backends cpu --sections presets --time-only --out "$out" >"$out.stdout" 2>"$out.stderr" ||
  die "sao-bench --quick --time-only failed: $(tail -2 "$out.stderr")"
csv=$out/results.csv
test -s "$csv" || die "missing results.csv"
col() { head -1 "$csv" | tr ',' '\n' | grep -nx "$1" | cut -d: -f1; }
# 2 scenes x 5 presets, each timed, no error of any kind.
awk -F, -v t="$(col total_ms)" -v a="$(col ao_rmse_raw)" -v b="$(col obscurance_rmse_raw)" \
    -v c="$(col converged_rmse_raw)" -v m="$(col error_map)" '
  NR > 1 { n++; if ($1 != "presets" || !($t > 0) || $a != "" || $b != "" || $c != "" || $m != "") bad = 1 }
  END { exit bad || n != 10 }' "$csv" || die "expected 10 timed preset rows without errors: $(cat "$csv")"
test ! -e "$out/maps" || die "error maps were written without references"

expect_refusal() {
  msg=$1; shift
  if "$bench" "$@" >"$out.refused" 2>&1; then die "sao-bench $* was accepted"; fi
  grep -qF -e "$msg" "$out.refused" || die "sao-bench $*: expected '$msg', got: $(cat "$out.refused")"
}
expect_refusal "--time-only computes no references: --rays, --converged-taps, --converged-noise and --ao-noise do not apply" \
  --time-only --rays 16
expect_refusal "--time-only: the spiral section measures error only" --time-only --sections presets,spiral
echo "time-only smoke: ok"
