#!/usr/bin/env bash
# Hostile input and faults (docs/robustness.md): output files never replace what
# is not theirs and come back on a failure, results are never lost to a chart, signals
# stop every command in time without leaving temporaries, numerical range, exit codes.
#   check_robustness.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
scene=$src/data/scenes/default.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"
cd "$work"
# No temporaries of ours (".NAME.tmp-*", ".NAME.old-*", ".NAME.part-*") under $1.
no_temporaries() { [ -z "$(find "$1" -name '.*.tmp-*' -o -name '.*.old-*' -o -name '.*.part-*' 2>/dev/null)" ]; }

# --- 1. output targets ------------------------------------------------------------------
"$bin" equilibria "$scene" --format csv -o /dev/null 2>/dev/null
check "-o /dev/null: exit 0, written in place" "[ $? -eq 0 ] && [ -c /dev/null ]"
mkdir -p "$work/adir"
"$bin" equilibria "$scene" --format csv -o "$work/adir" 2>"$work/dir.err"
check "-o DIRECTORY refused with exit 2" "[ $? -eq 2 ] && grep -q 'is a directory' '$work/dir.err' && [ -d '$work/adir' ]"
echo precious >"$work/precious"
ln -s "$work/precious" "$work/link.csv"
"$bin" equilibria "$scene" --format csv -o "$work/link.csv" 2>"$work/link.err"
check "-o SYMLINK refused with exit 2, its target untouched" \
  "[ $? -eq 2 ] && [ -L '$work/link.csv' ] && [ \"\$(cat '$work/precious')\" = precious ]"
echo x >"$work/notdir"
"$bin" sweep "$scene" --param omega --from 100 --to 200 --steps 2 --no-chart -o "$work/notdir" 2>"$work/nd.err"
check "-o DIR that is a file refused with exit 2" "[ $? -eq 2 ] && [ \"\$(cat '$work/notdir')\" = x ]"
# -o at a dangling symbolic link (or below one): exit 2 naming the link, nothing created.
ln -s "$work/nowhere/deeper" "$work/dangling"
"$bin" sweep "$scene" --param omega --from 100 --to 200 --steps 2 --no-chart -o "$work/dangling" 2>"$work/dl.err"
check "-o DANGLING_SYMLINK refused with exit 2 naming the link" \
  "[ $? -eq 2 ] && grep -q 'symbolic link to a path that does not exist' '$work/dl.err' && [ ! -e '$work/nowhere' ]"
"$bin" sweep "$scene" --param omega --from 100 --to 200 --steps 2 --no-chart -o "$work/dangling/sub" 2>"$work/dl2.err"
check "-o DIR below a dangling symbolic link refused with exit 2" \
  "[ $? -eq 2 ] && grep -q 'dangling is a symbolic link' '$work/dl2.err' && [ ! -e '$work/nowhere' ]"
# A planted link with the old predictable temporary name is not followed.
mkdir -p "$work/plant"
for pid in $(seq $$ $(($$ + 400))); do ln -s "$work/precious" "$work/plant/.eq.csv.tmp-$pid"; done
"$bin" equilibria "$scene" --format csv -o "$work/plant/eq.csv" 2>/dev/null
check "planted temporary links are not followed" "[ $? -eq 0 ] && [ \"\$(cat '$work/precious')\" = precious ] && [ -s '$work/plant/eq.csv' ]"

# --- 1. commit as a group, rolled back on failure -----------------------------------------
"$bin" continue "$scene" --set omega=200 --param omega --to 400 --no-chart -o "$work/grp" 2>/dev/null
cp "$work/grp/branch_omega.csv" "$work/old_branch"; cp "$work/grp/special_omega.csv" "$work/old_special"
ls -A "$work/grp" > "$work/grp.list"
ABU_TEST_FAIL_RENAME=2 "$bin" continue "$scene" --set omega=210 --param omega --to 400 --no-chart -o "$work/grp" 2>"$work/grp.err"
check "a rename failing halfway: exit 1, message" "[ $? -eq 1 ] && grep -q 'previous files are restored' '$work/grp.err'"
check "... and both old files are back, unchanged" \
  "cmp -s '$work/old_branch' '$work/grp/branch_omega.csv' && cmp -s '$work/old_special' '$work/grp/special_omega.csv'"
check "... and no temporary is left" "no_temporaries '$work/grp' && ls -A '$work/grp' | cmp -s - '$work/grp.list'"

