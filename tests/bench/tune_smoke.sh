#!/bin/sh
# The sao-bench --tune smoke test (--quick: two scenes, 26 grid candidates (2 of the visibility estimator), the untuned medium and defaults, today's 5 presets, the
# AlchemyAO-style baseline and 3 more measurements of medium (the time anchors), on the cpu
# backend): it writes tune.csv (one row per candidate, a header with the scenes), tune_front.csv/.svg and tune_presets.txt with pasteable preset
# lines; the chosen chain steps up on every scene (slower, lower RMSE vs (c)); a second run into
# the same folder evaluates nothing, leaves tune.csv as it was and writes the same tune_presets.txt;
# a run after losing rows evaluates exactly the lost ones and, in its own session (tune.csv's last
# column), the time anchors around them, leaving the earlier rows as they were; a tune.csv written
# before the session column is read as session 1 and gains the column when appended to; a tune.csv
# with another header is refused.
# usage: tune_smoke.sh SAO_BENCH OUT_DIR
set -eu
bench=$1
out=$2
rm -rf "$out"
mkdir -p "$out"
die() { echo "tune smoke: $*" >&2; exit 1; }
tune() { "$bench" --tune --quick --backends cpu --out "$1" >"$out/stdout" 2>"$out/stderr" || die "sao-bench --tune --quick failed: $(tail -3 "$out/stderr")"; }

tune "$out/t"
for f in tune.csv tune_front.csv tune_front.svg tune_presets.txt; do test -s "$out/t/$f" || die "missing $f"; done
grep -q ', 37 to evaluate$' "$out/stderr" || die "first run: expected 37 candidates to evaluate: $(grep 'to evaluate' "$out/stderr")"
grep -q '\[37/37\] ' "$out/stderr" || die "no progress line [37/37]"
[ "$(awk 'END { print NR }' "$out/t/tune.csv")" -eq 38 ] || die "tune.csv: expected a header and 37 rows"
[ "$(grep -c '^anchor,medium-' "$out/t/tune.csv")" -eq 3 ] || die "tune.csv: expected 3 anchor rows"
head -1 "$out/t/tune.csv" | grep -q ',crease_rmse_vs_c,.*,sphere-plane_rmse_vs_c,' || die "tune.csv: no per-scene columns"
head -1 "$out/t/tune.csv" | grep -q ',sphere-plane_silhouette,session$' || die "tune.csv: no session column last"
[ "$(awk -F, 'NR > 1 && $NF != 1' "$out/t/tune.csv")" = "" ] || die "first run: a row not of session 1"
for label in "Pareto front" "tuned presets" "today's presets" "AlchemyAO-style baseline"; do
  grep -qF ">$label<" "$out/t/tune_front.svg" || die "tune_front.svg has no series '$label'"
done

# Preset lines in the effect's format, named as today's presets, cheapest first. Five when a chain
# of five steps up on every scene; the tuner falls back to the longest shorter chain (and says so)
# when the run's times allow none: how many depends on timing (under the sanitizers four were
# chosen once), so at least two are asked for here, in budget order.
[ "$(grep -c '^#pragma sao preset ' "$out/t/tune_presets.txt")" -ge 2 ] || die "expected at least 2 preset lines: $(cat "$out/t/tune_presets.txt")"
awk '/^#pragma sao preset/ { print $4 }' "$out/t/tune_presets.txt" | awk '
  BEGIN { rank["low"] = 1; rank["medium"] = 2; rank["high"] = 3; rank["ultra"] = 4; rank["reference"] = 5 }
  { if (!($1 in rank) || rank[$1] <= last) bad = 1; last = rank[$1] } END { exit bad }' ||
  die "preset names: $(cat "$out/t/tune_presets.txt")"
grep '^#pragma sao preset' "$out/t/tune_presets.txt" | grep -qv ' samples=[0-9]* blur_radius=[0-9] blur_stride=[0-9] use_z_hierarchy=\(true mip_switch_log2=[0-9]\|false\) resolution_divisor=[124]\( estimator=1 slices=[0-9] thickness=[0-9.]* thickness_model=[01]\)\? "[^"]*"$' &&
  die "a preset line is not in the effect's format: $(grep '^#pragma' "$out/t/tune_presets.txt")"

# The chain, cheapest first, from tune_front.csv: on each scene every step is slower and has a
# lower RMSE vs (c); the span targets are printed.
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
  $1 == "tuned" || $1 == "front+tuned" { rank["low"] = 1; rank["medium"] = 2; rank["high"] = 3; rank["ultra"] = 4; rank["reference"] = 5
    k = rank[$2]; n++
    for (s = 1; s <= 2; s++) { sc = s == 1 ? "crease" : "sphere-plane"; t[k, s] = $col[sc "_x_medium"]; e[k, s] = $col[sc "_rmse_vs_c"] } }
  END { if (n < 2) exit 1
    prev = 0
    for (k = 1; k <= 5; k++) {
      if (!((k, 1) in t)) continue
      if (prev) for (s = 1; s <= 2; s++)
        if (!(t[k, s] > t[prev, s] && e[k, s] < e[prev, s])) { print "step " k " scene " s > "/dev/stderr"; exit 1 }
      prev = k } }' \
  "$out/t/tune_front.csv" || die "the chosen chain does not step up on every scene: $(grep '^\(front+\)\?tuned,' "$out/t/tune_front.csv")"
