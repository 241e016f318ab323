#!/bin/sh
# sao-viewer at a few frames a second, under Xvfb with xdotool: every frame held at least 300 ms
# (--min-frame-ms) and every key down for 5 ms only, far shorter than a frame.
#   presses (apps_viewer_<backend>_short_key_presses): eight view-mode keys 40 ms apart, then
#     Escape. The viewer prints "view mode NAME (key N)" for each press; the test asks for all
#     eight, in order, and a clean exit.
#   text-field (apps_viewer_<backend>_text_field_keys): Ctrl+click on the panel's "split" slider
#     opens ImGui's text field; "0.25" typed into it must not switch view modes (2 and 5 are mode
#     keys), a short Enter must close it, and then key 1 must give the AO view; F12's screenshot
#     shows the divider moved to 0.25 of the strip beside the panel.
# No timing enters the verdict: the test waits for the viewer's own lines ("a text field has the
# keyboard", ...) before each next step, and each press is queued by GLFW's key callback until the
# next frame however slow the frame.
#   viewer_keys.sh XVFB_RUN SAO_VIEWER VIEWER_CHECK BACKEND DIR presses|text-field [VIEWER FLAGS...]
set -u
if [ "${1:-}" != "--inside" ]; then  # run this script again inside the X server
  xvfb=$1
  shift
  exec "$xvfb" -a -s '-screen 0 1280x800x24' sh "$0" --inside "$@"
fi
shift
viewer=$1 check=$2 backend=$3 dir=$4 scenario=$5
shift 5
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir" || exit 1

fail() {
  kill "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  echo "--- stdout"; cat out.txt; echo "--- stderr"; cat err.txt
  echo "FAIL: $*"
  exit 1
}

# Waits until the viewer's stdout holds LINE (N times; default 1), as long as the viewer runs.
wait_for() {
  while [ "$(grep -cx "sao-viewer: $1" out.txt)" -lt "${2:-1}" ]; do
    kill -0 "$pid" 2>/dev/null || fail "sao-viewer exited before printing '$1' (${2:-1} times)"
    sleep 0.05
  done
}

press() {  # KEY: down for 5 ms
  xdotool keydown "$1" sleep 0.005 keyup "$1" || fail "xdotool keydown/keyup $1"
}

# --frames: a bound for a failed run only (Escape ends a good one).
case $scenario in
  presses) size=320x200 flags="--hide-ui --view-mode lit" ;;
  text-field) size=1280x720 flags="--view-mode split" ;;
  *) echo "unknown scenario '$scenario'"; exit 2 ;;
esac
"$viewer" --backend "$backend" "$@" --scene sphere-plane --size $size $flags --min-frame-ms 300 --frames 200 \
  >out.txt 2>err.txt &
pid=$!

# The viewer's window (it exists before the first frame; keys wait in the X queue till then).
wid=
while [ -z "$wid" ]; do
  kill -0 "$pid" 2>/dev/null || fail "sao-viewer exited before its window appeared"
  wid=$(xdotool search --onlyvisible --name '^sao-viewer' 2>/dev/null | head -n 1)
  [ -n "$wid" ] || sleep 0.1
done
xdotool windowfocus --sync "$wid" || fail "xdotool cannot focus the window"

if [ "$scenario" = presses ]; then
  keys="3 5 1 6 9 4 7 8"  # the run starts in lit (key 2)
  for k in $keys; do
    press "$k"
    sleep 0.04
  done
  press Escape
  wait "$pid"
  rc=$?
  [ $rc -eq 0 ] || fail "sao-viewer exited with status $rc"
  want=""
  for k in $keys; do want="$want $k"; done
  got=$(sed -n 's/^sao-viewer: view mode [a-z-]* (key \([0-9]\))$/\1/p' out.txt | tr '\n' ' ')
  [ "$(echo $got)" = "$(echo $want)" ] || fail "key presses seen: '$(echo $got)', sent: '$(echo $want)'"
  grep -qx 'sao-viewer: view mode split-resolution (key 9)' out.txt || fail "no 'view mode split-resolution (key 9)'"
  echo "every key press took effect:$want ($(grep -o '[0-9]* frames' out.txt))"
  exit 0
fi

# text-field. First a frame with the panel: ImGui finds the window under a click from the last
# frame's windows (key 4, the split view the run starts in, is printed at a frame's start; the
# click after it is read at the next frame's start at the earliest).
press 4
wait_for "view mode split (key 4)"
# The "split" slider is the panel's fourth row (the backend's line, the frame time, the view mode,
# the split), at the same place on every backend and driver.
xdotool mousemove --window "$wid" 100 101 keydown ctrl sleep 0.005 click 1 sleep 0.005 keyup ctrl ||
  fail "xdotool Ctrl+click"
wait_for "a text field has the keyboard"
xdotool type --delay 5 "0.25" || fail "xdotool type"
press Return
wait_for "the text field let the keyboard go"
press 1
wait_for "view mode ao (key 1)"
press 4
wait_for "view mode split (key 4)" 2
press F12
while ! grep -q '^sao-viewer: screenshot ' out.txt; do
  kill -0 "$pid" 2>/dev/null || fail "sao-viewer exited before its screenshot"
  sleep 0.05
done
press Escape
wait "$pid"
rc=$?
[ $rc -eq 0 ] || fail "sao-viewer exited with status $rc"
got=$(sed -n 's/^sao-viewer: view mode [a-z-]* (key \([0-9]\))$/\1/p' out.txt | tr '\n' ' ')
[ "$(echo $got)" = "4 1 4" ] || fail "view-mode keys seen: '$(echo $got)', want '4 1 4' (not the 2 and 5 typed into the field)"
shot=$(sed -n 's/^sao-viewer: screenshot //p' out.txt)
# The divider at 0.25 of the strip right of the panel (x 366.4..1280 of 1280): x 594, white.
"$check" "$shot" --rgb 0.4643,0.45,0.4644,0.85 1,1,1 0.02 || fail "the split is not at 0.25 (divider not at x 594)"
echo "the text field kept its keys (0.25 typed, Enter closed it; $(grep -o '[0-9]* frames' out.txt)), keys 1 and 4 worked after it"
