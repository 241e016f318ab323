#!/bin/sh
# sao-viewer's split-resolution view (apps_viewer_<backend>_split_resolution): the sphere on its
# plane in the AO view at resolution_divisor 1, 2 and 4, and in the split-resolution view with the
# panel's divisor at 1 (the second effect runs 2, right of the divider) and at 4 (the second
# effect runs 1, left of it). viewer_check asks, away from the 2-pixel divider and above the
# labels, that the left half be exactly the divisor-1 AO screenshot and the right half exactly the
# reduced one, that each half differ from the other divisor's screenshot in at least 1000 pixels
# (so the equalities tell the two apart), and that the divider be drawn.
#   viewer_split_resolution.sh XVFB_RUN SAO_VIEWER VIEWER_CHECK BACKEND DIR [VIEWER FLAGS...]
set -u
xvfb=$1 viewer=$2 check=$3 backend=$4 dir=$5
shift 5
rm -rf "$dir" && mkdir -p "$dir" || exit 1

shot() {  # NAME VIEWER ARGS...: a screenshot after 5 frames, or the log and exit 1
  name=$1
  shift
  if ! "$xvfb" -a -s '-screen 0 1280x800x24' "$viewer" --size 640x400 --frames 5 --screenshot "$dir/$name.png" \
      --backend "$backend" --scene sphere-plane --hide-ui "$@" >"$dir/$name.log" 2>&1; then
    cat "$dir/$name.log"
    echo "FAIL: sao-viewer $* exited with an error"
    exit 1
  fi
}

# $@ (the backend's flags) goes to every run. The divisor is always given: the defaults' is 2.
shot full "$@" --view-mode ao --set resolution_divisor=1
shot half "$@" --view-mode ao --set resolution_divisor=2
shot quarter "$@" --view-mode ao --set resolution_divisor=4
shot split_1 "$@" --view-mode split-resolution --set resolution_divisor=1
shot split_4 "$@" --view-mode split-resolution --set resolution_divisor=4

left=0,0,0.498,0.94 right=0.502,0,1,0.94
status=0
"$check" "$dir/split_1.png" --min-stddev 0.02 --rgb 0.499,0.02,0.5015,0.9 1,0.45,0.1 0.01 \
  --same-as "$dir/full.png" $left --same-as "$dir/half.png" $right \
  --differs-from "$dir/half.png" $left 1000 --differs-from "$dir/full.png" $right 1000 || status=1
"$check" "$dir/split_4.png" --min-stddev 0.02 --rgb 0.499,0.02,0.5015,0.9 1,0.45,0.1 0.01 \
  --same-as "$dir/full.png" $left --same-as "$dir/quarter.png" $right \
  --differs-from "$dir/quarter.png" $left 1000 --differs-from "$dir/full.png" $right 1000 || status=1
exit $status
