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
"$bench" --quick --sections presets --backends cpu --set estimator=1 --set thickness=0.2 --out "$out/ok" >/dev/null 2>"$out/ok.err" ||
  die "--set estimator=1 --set thickness=0.2 failed: $(tail -3 "$out/ok.err")"
rows=$(awk -F, 'NR > 1 && $1 == "presets"' "$out/ok/results.csv" | wc -l)
[ "$rows" -eq 10 ] || die "expected 10 preset rows (2 scenes x 5 presets), got $rows"
bad=$(awk -F, 'NR > 1 && $1 == "presets" && ($5 != "estimator=1 thickness=0.2" || $7 !~ /ESTIMATOR=1/)' "$out/ok/results.csv" | wc -l)
[ "$bad" -eq 0 ] || die "rows without the --set variant or ESTIMATOR=1: $(awk -F, 'NR > 1 { print $5 \" | \" $7 }' "$out/ok/results.csv" | head -3)"
echo "set option: ok"
