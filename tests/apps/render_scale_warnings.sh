#!/bin/sh
# sao-render's scale warnings (samples/common/include/sao/samples/scale_warnings.h), each on stderr
# (prefixed "sao-render: warning: "), in summary.txt ("warning: ") and in summary.json
# ("warnings"), with exit status 0; none for a scene at the right scale.
#   - radius below 1 px on most geometry pixels (sponza-like with radius 1 cm), which also gives
#     the all-white warning (the effect returns 1 there);
#   - radius beyond the image (sphere-plane read as millimetres);
#   - AO 1.0 on every geometry pixel at a fine radius (a flat square: nothing occludes anything);
#   - no warning: the crease at its defaults.
# Usage: render_scale_warnings.sh SAO_RENDER WORK_DIR
set -u
render=$1 work=$2
rm -rf "$work" && mkdir -p "$work" || exit 1
fail=0

printf 'v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 3 2\nf 1 4 3\n' > "$work/square.obj"

# case NAME "WARNING TEXT|..." ARGS...: the warnings expected (fixed strings, '|'-separated; empty:
# none), in that order.
case_() {
  name=$1 expected=$2; shift 2
  if ! "$render" --backend cpu --size 160x90 --json --out "$work/$name" "$@" > /dev/null 2> "$work/$name.err"; then
    echo "FAIL: $name: exit status not 0:"; cat "$work/$name.err"; fail=1; return
  fi
  python3 - "$work/$name" "$expected" <<'EOF' || fail=1
import json, sys
out, expected = sys.argv[1], [w for w in sys.argv[2].split("|") if w]
stderr = [l[len("sao-render: warning: "):] for l in open(out + ".err").read().splitlines() if l.startswith("sao-render: warning: ")]
text = [l[len("warning: "):] for l in open(out + "/summary.txt").read().splitlines() if l.startswith("warning: ")]
data = json.load(open(out + "/summary.json"))["warnings"]
ok = len(stderr) == len(expected) and all(e in w for e, w in zip(expected, stderr)) and stderr == text == data
print(("ok: " if ok else "FAIL: ") + out + ": " + repr(stderr))
if not ok:
    print("  expected " + repr(expected) + "\n  summary.txt " + repr(text) + "\n  summary.json " + repr(data))
sys.exit(0 if ok else 1)
EOF
}

case_ below-1px "the radius (0.01 m = 0.01 scene units) projects below 1 px on 100 % of the geometry|the AO is 1.0 on every geometry pixel" \
  --scene sponza-like --set radius=0.01
case_ beyond-image "the radius (1 m = 1000 scene units) projects beyond the image's 160 px on 100 % of the geometry" \
  --scene sphere-plane --units mm
case_ all-white "the AO is 1.0 on every geometry pixel: nothing is occluded" --scene "$work/square.obj"
case_ none "" --scene crease
exit $fail
