#!/bin/sh
# sao-viewer at a few frames a second (apps_viewer_<backend>_short_key_presses): under Xvfb, the
# viewer holds every frame at least 300 ms (--min-frame-ms) while xdotool gives eight view-mode
# keys, each held a few milliseconds (far shorter than a frame), then Escape. Every press must
# take effect: the viewer prints "view mode NAME (key N)" for each, and the test asks for all
# eight, in order, and a clean exit. No timing enters the verdict: however slow the frames, each
# press is queued by GLFW's key callback until the next frame.
#   viewer_keys.sh XVFB_RUN SAO_VIEWER BACKEND DIR [VIEWER FLAGS...]
set -u
if [ "${1:-}" != "--inside" ]; then  # run this script again inside the X server
  xvfb=$1
  shift
  exec "$xvfb" -a -s '-screen 0 1280x800x24' sh "$0" --inside "$@"
fi
shift
viewer=$1 backend=$2 dir=$3
shift 3
rm -rf "$dir" && mkdir -p "$dir" || exit 1

# --frames: a bound for a failed run only (Escape ends a good one after a frame or two).
"$viewer" --backend "$backend" "$@" --scene sphere-plane --size 320x200 --hide-ui --view-mode lit \
  --min-frame-ms 300 --frames 200 >"$dir/out.txt" 2>"$dir/err.txt" &
pid=$!

fail() {
  kill "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  echo "--- stdout"; cat "$dir/out.txt"; echo "--- stderr"; cat "$dir/err.txt"
  echo "FAIL: $*"
  exit 1
}

# The viewer's window (it exists before the first frame; keys wait in the X queue till then).
wid=
while [ -z "$wid" ]; do
  kill -0 "$pid" 2>/dev/null || fail "sao-viewer exited before its window appeared"
  wid=$(xdotool search --onlyvisible --name '^sao-viewer' 2>/dev/null | head -n 1)
  [ -n "$wid" ] || sleep 0.1
done
xdotool windowfocus --sync "$wid" || fail "xdotool cannot focus the window"

# Eight view modes (the run starts in lit, key 2), each key down for 5 ms, 40 ms apart.
keys="3 5 1 6 9 4 7 8"
for k in $keys; do
  xdotool keydown "$k" sleep 0.005 keyup "$k" sleep 0.04 || fail "xdotool keydown/keyup $k"
done
xdotool keydown Escape sleep 0.005 keyup Escape || fail "xdotool Escape"
wait "$pid"
rc=$?
[ $rc -eq 0 ] || fail "sao-viewer exited with status $rc"

want=""
for k in $keys; do want="$want $k"; done
got=$(sed -n 's/^sao-viewer: view mode [a-z-]* (key \([0-9]\))$/\1/p' "$dir/out.txt" | tr '\n' ' ')
[ "$(echo $got)" = "$(echo $want)" ] || fail "key presses seen: '$(echo $got)', sent: '$(echo $want)'"
grep -q '^sao-viewer: view mode split-resolution (key 9)$' "$dir/out.txt" || fail "no 'view mode split-resolution (key 9)' line"
echo "every key press took effect:$want ($(grep -o '[0-9]* frames' "$dir/out.txt"))"
