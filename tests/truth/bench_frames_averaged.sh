#!/bin/sh
# sao-bench --frames-averaged (presets section): each row's errors are those of the mean of N frames,
# the preset's own converged value. On crease (one of the quick scenes: half the time of both) with
# the CPU reference, one frame and the mean of 8: the rows say so in their variant column, keep their
# times, and the paper's estimator's presets (low, medium, high) come nearer reference (c), the
# converged estimator of the same settings (their frames' taps differ, eq. 6's frame spiral, and (c)
# is what the taps average to). The visibility presets' limit is their own, not (c) nor (d): printed, not
# asserted.
#   bench_frames_averaged.sh SAO_BENCH WORK_DIR
set -eu
bench=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
"$bench" --quick --scenes crease --sections presets --backends cpu --out "$work/one" >/dev/null 2>&1
"$bench" --quick --scenes crease --sections presets --backends cpu --frames-averaged 8 --out "$work/eight" >/dev/null 2>&1
/usr/bin/python3 - "$work/one/results.csv" "$work/eight/results.csv" <<'PY'
import csv, sys
one = {(r["scene"], r["preset"]): r for r in csv.DictReader(open(sys.argv[1]))}
eight = {(r["scene"], r["preset"]): r for r in csv.DictReader(open(sys.argv[2]))}
assert one.keys() == eight.keys() and len(one) >= 5, "the two runs' rows differ"
bad = []
for key, r in sorted(eight.items()):
    o = one[key]
    c1, c8 = float(o["converged_rmse_raw"]), float(r["converged_rmse_raw"])
    d1, d8 = float(o["screen_rmse_raw"]), float(r["screen_rmse_raw"])
    print(f"{key[0]:12} {key[1]:9} vs (c) {c1:.4f} -> {c8:.4f}   vs (d) {d1:.4f} -> {d8:.4f}   total {r['total_ms']} ms")
    if o["variant"] != "" or r["variant"] != "frames_averaged=8":
        bad.append(f"{key}: variant '{o['variant']}' / '{r['variant']}'")
    if not float(r["total_ms"]) > 0:
        bad.append(f"{key}: no time")
    if key[1] in ("low", "medium", "high") and not c8 < c1:
        bad.append(f"{key}: 8 frames no nearer (c): {c1} -> {c8}")
if bad:
    sys.exit("FAIL: " + "; ".join(bad))
print("the mean of 8 frames is nearer (c) on every paper's-estimator row")
PY
