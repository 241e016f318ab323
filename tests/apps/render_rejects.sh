#!/bin/sh
# sao-render refuses bad input (docs/ROBUSTNESS.md): for each row of the table below, the exit
# status (2 bad option, 1 failed run), nothing on stdout, exactly one line on stderr that starts
# with "sao-render: " and names the problem, and no output folder left behind.
#
#   render_rejects.sh SAO_RENDER WORK_DIR
#
# Rows run in WORK_DIR with relative paths, so WORK_DIR may hold spaces.
set -u
render=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")  # absolute: the rows run in WORK_DIR
work=$2
rm -rf "$work" && mkdir -p "$work/adir" "$work/dir.exr" && cd "$work" || exit 1

# Depth files: a good one with its camera, then broken ones made from it.
"$render" --backend cpu --size 32x18 --scene crease --save-depth good.exr --out setup >/dev/null || exit 1
head -c 300 good.exr > truncated.exr
printf 'not an exr' > text.exr
: > empty.exr
mkfifo fifo.exr || exit 1
# The --reference row below must fail for --reference alone: the same run without it succeeds.
"$render" --backend cpu --depth good.exr --out control >/dev/null && test -s control/ao.png || {
  echo "control run on good.exr failed"; exit 1; }

fail=0
check() {  # RC SUBSTRING ARGS...
  want_rc=$1 want=$2
  shift 2
  rm -rf out
  # Rows name their own --backend when they test it; the last one given wins.
  "$render" --backend cpu --out out "$@" >stdout.txt 2>stderr.txt
  rc=$?
  err=$(cat stderr.txt)
  echo "$* -> $rc: $err"
  problem=""
  [ "$rc" -eq "$want_rc" ] || problem="exit status $rc, want $want_rc"
  [ -s stdout.txt ] && problem="$problem; wrote to stdout"
  [ "$(wc -l < stderr.txt)" -eq 1 ] || problem="$problem; stderr is not one line"
  case $err in "sao-render: "*) ;; *) problem="$problem; stderr does not start with 'sao-render: '" ;; esac
  printf '%s\n' "$err" | grep -qF -e "$want" || problem="$problem; stderr lacks '$want'"
  [ -e out ] && problem="$problem; the output folder was created"
  [ -z "$problem" ] || { echo "  FAIL:$problem"; fail=1; }
}

check 2 "unknown backend 'nosuch'" --backend nosuch
check 2 "unknown preset 'nosuch'" --preset nosuch
check 2 "--depth-format expects D16, D24 or D32F, got 'nosuch'" --depth-format nosuch
check 2 "unknown option '--nosuch'" --nosuch
check 2 "--size needs a value" --size
check 2 "--size width expects a whole number in [1, 16384], got '0'" --size 0x0
check 2 "--size height expects a whole number in [1, 16384], got '0'" --size 64x0
check 2 "--size expects WxH, got 'abc'" --size abc
check 2 "--size expects WxH, got '64'" --size 64
check 2 "got '20000'" --size 20000x20000
check 2 "got '99999999999'" --size 99999999999x2
check 2 "--guard expects a whole number in [0, 4096], got '5000'" --guard 5000
check 2 "--view 999 is out of range: scene 'sponza-like' has views 0.." --view 999
check 2 "--view 3 is out of range: scene 'crease' has views 0..0" --scene crease --view 3
check 2 "--view expects a whole number in [0, 1000], got '-1'" --view -1
check 2 "--clip expects gl or zero-one, got 'nosuch'" --clip nosuch
check 2 "--far expects a finite number, got 'abc'" --far abc
check 2 "expected name=value, got 'noequals'" --set noequals
check 2 "setting 'radius' is NaN" --set radius=nan
check 2 "setting 'samples' is +inf" --set samples=1e400
check 2 "unknown setting 'unknown'" --set unknown=1
check 2 "setting 'radius' = 1000 is outside its range [0.01, 100] m" --set radius=1000
check 2 "--reference needs a scene, not a --depth file" --depth good.exr --reference
check 1 "unknown built-in scene 'nope'" --scene nope
check 1 "/nonexistent.glb: no such file" --scene /nonexistent.glb
check 1 "adir: is a directory" --scene adir
check 1 "/nonexistent/depth.exr: no such file" --depth /nonexistent/depth.exr
check 1 "missing.exr: no such file" --depth missing.exr
check 1 "directory" --depth dir.exr
check 1 "not an OpenEXR" --depth text.exr
check 1 "not an OpenEXR" --depth empty.exr
check 1 "corrupt header" --depth truncated.exr
check 1 "not a regular file" --depth fifo.exr

# --help is no error: usage on stdout, exit 0, nothing on stderr.
"$render" --help >stdout.txt 2>stderr.txt
rc=$?
if [ "$rc" -ne 0 ] || [ -s stderr.txt ] || [ "$(head -n 1 stdout.txt)" != "usage: sao-render [options]" ] ||
   ! grep -qF -e "--backend NAME" stdout.txt; then
  echo "--help -> $rc: want exit 0, usage on stdout, empty stderr"; fail=1
fi
exit $fail