# --- 1. standard output checked -----------------------------------------------------------
if [ -w /dev/full ]; then
  "$bin" equilibria "$scene" --format csv >/dev/full 2>"$work/full.err"
  check "stdout write error: exit 1 with the cause" "[ $? -eq 1 ] && grep -q 'standard output' '$work/full.err'"
fi

# --- 1. results never lost to a chart ------------------------------------------------------
ABU_GNUPLOT=/nonexistent/gnuplot "$bin" sweep "$scene" --param omega --from 100 --to 1000 --steps 10 -o "$work/nog" 2>"$work/nog.err"
check "gnuplot missing: exit 4, the CSV written, the cause said" \
  "[ $? -eq 4 ] && [ -s '$work/nog/sweep_omega.csv' ] && [ ! -e '$work/nog/sweep_omega.png' ] && grep -q 'gnuplot not found' '$work/nog.err'"
check "... and no temporary is left" "no_temporaries '$work/nog'"
mkdir -p "$work/badplots"; echo 'this is not gnuplot;' >"$work/badplots/sweep.gp"
ABU_PLOTS_DIR="$work/badplots" "$bin" sweep "$scene" --param omega --from 100 --to 1000 --steps 10 -o "$work/badg" 2>"$work/badg.err"
check "gnuplot failing: exit 4, the CSV written, gnuplot's message quoted" \
  "[ $? -eq 4 ] && [ -s '$work/badg/sweep_omega.csv' ] && grep -q \"chart 'sweep' not drawn: gnuplot exited\" '$work/badg.err'"
for cmd in "equilibria $scene" "sweep $scene --param omega --from 100 --to 200 --steps 2 -o $work/nc1" \
  "continue $scene --set omega=200 --param omega --to 220 -o $work/nc2" \
  "map $scene --x omega:100:200:3 --y mu:0.001:0.01:3 --quiet --no-boundaries -o $work/nc3" \
  "simulate $scene --balls 0,1 --t-end 0.01 --quiet -o $work/nc4"; do
  ABU_GNUPLOT=/nonexistent/gnuplot "$bin" $cmd --no-chart >/dev/null 2>&1
  check "--no-chart accepted by ${cmd%% *} (exit 0 without gnuplot)" "[ $? -eq 0 ]"
done
# A documented degenerate case (no fold or Hopf point in a two-parameter run): the CSVs and
# an empty chart with a note, exit 0.
"$bin" continue "$scene" --set omega=900 --param omega --to 1000 --param2 mu --to2 0.01 -o "$work/deg" 2>"$work/deg.err"
check "no boundary curve: exit 0, CSVs and a chart" \
  "[ $? -eq 0 ] && [ -s '$work/deg/boundary_omega_mu.csv' ] && [ -s '$work/deg/branch_omega.csv' ] && [ -s '$work/deg/boundary_omega_mu.png' ]"

"$bin" sweep "$scene" --set U=0 --param omega --from 100 --to 1000 --steps 20 -o "$work/u0" 2>"$work/u0.err"
# (plots/sweep.gp draws this case itself, with the note "no state with q != 0"; were it to
# fail, the chart would be drawn empty with the failure's note: either way a chart, exit 0.)
check "U = 0 sweep (nothing on the log axis): exit 0, CSV and a chart" \
  "[ $? -eq 0 ] && [ -s '$work/u0/sweep_omega.csv' ] && [ -s '$work/u0/sweep_omega.png' ]"

# --- 2. signals ----------------------------------------------------------------------------
# $1: signal; the rest: the command. Runs it, signals it after 0.7 s, prints "CODE SECONDS".
stop_after() {
  local sig=$1; shift
  "$@" >/dev/null 2>"$work/stop.err" &
  local pid=$!
  sleep 0.7
  local t0=$(date +%s.%N)
  kill -"$sig" "$pid" 2>/dev/null
  wait "$pid"
  local code=$?
  echo "$code $(echo "$(date +%s.%N) - $t0" | bc)"
}
read code secs < <(stop_after TERM "$bin" sweep "$scene" --param omega --from 100 --to 2000 --steps 200000 --no-chart -o "$work/sig1")
check "SIGTERM stops sweep: exit 143 within 3 s ($code, $secs s)" "[ $code -eq 143 ] && [ \$(echo '$secs < 3' | bc) -eq 1 ]"
check "... no file, no temporary" "[ ! -e '$work/sig1/sweep_omega.csv' ] && no_temporaries '$work/sig1'"
read code secs < <(stop_after INT "$bin" continue "$scene" --set omega=50 --param omega --to 2000 --ds 1e-5 --ds-min 1e-9 --ds-max 1e-5 --max-steps 50000 --no-chart -o "$work/sig2")
check "SIGINT stops continue: exit 130 within 3 s ($code, $secs s)" "[ $code -eq 130 ] && [ \$(echo '$secs < 3' | bc) -eq 1 ]"
# ... and it is the continuation that stops (the stop request seen at a branch point and
# unwound), not the signal thread's fallback after 1 s.
"$bin" continue "$scene" --set omega=50 --param omega --to 2000 --ds 1e-5 --ds-min 1e-9 --ds-max 1e-5 --max-steps 50000 \
  --no-chart -o "$work/sig2b" 2>"$work/sig2b.err" &
