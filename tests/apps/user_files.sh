#!/bin/sh
# Nothing of the user's is overwritten (docs/ROBUSTNESS.md, "Files of the user's"): every writer of
# sao-render, sao-viewer and sao-bench follows one rule (sao/samples/output_files.h). For each row
# of the program's table: the exit status (2: a bad name, or an input named as an output; 1: a file
# or folder of the user's in the way), exactly one line on stderr naming the path and the fix, the
# user's files byte for byte as they were, and nothing left behind (no output folder, no staging
# file). Then --overwrite doing the replacement, and only that.
#
#   user_files.sh render SAO_RENDER WORK_DIR
#   user_files.sh viewer SAO_VIEWER WORK_DIR XVFB_RUN   (the replacing run opens a window)
#   user_files.sh bench  SAO_BENCH  WORK_DIR
set -u
what=$1
tool=$(cd "$(dirname "$2")" && pwd)/$(basename "$2")  # absolute: the rows run in WORK_DIR
work=$3
xvfb=${4:-}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
name=$(basename "$tool")
fail=0
problem() { echo "FAIL: $*"; fail=1; }
fingerprint() { find . -path ./stdout.txt -prune -o -path ./stderr.txt -prune -o -print | LC_ALL=C sort |
  while read -r f; do if [ -f "$f" ]; then echo "$f $(cksum < "$f")"; else echo "$f"; fi; done; }
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; }
is_exr() { [ "$(head -c 4 "$1" | od -An -tx1 | tr -d ' \n')" = 762f3101 ]; }

# check RC SUBSTRING ARGS...: refused, one line, and the folder exactly as it was.
check() {
  want_rc=$1 want=$2
  shift 2
  before=$(fingerprint)
  "$tool" "$@" >stdout.txt 2>stderr.txt
  rc=$?
  err=$(cat stderr.txt)
  echo "$* -> $rc: $err"
  bad=""
  [ "$rc" -eq "$want_rc" ] || bad="exit status $rc, want $want_rc"
  [ "$(wc -l < stderr.txt)" -eq 1 ] || bad="$bad; stderr is not one line (work before the refusal?)"
  case $err in "$name: "*) ;; *) bad="$bad; stderr does not start with '$name: '" ;; esac
  printf '%s\n' "$err" | grep -qF -e "$want" || bad="$bad; stderr lacks '$want'"
  [ "$(fingerprint)" = "$before" ] || bad="$bad; the folder changed: $(fingerprint | tr '\n' ' ')"
  [ -z "$bad" ] || problem "$*: $bad"
}

