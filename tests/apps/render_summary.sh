#!/bin/sh
# sao-render's summary (docs/ROBUSTNESS.md): summary.json is valid JSON whatever the paths hold
# (a TAB, quotes, a backslash, a newline), an undefined metric is "n/a" in summary.txt and null in
# summary.json (never "1.0000" or nan), and --runs N gives each pass's median and spread.
#
#   render_summary.sh SAO_RENDER WORK_DIR
set -u
render=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$2
python=/usr/bin/python3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail=0
problem() { echo "FAIL: $*"; fail=1; }

# A depth file whose name holds a TAB, a quote, a backslash and a newline.
name=$(printf 'd\tq"b\\s\nn.exr')
"$render" --backend cpu --size 64x36 --scene crease --save-depth "$name" --out setup >/dev/null || problem "setup failed"
"$render" --backend cpu --depth "$name" --json --out "$(printf 'out\tdir')" >/dev/null || problem "depth run failed"
json=$(printf 'out\tdir')/summary.json
$python -m json.tool "$json" >/dev/null || problem "summary.json with a TAB in a path is not valid JSON"
$python - "$json" "$name" <<'PY' || problem "summary.json does not carry the path"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["input"] == "depth file " + sys.argv[2] + " (D32F)", s["input"]
PY

# A flat plane: nothing is occluded, so the AO and the reference are both constant: SSIM and the
# best-fit scale are undefined.
printf 'v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 2 3\nf 1 3 4\n' > plane.obj
"$render" --backend cpu --size 64x36 --scene plane.obj --reference --reference-rays 8 --json --out plane >stdout.txt 2>/dev/null ||
  problem "plane run failed"
grep -q '^  raw: RMSE 0.0000, mean bias 0.0000, SSIM n/a,' plane/summary.txt || problem "summary.txt: raw SSIM is not n/a"
grep -q '^  best-fit occlusion scale n/a' plane/summary.txt || problem "summary.txt: the best-fit scale is not n/a"
grep -q 'SSIM n/a' stdout.txt || problem "stdout: SSIM is not n/a"
grep -qi 'nan' plane/summary.json && problem "summary.json holds nan"
$python - plane/summary.json <<'PY' || problem "summary.json: undefined metrics are not null"
import json, sys
r = json.load(open(sys.argv[1]))["reference"]
assert r["raw"]["ssim"] is None and r["fitted"]["ssim"] is None and r["fitted_intensity"] is None, r
assert r["raw"]["rmse"] == 0.0 and r["pixels"] > 0, r
PY
# The crease: occlusion everywhere near the corner, so every metric is defined.
"$render" --backend cpu --size 64x36 --scene crease --reference --reference-rays 8 --json --out crease >/dev/null ||
  problem "crease run failed"
grep -q 'n/a' crease/summary.txt && problem "crease: a metric is n/a"
$python - crease/summary.json <<'PY' || problem "crease: a metric is null"
import json, sys
r = json.load(open(sys.argv[1]))["reference"]
assert None not in (r["raw"]["ssim"], r["fitted"]["ssim"], r["fitted_intensity"]), r
PY

# --runs 5: the median of 5 runs after a warm-up, and min <= median <= max for every pass.
"$render" --backend cpu --size 64x36 --scene crease --runs 5 --json --out runs >stdout.txt || problem "--runs run failed"
grep -q '^timing (CPU steady clock, median of 5 runs after 1 warm-up run): ' stdout.txt || problem "stdout: no median of 5 runs"
grep -q '^timing spread (fastest..slowest of 5): ' runs/summary.txt || problem "summary.txt: no spread line"
$python - runs/summary.json runs/summary.txt <<'PY' || problem "--runs: the JSON and text do not agree"
import json, re, sys
s = json.load(open(sys.argv[1]))
text = open(sys.argv[2]).read()
assert s["runs"] == 5, s["runs"]
passes = s["pass_ms"]
assert len(passes) >= 3 and "ao_sample" in passes, passes
for p, median in passes.items():
    lo, hi = s["pass_ms_min"][p], s["pass_ms_max"][p]
    assert 0 < lo <= median <= hi, (p, lo, median, hi)
    m = re.search(r" %s ([0-9.]+)\.\.([0-9.]+) ms;" % p, text)
    assert m and abs(float(m.group(1)) - lo) < 1e-3 and abs(float(m.group(2)) - hi) < 1e-3, (p, m)
assert s["total_ms_min"] <= s["total_ms"] <= s["total_ms_max"]
PY
# A mesh with some degenerate triangles: they are left out with a warning on stderr, in
# summary.txt and in summary.json (a plane of two triangles, and one triangle on a line).
printf 'v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nv 0 0 0\nf 1 2 3\nf 1 3 4\nf 1 5 3\n' > degenerate.obj
"$render" --backend cpu --size 64x36 --scene degenerate.obj --json --out degenerate >/dev/null 2>stderr.txt ||
  problem "degenerate.obj run failed"
grep -q '^sao-render: warning: .*degenerate.obj: 1 of 3 triangles are degenerate' stderr.txt ||
  problem "no degenerate-triangle warning on stderr: $(cat stderr.txt)"
grep -q '^warning: .*1 of 3 triangles are degenerate' degenerate/summary.txt || problem "summary.txt: no degenerate-triangle warning"
$python - degenerate/summary.json <<'PY' || problem "summary.json: no degenerate-triangle warning"
import json, sys
w = json.load(open(sys.argv[1]))["warnings"]
assert any("1 of 3 triangles are degenerate" in x for x in w), w
PY
exit $fail
