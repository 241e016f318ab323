#!/bin/sh
# The inert-setting rule (gen::kInertRules, docs/effect-format.md `inert`) judges the final settings
# and what the user gave, not each --set on its own or a preset's values: each row runs and exits 0.
# (The refusals are rows of render_rejects.sh.)
#
#   render_inert_settings.sh SAO_RENDER WORK_DIR
set -u
render=$1 work=$2
rm -rf "$work" && mkdir -p "$work" || exit 1
fail=0
n=0
accepts() {  # ARGS...
  n=$((n + 1))
  "$render" --backend cpu --size 32x18 --scene crease --out "$work/run$n" "$@" >/dev/null 2>"$work/err$n.txt"
  rc=$?
  echo "$* -> $rc"
  [ "$rc" -eq 0 ] || { echo "  FAIL: refused: $(cat "$work/err$n.txt")"; fail=1; }
}
# The low preset lists blur_stride=1; with blur_radius=0 it has no effect, but a preset's own values
# are never refused.
accepts --preset low --set blur_radius=0
# A setting given before the one that makes it effective, and after.
accepts --set fade_start=1 --set fade_end=5
accepts --set fade_end=5 --set fade_start=1
# A later --set takes the rule back: blur_radius ends at 1.
accepts --set blur_radius=0 --set blur_stride=2 --set blur_radius=1
# --resolution-divisor, applied after --preset and --set, decides too: divisor 2 is no direct output.
accepts --preset reference --set blur_radius=0 --set half_intermediates=false --resolution-divisor 2
# Temporal accumulation makes its settings count (a path of frames, as --set temporal=true needs).
accepts --set temporal=true --set temporal_hysteresis=0.5 --set temporal_depth_tolerance=0.1 --frames 2
exit $fail