grep -q '^targets: [2-5] presets' "$out/stdout" || die "no targets line: $(tail -5 "$out/stdout")"

# Resumed: nothing new, the same record and the same presets.
cp "$out/t/tune.csv" "$out/tune.csv.first"
cp "$out/t/tune_presets.txt" "$out/presets.first"
tune "$out/t"
grep -q ', 37 in .*, 0 to evaluate$' "$out/stderr" || die "second run evaluated again: $(grep 'to evaluate' "$out/stderr")"
cmp -s "$out/t/tune.csv" "$out/tune.csv.first" || die "the second run changed tune.csv"
cmp -s "$out/t/tune_presets.txt" "$out/presets.first" || die "the second run wrote another tune_presets.txt: $(diff "$out/presets.first" "$out/t/tune_presets.txt")"

# A row's candidate columns (all before runs): what a resumed run looks a grid or preset row up by.
candidate() { awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "runs") n = i - 1; next }
  { line = $1; for (i = 2; i <= n; i++) line = line "," $i; print line }' "$@"; }

# Interrupted after 20 rows (candidates 0-19, anchor 0 (the untuned medium) and anchor medium-18
# among them): the rerun, session 2, evaluates the other 15 candidates and the anchors around them,
# medium-18, medium-29 and medium-36, measured again in this session (18 rows); the 20 rows stay
# session 1, their anchors untouched.
mkdir -p "$out/cut"
cp "$out/t/sao-bench-outputs.txt" "$out/cut/"  # written before the first row: the folder is the tune's
head -21 "$out/tune.csv.first" >"$out/cut.csv"
cp "$out/cut.csv" "$out/cut/tune.csv"
tune "$out/cut"
grep -q ', 20 in .*, 18 to evaluate$' "$out/stderr" || die "resume after 20 rows: $(grep 'to evaluate' "$out/stderr")"
grep -q 'session 2 of tune.csv: 3 of those are measurements of the untuned medium' "$out/stderr" ||
  die "resume after 20 rows: no session line: $(grep 'session' "$out/stderr")"
[ "$(awk 'END { print NR }' "$out/cut/tune.csv")" -eq 39 ] || die "resumed tune.csv: expected 38 rows"
head -21 "$out/cut/tune.csv" | cmp -s - "$out/cut.csv" || die "the resumed run changed the earlier rows"
[ "$(tail -n +22 "$out/cut/tune.csv" | awk -F, '$NF != 2')" = "" ] || die "a row added by the resumed run is not of session 2"
[ "$(tail -n +22 "$out/cut/tune.csv" | grep '^anchor,' | cut -d, -f2 | tr '\n' ' ')" = "medium-18 medium-29 medium-36 " ] ||
  die "session 2's anchors: $(tail -n +22 "$out/cut/tune.csv" | grep '^anchor,' | cut -d, -f2,1 | tr '\n' ' ')"
[ "$(grep -c '^anchor,medium-18,' "$out/cut/tune.csv")" -eq 2 ] || die "medium-18 of session 1 was not kept beside session 2's"
{ head -1 "$out/tune.csv.first"; tail -n +22 "$out/tune.csv.first" | grep -v '^anchor,'; } | candidate | sort >"$out/lost"
{ head -1 "$out/cut/tune.csv"; tail -n +22 "$out/cut/tune.csv" | grep -v '^anchor,'; } | candidate | sort >"$out/again"
[ "$(wc -l <"$out/lost")" -eq 15 ] && cmp -s "$out/lost" "$out/again" ||
  die "session 2 evaluated other candidates than the 15 lost: $(diff "$out/lost" "$out/again")"
grep -q '^tune.csv holds 2 sessions' "$out/stdout" || die "the report does not say the record holds 2 sessions: $(tail -3 "$out/stdout")"

