#!/bin/sh
# sao-render's output folders (docs/ROBUSTNESS.md): a new run replaces an earlier run's folder as
# a whole (no stale lit.png, reference.png, summary.json or passes/ survive), never deletes a file
# it did not write, and a run that fails leaves the folder it would have replaced as it was.
#
#   render_outputs.sh SAO_RENDER WORK_DIR
set -u
render=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
fail=0
problem() { echo "FAIL: $*"; fail=1; }
listing() { (cd "$1" && find . | LC_ALL=C sort | tr '\n' ' '); }
fingerprint() { (cd "$1" && find . -type f | LC_ALL=C sort | xargs cat | cksum); }
leftovers() { ls -A "$1" | grep -F '.sao-render-' ; }  # staging folders and files left beside the outputs

# A scene run with every optional output, then a depth-file run into the same folder.
"$render" --backend cpu --size 64x36 --scene crease --save-depth depth.exr --reference --reference-rays 4 --json \
  --dump-passes out/passes --out out >/dev/null || problem "first run failed"
for f in lit.png reference.png summary.json passes/ao_raw.exr; do [ -s "out/$f" ] || problem "first run: no $f"; done
grep -qx 'passes/ao_raw.exr' out/sao-render-outputs.txt || problem "the manifest does not list passes/ao_raw.exr"
"$render" --backend cpu --depth depth.exr --out out >/dev/null || problem "second run failed"
want=". ./ao.exr ./ao.png ./sao-render-outputs.txt ./summary.txt "
[ "$(listing out)" = "$want" ] || problem "after the depth-file run: '$(listing out)', want '$want'"
grep -q '^input: depth file depth.exr' out/summary.txt || problem "summary.txt is not the second run's"
[ -z "$(leftovers .)" ] || problem "left beside the outputs: $(leftovers .)"

# A separate --dump-passes folder is replaced the same way (every backend writes the same
# intermediates; the CPU's here).
"$render" --backend cpu --size 64x36 --scene crease --dump-passes passes --out out >/dev/null || problem "dump run failed"
[ -s passes/csz_level0.exr ] && [ -s passes/sao-render-outputs.txt ] || problem "no passes/csz_level0.exr or manifest"
# The blur's image ao_low (the upsample's input) is among the intermediates; not without blur.
[ -s passes/ao_low.exr ] || problem "no passes/ao_low.exr with the defaults' blur"
"$render" --backend cpu --size 64x36 --scene crease --set use_z_hierarchy=0 --set blur_radius=0 --dump-passes passes \
  --out out >/dev/null || problem "second dump run failed"
[ -e passes/csz_level1.exr ] && problem "a stale passes/csz_level1.exr survived a run without MIP levels"
[ -e passes/ao_low.exr ] && problem "a stale passes/ao_low.exr survived a run without blur"

# A file the user put into the folder: refused before rendering, nothing deleted or changed.
before=$(fingerprint out)
echo mine > out/notes.txt
out=$("$render" --backend cpu --size 64x36 --scene crease --out out 2>&1 >/dev/null); rc=$?
[ $rc -eq 1 ] || problem "a foreign file in --out: exit $rc, want 1"
echo "$out" | grep -qF "holds 'notes.txt'" || problem "a foreign file in --out: message '$out'"
[ "$(cat out/notes.txt)" = mine ] || problem "notes.txt was changed"
rm out/notes.txt
[ "$(fingerprint out)" = "$before" ] || problem "the refused run changed the folder"

# A non-empty folder without a manifest, and a file as --out: refused, untouched.
mkdir theirs && echo x > theirs/ao.png
out=$("$render" --backend cpu --size 64x36 --scene crease --out theirs 2>&1 >/dev/null); rc=$?
[ $rc -eq 1 ] && echo "$out" | grep -qF "not an earlier sao-render output" || problem "folder without manifest: $rc '$out'"
[ "$(cat theirs/ao.png)" = x ] || problem "theirs/ao.png was overwritten"

# A run that fails after its checks (here: stdout is full) leaves the earlier output as it was
# and nothing beside it.
"$render" --backend cpu --size 64x36 --scene crease --out out >/dev/full 2>err.txt; rc=$?
[ $rc -eq 1 ] && grep -qF "cannot write the summary to stdout" err.txt || problem "stdout full: exit $rc, '$(cat err.txt)'"
[ "$(fingerprint out)" = "$before" ] || problem "the failed run changed the folder"
[ -z "$(leftovers .)" ] || problem "left beside the outputs after a failure: $(leftovers .)"
# Into a folder that did not exist, with missing parents: none of them is left behind.
"$render" --backend cpu --size 64x36 --scene crease --out new/a/b >/dev/full 2>/dev/null
[ -e new ] && problem "a failed run left 'new' behind"
exit $fail
