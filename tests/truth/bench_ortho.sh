#!/bin/sh
# sao-bench --ortho (orthographic views of the scenes): a --quick presets run on the cpu backend
# writes one row per scene and preset with finite errors against references (a) and (c), and the
# report's depth note says the views are orthographic; --ortho with --tune is refused.
# usage: bench_ortho.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
die() { echo "bench ortho: $*" >&2; exit 1; }

"$bench" --quick --backends cpu --sections presets --ortho --out "$out/ortho" >/dev/null 2>"$out.stderr" ||
  die "sao-bench --quick --ortho failed: $(tail -2 "$out.stderr")"
python3 - "$out/ortho/results.csv" <<'PY' || die "results.csv: missing rows or non-finite errors"
import csv, math, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["section"] == "presets"]
scenes = {r["scene"] for r in rows}
assert scenes == {"crease", "sphere-plane"}, scenes
for r in rows:
    for c in ("ao_rmse_raw", "converged_rmse_raw"):
        v = float(r[c])
        assert math.isfinite(v) and 0 <= v < 0.2, (r["scene"], r["preset"], c, v)
    print(r["scene"], r["preset"], "ao_rmse_raw", r["ao_rmse_raw"], "converged_rmse_raw", r["converged_rmse_raw"])
PY
grep -q 'finite far: orthographic views (--ortho)' "$out/ortho/results.json" || die "results.json does not say the views are orthographic"
if "$bench" --tune --ortho --out "$out/tune" >/dev/null 2>"$out.stderr"; then die "--tune --ortho was accepted"; fi
echo "bench ortho: ok"
