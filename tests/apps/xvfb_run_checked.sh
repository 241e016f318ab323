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
# The server without its reset when the last client disconnects (-noreset): the readiness probe
# below is such a client, and a command connecting while the server resets after it was refused
# under load ("GLFW error 65544: X11: Failed to open display :553" 0.2 s into a run, once in 12
# runs of apps_viewer_gl_short_key_presses beside a CPU render). xvfb-run's own default, else.
server_args="-screen 0 1280x1024x24"
while [ $# -gt 0 ]; do
  case $1 in
    -a | -l) opts+=("$1"); shift ;;
    -s) server_args=$2; shift 2 ;;
    -n | -e | -f | -p | -w) opts+=("$1" "$2"); shift 2 ;;
    --) shift; break ;;
    *) break ;;
  esac
done
opts+=(-s "$server_args -noreset")
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
