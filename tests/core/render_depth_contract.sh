#!/bin/sh
# One contract for depth input on every backend (sao/image.h, docs/ROBUSTNESS.md): sao-render
# refuses a depth file that is not hardware depth (NaN, infinities, values outside [0, 1], linear
# metres) with the same one-line error on cpu, gl and vulkan and leaves no output folder; a sky
# written as -0.0 gives on every backend exactly the ao.exr that +0.0 gives.
#
#   render_depth_contract.sh SAO_RENDER WRITE_DEPTH_FILES WORK_DIR
set -u
render=$1 writer=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
"$writer" . || exit 1

fail=0
backends=""
for b in cpu gl vulkan; do
  if "$render" --backend $b --depth sky_plus_zero.exr --out plus_$b >/dev/null 2>err.txt; then
    backends="$backends $b"
  elif grep -q "built without" err.txt; then
    echo "$b: not built, skipped"
  else
    echo "$b: the control run failed: $(cat err.txt)"; fail=1
  fi
done
[ -n "$backends" ] || { echo "no backend ran"; exit 1; }

refused() {  # NAME SUBSTRING ARGS...: exit 1, one line naming SUBSTRING, the same on every backend
  name=$1 want=$2
  shift 2
  first=""
  for b in $backends; do
    rm -rf out
    "$render" --backend $b --out out "$@" >stdout.txt 2>stderr.txt
    rc=$?
    err=$(cat stderr.txt)
    echo "$name on $b -> $rc: $err"
    problem=""
    [ "$rc" -eq 1 ] || problem="exit status $rc, want 1"
    [ -s stdout.txt ] && problem="$problem; wrote to stdout"
    [ "$(wc -l < stderr.txt)" -eq 1 ] || problem="$problem; stderr is not one line"
    printf '%s\n' "$err" | grep -qF -e "$want" || problem="$problem; stderr lacks '$want'"
    [ -e out ] && problem="$problem; the output folder was created"
    [ -z "$first" ] && first=$err
    [ "$err" = "$first" ] || problem="$problem; differs from the first backend's error"
    [ -z "$problem" ] || { echo "  FAIL:$problem"; fail=1; }
  done
}

refused "NaN, infinities, outside [0, 1]" \
  "'bad_values.exr': 5 of 1536 texels are not D32F depth (1 NaN, 1 +inf, 1 -inf, 1 below 0, 1 above 1); the first is (3, 2) = nan" \
  --depth bad_values.exr
refused "linear metres" \
  "1488 of 1536 texels are not D32F depth (1488 above 1); the first is (0, 1) = 1.25: values above 1 look like linear depth" \
  --depth linear_metres.exr --fovy 60 --near 0.1 --reversed-z

for b in $backends; do
  if "$render" --backend $b --depth sky_minus_zero.exr --out minus_$b >/dev/null 2>err.txt; then
    if cmp -s plus_$b/ao.exr minus_$b/ao.exr; then echo "sky -0.0 on $b: ao.exr identical to +0.0"
    else echo "  FAIL: sky -0.0 on $b: ao.exr differs from +0.0's"; fail=1; fi
  else
    echo "  FAIL: sky -0.0 on $b refused: $(cat err.txt)"; fail=1
  fi
done
exit $fail
