#!/usr/bin/env bash
# xvfb-run, checked. Debian's `xvfb-run -a` starts at display :99, which the server of the test
# before may still hold while it goes away (seen under load: "GLFW error 65544: X11: Failed to open
# display :99", the viewer failing in 0.2 s): this run takes a display number of its own, and the
# command starts only once that server answers (else the server is started again, at most three
# times). Only the server's start is retried, never the command: its exit status is returned as it
# is (75 is this script's).
# usage: xvfb_run_checked.sh [XVFB-RUN OPTIONS: -a, -s ARGS, ...] COMMAND [ARGS...]
set -u
real=$(command -v xvfb-run) || { echo "xvfb_run_checked.sh: xvfb-run is not installed" >&2; exit 2; }
opts=()
while [ $# -gt 0 ]; do
  case $1 in
    -a | -l) opts+=("$1"); shift ;;
    -s | -n | -e | -f | -p | -w) opts+=("$1" "$2"); shift 2 ;;
    --) shift; break ;;
    *) break ;;
  esac
done
# A display number of this run's own, past any lock file or socket still there: the server of the
# test before (:99, xvfb-run's first choice) may still answer while it goes away.
n=$((100 + $$ % 800))
while [ -e "/tmp/.X$n-lock" ] || [ -e "/tmp/.X11-unix/X$n" ]; do n=$((n + 1)); done
opts+=(-n "$n")
for attempt in 1 2 3; do
  "$real" "${opts[@]}" bash -c \
    'for i in $(seq 1 50); do xdotool getdisplaygeometry >/dev/null 2>&1 && exec "$@"; sleep 0.1; done; exit 75' bash "$@"
  rc=$?
  [ "$rc" -ne 75 ] && exit "$rc"
  echo "xvfb_run_checked.sh: the X server did not answer (attempt $attempt of 3)" >&2
done
exit 75