pid=$!
sleep 0.7
kill -INT $pid
wait $pid
check "... the continuation itself sees the stop request ($(head -c 120 "$work/sig2b.err"))" \
  "grep -q 'interrupted by SIGINT during continuation' '$work/sig2b.err'"
read code secs < <(stop_after TERM "$bin" map "$scene" --x omega:50:2000:400 --y mu:1e-4:0.1:400:log --method full --threads 2 --no-chart --no-boundaries --quiet -o "$work/sig3")
check "SIGTERM stops map: exit 143 within 3 s ($code, $secs s)" "[ $code -eq 143 ] && [ \$(echo '$secs < 3' | bc) -eq 1 ]"
check "... says the tiles are kept" "grep -q 'tiles are kept' '$work/stop.err' && grep -q -- '--resume' '$work/stop.err'"
check "... no temporary in the tile directory" "no_temporaries '$work/sig3'"

# --- 4. maps: tiles streamed (memory per worker independent of the y axis) ----------------
# Tiles of ~25 MB, written through 1 MB buffers (many spills per tile): the same bytes for
# 1 and 2 threads, every cell present once, and the estimate printed with --progress.
for t in 1 2; do
  "$bin" map "$scene" --set kappa=1e6 --x omega:50:2000:12 --y U:1e-7:1e-6:6000 --long --no-chart --no-boundaries \
    --progress --threads $t -o "$work/stream$t" 2>"$work/stream$t.err"
done
check "streamed tiles: 1 and 2 threads give the same bytes" \
  "cmp -s <(grep -v '^# command' '$work/stream1/map_omega_U.csv') <(grep -v '^# command' '$work/stream2/map_omega_U.csv') && cmp -s <(grep -v '^# command' '$work/stream1/summary_omega_U.csv') <(grep -v '^# command' '$work/stream2/summary_omega_U.csv')"
check "... every cell once, in order (72000 summary rows)" \
  "[ \$(grep -v '^#' '$work/stream1/summary_omega_U.csv' | tail -n +2 | cut -d, -f1,2 | uniq | wc -l) -eq 72000 ]"
check "... the disk and memory estimate printed first ($(head -c 150 "$work/stream2.err"))" \
  "grep -q '^map: 72000 cells, about .* GB of disk .* of memory (2 workers x ' '$work/stream2.err'"
check "... no temporary left" "no_temporaries '$work/stream1' && no_temporaries '$work/stream2'"

# --- 3. numerical range: never a hang -----------------------------------------------------
for set in omega=1e155 U=1e300 c=1e300 omega=1e-200 U=1e-22 k=1e300 kappa=1e20 kappa=1e200 M_r=1e-300 k=1e-300 m=1e-40 l=1e-30; do
  timeout -s KILL 20 "$bin" equilibria "$scene" --format csv --set "$set" >"$work/range.csv" 2>"$work/range.err"
  code=$?
  check "--set $set: refused (2) or reported (3) or right (0), never a hang (exit $code)" \
    "[ $code -eq 0 ] || [ $code -eq 2 ] || [ $code -eq 3 ]"
  if [ $code -eq 0 ]; then
    check "--set $set: no DBL_MAX printed" "! grep -v '^#' '$work/range.csv' | grep -q '1.7976931348623157e+308'"
    check "--set $set: every row an equilibrium (residual < 1e-6)" \
      "grep -v '^#' '$work/range.csv' | tail -n +2 | awk -F, '{if (\$8 + 0 > 1e-6 || \$8 == \"\") exit 1}'"
  fi
done