# A tune.csv of the format before the session column (no such column): its rows are session 1. Whole,
# it is resumed as it is (nothing evaluated, the file not rewritten, the same presets); without a
# preset's row, that row and the anchors around it (the untuned medium, candidate 0, and medium-18)
# are measured in session 2, and the file is rewritten with the column first, its rows session 1.
mkdir -p "$out/old"
cp "$out/t/sao-bench-outputs.txt" "$out/old/"
sed 's/,[^,]*$//' "$out/tune.csv.first" >"$out/old.csv"
cp "$out/old.csv" "$out/old/tune.csv"
tune "$out/old"
grep -q ', 37 in .*, 0 to evaluate$' "$out/stderr" || die "old format, whole: $(grep 'to evaluate' "$out/stderr")"
cmp -s "$out/old/tune.csv" "$out/old.csv" || die "old format, whole: tune.csv was rewritten"
cmp -s "$out/old/tune_presets.txt" "$out/presets.first" || die "old format, whole: other presets: $(diff "$out/presets.first" "$out/old/tune_presets.txt")"
[ "$(sed -n 4p "$out/old.csv" | cut -d, -f1)" = preset ] || die "expected a preset on tune.csv's line 4: $(sed -n 4p "$out/old.csv")"
sed 4d "$out/old.csv" >"$out/old/tune.csv"
tune "$out/old"
grep -q ', 36 in .*, 3 to evaluate$' "$out/stderr" || die "old format without a preset: $(grep 'to evaluate' "$out/stderr")"
{ head -1 "$out/tune.csv.first"; sed '1d;4d;s/$/,1/' "$out/old.csv"; } >"$out/old.expected"
head -37 "$out/old/tune.csv" | cmp -s - "$out/old.expected" || die "old format: not rewritten with session 1: $(head -37 "$out/old/tune.csv" | diff "$out/old.expected" - | head -5)"
[ "$(tail -n +38 "$out/old/tune.csv" | awk -F, '{ print $1 "," $2 "," $NF }' | tr '\n' ' ')" = "unit,untuned-medium,2 $(sed -n 4p "$out/old.csv" | cut -d, -f1,2),2 anchor,medium-18,2 " ] ||
  die "old format: session 2's rows: $(tail -n +38 "$out/old/tune.csv" | cut -c1-40)"

# Another header (another scene set) is refused, naming the file.
mkdir -p "$out/bad"
cp "$out/t/sao-bench-outputs.txt" "$out/bad/"
echo "kind,name,something,else" >"$out/bad/tune.csv"
if "$bench" --tune --quick --backends cpu --out "$out/bad" >/dev/null 2>"$out/stderr"; then die "a mismatching header was accepted"; fi
grep -q 'tune.csv was written by another tune (its header differs' "$out/stderr" || die "unclear header error: $(cat "$out/stderr")"
# The visibility estimator's rows name the frames of their own converged value (4 with --quick),
# the paper's estimator's 0.
grep -q '^grid,,cpu,[a-z]*,depth,160x90,4096,4,.*,1,2,0.3,1,' "$out/t/tune.csv" ||
  die "no visibility-estimator row with 4 frames of its converged value: $(grep -m1 ',1,2,0.3,' "$out/t/tune.csv")"
grep -q '^grid,,cpu,[a-z]*,depth,160x90,4096,0,' "$out/t/tune.csv" || die "no paper's-estimator row with own_converged_frames 0"

# --objective a: the error vs reference (a) (16 rays with --quick), its own header; a tune.csv of
# the other objective is refused rather than mixed; the options it needs are checked.
"$bench" --tune --quick --backends cpu --objective a --out "$out/a" >"$out/stdout" 2>"$out/stderr" ||
  die "--objective a failed: $(tail -3 "$out/stderr")"
head -1 "$out/a/tune.csv" | grep -q ',converged_taps,own_converged_frames,a_rays,.*,crease_rmse_vs_a,.*,sphere-plane_rmse_vs_a,' ||
  die "--objective a: tune.csv header: $(head -1 "$out/a/tune.csv")"
grep -q '^unit,untuned-medium,cpu,[a-z]*,depth,160x90,4096,0,16,' "$out/a/tune.csv" || die "--objective a: no a_rays 16 in the rows"
grep -q 'the error vs reference (a) with 16 rays' "$out/stdout" || die "--objective a: not said: $(head -3 "$out/stdout")"
head -1 "$out/a/tune_front.csv" | grep -q '^role,name,time_x_medium,total_ms,mean_rmse_vs_a,' || die "--objective a: tune_front.csv header"
cp "$out/t/tune.csv" "$out/a/tune.csv"
if "$bench" --tune --quick --backends cpu --objective a --out "$out/a" >/dev/null 2>"$out/stderr"; then die "objective a resumed objective c's tune.csv"; fi
grep -q 'another objective' "$out/stderr" || die "unclear objective mismatch: $(cat "$out/stderr")"
set +e
"$bench" --tune --quick --rays 64 --out "$out/r" >/dev/null 2>"$out/stderr"; rc=$?
set -e
[ $rc -eq 2 ] && grep -q -- '--quick and --rays' "$out/stderr" || die "--quick --rays: rc $rc $(cat "$out/stderr")"
set +e
"$bench" --tune --rays 64 --out "$out/r" >/dev/null 2>"$out/stderr"; rc=$?
set -e
[ $rc -eq 2 ] && grep -q 'only --objective a uses' "$out/stderr" || die "--tune --rays without --objective a: rc $rc $(cat "$out/stderr")"
set +e
"$bench" --objective a --out "$out/r" >/dev/null 2>"$out/stderr"; rc=$?
set -e
[ $rc -eq 2 ] && grep -q 'add --tune' "$out/stderr" || die "--objective without --tune: rc $rc $(cat "$out/stderr")"
echo "tune smoke: ok"
