#!/bin/sh
# sao-render's progress on stderr (docs/ROBUSTNESS.md): with --progress 0 a line when each step
# begins and ends, with the time since the start; a step longer than the threshold gets a line
# every threshold seconds, the reference trace with its share done; a fast run under the default
# threshold prints nothing.
#
#   render_progress.sh SAO_RENDER WORK_DIR
set -u
render=$1
work=$2
rm -rf "$work" && mkdir -p "$work" || exit 1
fail=0
problem() { echo "FAIL: $*"; fail=1; }

"$render" --backend cpu --size 64x36 --scene crease --reference --reference-rays 4 --progress 0 --out "$work/every" \
  >/dev/null 2>"$work/every.txt" || problem "--progress 0 run failed"
cat "$work/every.txt"
for step in "loading the scene" "building the ray-tracing structure" "rendering the depth" \
            "running the effect on cpu (1 warm-up + 1 measured run)" "writing the outputs" \
            "tracing the reference (4 rays/pixel)"; do
  grep -qE "^sao-render: \[[0-9]+\.[0-9] s\] $(printf '%s' "$step" | sed 's/[()+]/\\&/g') \.\.\.$" "$work/every.txt" ||
    problem "no line announcing '$step'"
  grep -qE "^sao-render: \[[0-9]+\.[0-9] s\] $(printf '%s' "$step" | sed 's/[()+]/\\&/g'): done in [0-9]+\.[0-9] s$" "$work/every.txt" ||
    problem "no line ending '$step'"
done

# The share done: with --progress 0 each tenth passed is reported, however fast the machine is
# (no timing in this test: the verdict must not depend on the machine's speed or load).
"$render" --backend cpu --size 160x90 --reference --reference-rays 16 --progress 0 --out "$work/long" \
  >/dev/null 2>"$work/long.txt" || problem "reference run failed"
cat "$work/long.txt"
shares=$(grep -cE '^sao-render: \[[0-9]+\.[0-9] s\] tracing the reference \(16 rays/pixel\): [0-9]+ % after [0-9]+\.[0-9] s$' \
  "$work/long.txt")
[ "$shares" -ge 9 ] || problem "$shares share-done lines for the reference, expected one a tenth (>= 9)"
grep -qE '^sao-render: \[[0-9]+\.[0-9] s\] tracing the reference \(16 rays/pixel\): done in' "$work/long.txt" ||
  problem "no line ending the reference"

# Silent when no step lasts the threshold (1000 s here, so that a loaded machine cannot change it).
"$render" --backend cpu --size 64x36 --scene crease --progress 1000 --out "$work/quiet" >/dev/null 2>"$work/quiet.txt" ||
  problem "quiet run failed"
[ -s "$work/quiet.txt" ] && problem "a fast run wrote to stderr: $(cat "$work/quiet.txt")"
exit $fail