# kappa beyond the verified range (kappa omega_n <= 1e16) is refused, also as a sweep's end.
"$bin" sweep "$scene" --param kappa --from 1e3 --to 1e200 --steps 3 --no-chart -o "$work/kap" 2>"$work/kap.err"
check "sweep reaching kappa = 1e200 refused with exit 2 naming kappa" "[ $? -eq 2 ] && grep -q \"key 'kappa'\" '$work/kap.err' && [ ! -e '$work/kap' ]"
# SIGTERM in the two commands not covered above (equilibria on a 12-ball ring, simulate).
read code secs < <(stop_after TERM "$bin" simulate "$scene" --balls 0,1 --t-end 1000 --quiet --no-chart -o "$work/sig4")
check "SIGTERM stops simulate: exit 143 within 3 s ($code, $secs s)" "[ $code -eq 143 ] && [ \$(echo '$secs < 3' | bc) -eq 1 ]"
check "... no temporary" "no_temporaries '$work/sig4'"

# A failed eigenvalue refinement (kappa = 1e12: spectra over 26 decades) classifies by the
# error it has: the balanced states, stable by a 40-digit computation (abscissa -3.6e-15),
# are stable or marginal, never unstable.
"$bin" equilibria "$scene" --set kappa=1e12 --set omega=400 --set mu=0.1 --format json 2>/dev/null >"$work/k.json"
check "kappa=1e12: no balanced state called unstable after a failed refinement" \
  "/usr/bin/python3 -c \"import json,sys; d=json.load(open('$work/k.json')); sys.exit(any(e['family']=='balanced' and e['stability']=='unstable' for e in d['equilibria']))\""

# kappa = 1e12: the spectrum spans 30 decades and a pair at -8.3 +- 99.8i came
# out of both QRs as two real values near +-0.8 that Newton could not leave ("marginal,
# abscissa 0.80"). 40-digit reference (tests/reference/mp_reference.py, this scene with
# kappa=1e12 omega=150 mu=0.08208914159638263): together 1 is stable, abscissa
# -2.9621114926954522e-15, and every eigenvalue refines (spectrum_converged). Tolerance 1e-9
# relative: the refined creep modes agree with the reference to ~1e-15.
"$bin" equilibria "$scene" --set kappa=1e12 --set omega=150 --set mu=0.08208914159638263 --format json 2>/dev/null >"$work/k150.json"
check "kappa=1e12, omega=150: together 1 stable at the 40-digit abscissa, every eigenvalue refined" \
  "/usr/bin/python3 -c \"import json,sys; e=[e for e in json.load(open('$work/k150.json'))['equilibria'] if e['family']=='together' and e['member']==1][0]; sys.exit(not (e['stability']=='stable' and e['spectrum_converged'] and abs(e['spectral_abscissa']/-2.9621114926954522e-15-1)<1e-9))\""
# ... and over a map (1440 cells, 8569 rows: 135 rows disagreed before), --method full and
# fast give the same stable flag and unstable count on every row.
for m in fast full; do
  "$bin" map "$scene" --set kappa=1e12 --x omega:50:2000:40 --y mu:1e-4:0.1:36:log --method $m --long --no-chart \
    --no-boundaries --quiet --threads 2 -o "$work/k12_$m" 2>/dev/null
done
disagree=$(paste -d, <(grep -v '^#' "$work/k12_fast/map_omega_mu.csv" | cut -d, -f7,8) \
  <(grep -v '^#' "$work/k12_full/map_omega_mu.csv" | cut -d, -f7,8) | awk -F, '$1 != $3 || $2 != $4' | wc -l)
rows=$(grep -vc '^#' "$work/k12_full/map_omega_mu.csv")
check "kappa=1e12 map: fast and full agree on every row ($disagree of $rows differ)" "[ $rows -gt 8000 ] && [ $disagree -eq 0 ]"

# Inputs without end: a scene or a speed profile read from /dev/zero was read without limit
# (memory growing until killed); now refused at 16 MiB / 256 MiB, exit 2, nothing written.
if [ -r /dev/zero ]; then
  timeout 20 "$bin" equilibria /dev/zero --format csv -o "$work/z.csv" 2>"$work/z.err"
  check "a scene from /dev/zero: exit 2 naming the limit, nothing written" \
    "[ $? -eq 2 ] && grep -q 'larger than 16 MiB' '$work/z.err' && [ ! -e '$work/z.csv' ]"
  timeout 20 "$bin" simulate "$scene" --balls 1,2 --speed-profile /dev/zero --t-end 0.1 --no-chart -o "$work/zp" \
    2>"$work/zp.err"
  check "a speed profile from /dev/zero: exit 2 naming the limit, nothing written" \
    "[ $? -eq 2 ] && grep -q 'larger than 256 MiB' '$work/zp.err' && [ ! -e '$work/zp' ]"