case $what in
  render)
    "$tool" --backend cpu --size 32x18 --scene crease --save-depth depth.exr --out setup >/dev/null || exit 1
    cp depth.exr theirs.exr  # an EXR of the user's
    echo "my notes" > notes.exr && echo "my notes" > notes.txt
    ln -s depth.exr link.exr && ln depth.exr hard.exr
    mkdir mine && echo mine > mine/notes.txt && cp depth.exr mine/input.exr
    # --progress 0 prints every step as it starts: one line on stderr means nothing was rendered.
    run="--backend cpu --size 32x18 --scene crease --progress 0 --out out"
    check 1 "--save-depth 'notes.exr' exists, and sao-render replaces no file it did not write: give another name, or --overwrite to replace it" $run --save-depth notes.exr
    check 1 "--save-depth 'theirs.exr' exists, and sao-render replaces no file it did not write" $run --save-depth theirs.exr
    check 2 "--save-depth 'notes.txt': sao-render writes an OpenEXR file there, so its name must end in .exr: give e.g. 'notes.exr'" $run --save-depth notes.txt
    check 2 "--save-depth 'new.png': sao-render writes an OpenEXR file there, so its name must end in .exr" $run --save-depth new.png
    check 2 "--save-depth 'out/d.png': sao-render writes an OpenEXR file there" $run --save-depth out/d.png
    # Its own input: refused even with --overwrite, also through a symbolic or a hard link.
    depth="--backend cpu --progress 0 --out out --overwrite"
    check 2 "--save-depth 'depth.exr' is the input --depth 'depth.exr' (the same file): an input is never written onto, --overwrite or not" $depth --depth depth.exr --save-depth depth.exr
    check 2 "--save-depth 'link.exr' is the input --depth 'depth.exr'" $depth --depth depth.exr --save-depth link.exr
    check 2 "--save-depth 'hard.exr' is the input --depth 'depth.exr'" $depth --depth depth.exr --save-depth hard.exr
    check 2 "--save-depth 'depth.exr' is the input --depth 'link.exr'" $depth --depth link.exr --save-depth depth.exr
    # An output folder around an input: replacing its files would delete it.
    check 2 "--out 'mine' holds the input --depth 'mine/input.exr'" --backend cpu --progress 0 --depth mine/input.exr --out mine --overwrite
    check 1 "--out 'mine' is not empty and not an earlier sao-render output" $run --out mine
    [ -e out ] && problem "a refused run left 'out'"

    # --overwrite: the user's file is replaced by the depth EXR; into a folder of the user's, the
    # run's files are written beside theirs, which are kept and not listed as the run's.
    "$tool" $run --save-depth notes.exr --overwrite >/dev/null 2>&1 || problem "--save-depth notes.exr --overwrite failed"
    is_exr notes.exr || problem "--overwrite did not replace notes.exr with an EXR"
    "$tool" --backend cpu --depth notes.exr --out readback >/dev/null 2>&1 || problem "the replaced notes.exr does not read back"
    "$tool" $run --out mine --overwrite >/dev/null 2>&1 || problem "--out mine --overwrite failed"
    [ "$(cat mine/notes.txt)" = mine ] || problem "--overwrite changed mine/notes.txt"
    is_png mine/ao.png || problem "--out mine --overwrite wrote no ao.png"
    grep -qx ao.png mine/sao-render-outputs.txt && ! grep -q notes.txt mine/sao-render-outputs.txt ||
      problem "the manifest of mine: $(cat mine/sao-render-outputs.txt)"
    # The folder still holds the user's file: without --overwrite the next run is refused.
    check 1 "which is not one of the files its sao-render-outputs.txt lists (sao-render did not write it)" $run --out mine
    ;;

  viewer)
    echo "my notes" > notes.png && echo "my notes" > notes.txt
    printf 'v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 2 3\nf 1 3 4\n' > plane.obj
    ln -s plane.obj plane.png
    # Refused before the window opens: these rows need no display.
    check 1 "--screenshot 'notes.png' exists, and sao-viewer replaces no file it did not write: give another name, or --overwrite to replace it" --frames 2 --screenshot notes.png
    check 2 "--screenshot 'notes.txt': sao-viewer writes a PNG file there, so its name must end in .png: give e.g. 'notes.png'" --frames 2 --screenshot notes.txt
    check 2 "--screenshot 'plane.png' is the input --scene 'plane.obj' (the same file)" --frames 2 --scene plane.obj --screenshot plane.png --overwrite
    check 1 "--screenshot 'nofolder/shot.png': its folder" --frames 2 --screenshot nofolder/shot.png
    # --overwrite: the user's file becomes the screenshot.
    "$xvfb" -a -s '-screen 0 1280x800x24' "$tool" --size 160x100 --frames 2 --scene crease --hide-ui \
      --screenshot notes.png --overwrite >stdout.txt 2>stderr.txt || problem "--screenshot notes.png --overwrite failed: $(cat stderr.txt)"
    is_png notes.png || problem "--overwrite did not replace notes.png with a PNG"
    ls -A | grep -qF '.sao-viewer-' && problem "left beside the screenshot: $(ls -A | grep -F '.sao-viewer-')"
    ;;

  bench)
    # The cheapest runs: the quick presets on one scene, timed only (no references), or with the
    # references (the error plot pareto.svg needs them).
    quick="--quick --backends cpu --sections presets --scenes crease"
    mkdir theirs && echo "my notes" > theirs/notes.txt
    mkdir results && echo "my table" > results/results.csv && echo "<svg>mine</svg>" > results/pareto.svg
    printf 'v -5 0 -5\nv 5 0 -5\nv 5 0 5\nv -5 0 5\nf 1 2 3\nf 1 3 4\n' > theirs/plane.obj
    check 1 "--out 'theirs' is not empty and not an earlier sao-bench output (it has no sao-bench-outputs.txt): empty it, choose another folder, or give --overwrite" $quick --time-only --out theirs
    check 1 "--out 'results' is not empty and not an earlier sao-bench output" $quick --out results
    check 1 "--out 'results' is not empty and not an earlier sao-bench output" --tune --quick --backends cpu --out results
    check 2 "--out 'theirs' holds the input --scenes 'theirs/plane.obj'" $quick --time-only --scenes theirs/plane.obj --out theirs --overwrite
    # An earlier sao-bench output is replaced as a whole.
    "$tool" $quick --time-only --out earlier >/dev/null 2>&1 || problem "first run into 'earlier' failed"
    "$tool" $quick --time-only --out earlier >/dev/null 2>&1 || problem "second run into 'earlier' failed"
    # --overwrite: results.csv and pareto.svg of the user's replaced, notes.txt kept.
    echo "my notes" > results/notes.txt
    "$tool" $quick --out results --overwrite >stdout.txt 2>stderr.txt || problem "--out results --overwrite failed: $(tail -1 stderr.txt)"
    head -1 results/results.csv | grep -q '^section,' || problem "--overwrite did not replace results.csv: $(head -1 results/results.csv)"
    grep -q mine results/pareto.svg && problem "--overwrite did not replace pareto.svg"
    [ "$(cat results/notes.txt)" = "my notes" ] || problem "--overwrite changed results/notes.txt"
    grep -qx pareto.svg results/sao-bench-outputs.txt && ! grep -q notes.txt results/sao-bench-outputs.txt ||
      problem "the manifest of results: $(cat results/sao-bench-outputs.txt)"
    grep -qF "wrote $work/results/{" stdout.txt || problem "the summary names another folder: $(grep wrote stdout.txt)"
    ls -A | grep -qF '.sao-bench-' && problem "left beside the outputs: $(ls -A | grep -F '.sao-bench-')"
    ;;
  *) echo "usage: user_files.sh render|viewer|bench TOOL WORK_DIR [XVFB_RUN]"; exit 2 ;;
esac
exit $fail