fi

# A sweep's memory, estimated before the work (scan.hpp sweep_memory_estimate: 37 kB a value,
# 28 kB measured): --steps 1000000 (allowed) held ~28 GB until killed; now refused up front
# where it cannot fit. The peak of a 5,000-value sweep stays below its estimate.
available=$(awk '/^MemAvailable:/ {print $2 * 1024}' /proc/meminfo)
if /usr/bin/python3 -c "import sys; sys.exit(0 if 37e3 * 1000001 + 20e6 > 0.8 * $available else 1)"; then
  "$bin" sweep "$scene" --param omega --from 100 --to 2000 --steps 1000000 --no-chart -o "$work/swbig" 2>"$work/swbig.err"
  check "sweep --steps 1000000 beyond the memory available: exit 2 naming the figures, nothing written" \
    "[ $? -eq 2 ] && grep -q 'the sweep would hold about' '$work/swbig.err' && [ ! -e '$work/swbig' ]"
fi
if [ -z "${ASAN_OPTIONS:-}" ]; then  # under the sanitizers the shadow memory is not the program's
  /usr/bin/time -f %M -o "$work/sw.kb" "$bin" sweep "$scene" --param omega --from 100 --to 2000 --steps 5000 \
    --no-chart -o "$work/sw5000" 2>/dev/null
  check "a sweep of 5001 values: peak $(($(tail -1 "$work/sw.kb") / 1000)) MB below its estimate 205 MB" \
    "[ $(tail -1 "$work/sw.kb") -lt 200000 ]"
fi

# --- 5. exit codes, escapes, integers, overlaps, --set order -------------------------------
"$bin" continue "$scene" --set omega=200 --param omega --to 400 --max-steps 2 --no-chart -o "$work/mx" 2>/dev/null
check "a branch ending in MX exits 3" "[ $? -eq 3 ] && grep -q ',MX,' '$work/mx/special_omega.csv'"
nl=$'bad\nname'
"$bin" equilibria "$work/$nl.toml" 2>"$work/ctl.err"
check "a newline in a path is escaped in the message (one line)" "[ $? -eq 2 ] && [ \$(wc -l <'$work/ctl.err') -eq 1 ] && grep -q 'bad\\\\nname' '$work/ctl.err'"
cp "$scene" "$work/$nl.toml"
"$bin" equilibria "$work/$nl.toml" --format csv -o "$work/ctl.csv" 2>/dev/null
check "... and in the CSV comment lines" "[ -z \"\$(grep -v '^#' '$work/ctl.csv' | grep -n 'name')\" ] && grep -q '^# scene: .*bad\\\\nname' '$work/ctl.csv'"
"$bin" sweep "$scene" --param omega --from 100 --to 200 --steps 010 --no-chart -o "$work/dec" 2>/dev/null
check "--steps 010 is ten steps (decimal)" "[ \$(grep -v '^#' '$work/dec/sweep_omega.csv' | tail -n +2 | cut -d, -f1 | sort -u | wc -l) -eq 11 ]"
"$bin" map "$scene" --x m:0.001:0.01:3 --y m1:0.001:0.01:3 --quiet -o "$work/ovl" 2>"$work/ovl.err"
check "overlapping map axes (m, m1) refused with exit 2" "[ $? -eq 2 ] && [ ! -e '$work/ovl' ]"
"$bin" continue "$scene" --param m --to 0.02 --param2 m2 --to2 0.02 --no-chart -o "$work/ovl2" 2>/dev/null
check "overlapping continuation parameters (m, m2) refused with exit 2" "[ $? -eq 2 ]"
"$bin" equilibria "$scene" --format csv --set r=0.03 --set l=0.2 >"$work/o1.csv" 2>/dev/null; c1=$?
"$bin" equilibria "$scene" --format csv --set l=0.2 --set r=0.03 >"$work/o2.csv" 2>/dev/null; c2=$?
check "--set order does not decide acceptance ($c1, $c2)" "[ $c1 -eq $c2 ] && [ $c1 -eq 0 ]"
"$bin" equilibria "$scene" --set r=0.3 --set l=0.2 >/dev/null 2>&1
check "... and a final scene breaking a rule is still refused" "[ $? -eq 2 ]"

finish
