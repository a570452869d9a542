#!/usr/bin/env bash
# The command-line contract of `stability-scan basin` (model.md §15.5): the CSVs
# and the chart, fractions summing to one, the same bytes on 1 and 2 threads, an interrupted
# run resumed equals a fresh run, the refusal to overwrite an interrupted run, the scene's
# [simulate] run-up equals --ramp, n = 3 balls (ball 3 sampled by Sobol points, or fixed), bad
# input (exit 2, nothing written).
#   check_basin.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"

# A viscous two-ball scene (not one of data/): cheap, non-stiff cells.
scene=$work/viscous.toml
sed -e 's/law = "coulomb".*/law = "viscous"/' -e 's/^mu = 0.002.*/d = 2.0e-3/' -e '/^kappa/d' \
    -e 's/omega = 900.0.*/omega = 400.0/' -e 's/unbalance = 6.0e-7/unbalance = 5.0e-7/' \
    "$src/data/scenes/default.toml" >"$scene"
args=(--grid 6 --t-end 4)

"$bin" basin "$scene" "${args[@]}" --threads 1 -o "$work/t1" 2>"$work/t1.err"
check "basin exits 0" "[ $? -eq 0 ]"
header=$(grep -v '^#' "$work/t1/basin.csv" | head -1)
check "long csv header" "[ '$header' = 'i,j,beta1_0,beta2_0,attractor,member,by_settle_test,t_settle,t_end,q_abs_end,max_q_abs,beta1_end,beta2_end,steps,rejected' ]"
check "one row per cell (36)" "[ \$(grep -v '^#' '$work/t1/basin.csv' | tail -n +2 | wc -l) -eq 36 ]"
check "no nan or inf" "! grep -v '^#' '$work/t1/basin.csv' | grep -qiE 'nan|inf'"
check "fractions sum to 1 and match the JSON" "/usr/bin/python3 -c \"
import csv, json, sys
rows = [r for r in csv.DictReader(l for l in open('$work/t1/basin_fractions.csv') if not l.startswith('#'))]
js = json.load(open('$work/t1/basin.json'))
s = sum(float(r['fraction']) for r in rows)
ok = abs(s - 1) < 1e-5 and sum(int(r['cells']) for r in rows) == 36 and js['cells'] == 36
ok = ok and all(abs(js['fractions'][r['attractor']] - float(r['fraction'])) < 1e-12 for r in rows)
sys.exit(0 if ok else 1)\""
check "the map is drawn" "[ -s '$work/t1/basin.png' ]"
check "the tile directory is removed after assembly" "[ ! -e '$work/t1/.basin.tiles' ]"

"$bin" basin "$scene" "${args[@]}" --threads 2 --no-chart --quiet -o "$work/t2" 2>/dev/null
check "2 threads give the same bytes as 1" "cmp -s '$work/t1/basin.csv' '$work/t2/basin.csv' && cmp -s '$work/t1/basin_fractions.csv' '$work/t2/basin_fractions.csv' && cmp -s '$work/t1/basin.json' '$work/t2/basin.json'"

# --- interrupted, then resumed: the same bytes as a fresh run -------------------------------
big=(--grid 10x4 --t-end 20)
"$bin" basin "$scene" "${big[@]}" --threads 1 --no-chart --quiet -o "$work/fresh" 2>/dev/null
"$bin" basin "$scene" "${big[@]}" --threads 1 --no-chart --quiet -o "$work/int" 2>/dev/null &
pid=$!
wait_for_tiles "$work/int/.basin.tiles" 2
kill -INT $pid
wait $pid
code=$?
check "SIGINT exits 130" "[ $code -eq 130 ]"
kept=$(tile_count "$work/int/.basin.tiles")
check "SIGINT keeps the finished tiles ($kept of 10)" "[ $kept -ge 2 ] && [ $kept -lt 10 ]"
check "nothing assembled after SIGINT" "[ ! -e '$work/int/basin.csv' ]"
"$bin" basin "$scene" "${big[@]}" --threads 2 --no-chart --quiet -o "$work/int" 2>"$work/refuse.err"
check "a second run without --resume is refused (exit 2)" "[ $? -eq 2 ] && grep -q -- '--resume' '$work/refuse.err'"
"$bin" basin "$scene" "${big[@]}" --threads 2 --no-chart --quiet --resume -o "$work/int" 2>/dev/null
check "resume exits 0" "[ $? -eq 0 ]"
check "resumed run equals the fresh run" "cmp -s '$work/fresh/basin.csv' '$work/int/basin.csv'"
"$bin" basin "$scene" --grid 10x4 --t-end 21 --threads 1 --no-chart --quiet -o "$work/other" 2>/dev/null &
pid=$!
wait_for_tiles "$work/other/.basin.tiles" 1
kill -INT $pid
wait $pid
"$bin" basin "$scene" "${big[@]}" --no-chart --quiet --resume -o "$work/other" 2>"$work/mismatch.err"
check "resuming another job's tiles is refused (exit 2)" "[ $? -eq 2 ] && grep -q 'different' '$work/mismatch.err'"
"$bin" basin "$scene" "${big[@]}" --no-chart --quiet --fresh -o "$work/other" 2>/dev/null
check "--fresh starts over and equals the fresh run" "cmp -s '$work/fresh/basin.csv' '$work/other/basin.csv'"

# --- a run-up: the scene's [simulate] ramp equals --ramp ------------------------------------
cp "$scene" "$work/ramp.toml"
printf '\n[simulate]\nramp = { omega0 = 150, omega1 = 400, alpha = 500 }\nt_end = 4\n' >>"$work/ramp.toml"
"$bin" basin "$work/ramp.toml" --grid 4 --no-chart --quiet -o "$work/r1" 2>/dev/null
check "run-up from the scene exits 0" "[ $? -eq 0 ]"
"$bin" basin "$scene" --grid 4 --ramp 150:400:500 --t-end 4 --no-chart --quiet -o "$work/r2" 2>/dev/null
check "scene run-up keys give the rows of --ramp" "cmp -s <(grep -v '^#' '$work/r1/basin.csv') <(grep -v '^#' '$work/r2/basin.csv')"
check "the run-up is named in the header" "grep -q 'ramp 150 -> 400' '$work/r1/basin.csv'"

# --- three balls ------------------------------------------------------------------------------
sed 's/^count = 11/count = 3/' "$src/data/scenes/ring11.toml" >"$work/ring3.toml"
"$bin" basin "$work/ring3.toml" --grid 3 --t-end 0.05 --no-chart --quiet -o "$work/n3" 2>"$work/n3.err"
check "three balls: exits 0, 9 cells, three end angles" \
  "[ $? -eq 0 ] && [ \$(grep -v '^#' '$work/n3/basin.csv' | tail -n +2 | wc -l) -eq 9 ] && grep -v '^#' '$work/n3/basin.csv' | head -1 | grep -q 'beta3_end'"
# Ball 3 sampled, not fixed: its start angle in cell (i, j) is 2 pi times point k = 3 i + j + 1
# of the Sobol sequence in GSL's Gray-code order (Antonov-Saleev), whose first coordinate is
# the base-2 van der Corput radical inverse of gray(k) = k xor (k >> 1) (the bits mirrored
# about the binary point), computed here independently of GSL; to the 10 significant digits
# the CSV prints.
check "three balls: ball 3 starts at the cell's Sobol point (van der Corput in one dimension)" "/usr/bin/python3 -c \"
import csv, math
rows = list(csv.DictReader(l for l in open('$work/n3/basin.csv') if not l.startswith('#')))
def vdc(k):
    x, f = 0.0, 0.5
    while k:
        x += f * (k & 1); k >>= 1; f /= 2
    return x
assert len(rows) == 9
for r in rows:
    k = 3 * int(r['i']) + int(r['j']) + 1
    k ^= k >> 1
    assert abs(float(r['beta3_0']) - 2 * math.pi * vdc(k)) <= 1e-9, (r['i'], r['j'], r['beta3_0'])
assert len({r['beta3_0'] for r in rows}) == 9  # every cell its own angle
# The fractions count attractors, whatever columns the ball count adds.
labels = [l.split(',')[0] for l in open('$work/n3/basin_fractions.csv') if not l.startswith('#')][1:]
assert labels and all(a.split(':')[0] in ('balanced', 'aligned', 'periodic', 'stuck', 'stuck_outside', 'slipping', 'not_settled') for a in labels), labels
\" && grep -q '^# others: balls 3..3' '$work/n3/basin.csv'"
"$bin" basin "$work/ring3.toml" --grid 3 --t-end 0.05 --no-chart --quiet --others symmetric -o "$work/n3s" 2>/dev/null
check "three balls, --others symmetric: ball 3 at 4 pi / 3 in every cell" \
  "grep -q '^# fixed: balls 3..3 start at 4.18879' '$work/n3s/basin.csv' && [ \$(grep -v '^#' '$work/n3s/basin.csv' | tail -n +2 | awk -F, '{print \$NF}' | sort -u) = 4.188790205 ]"

# --- an anisotropic support (model.md §20): the composed field; the balanced states judged by
# their Floquet multipliers are the settle test's attractors (the fixed-frame reference of every
# cell: reference/aniso_basin, label slow)
aniso=$src/tests/scenes/anisotropic/ref_viscous.toml
"$bin" basin "$aniso" --grid 3 --t-end 8 --threads 2 --no-chart -o "$work/an" 2>"$work/an.err"
check "anisotropic support: basin exits 0" "[ $? -eq 0 ]"
check "anisotropic support: its matrices in the header (and so in the resume manifest)" \
  "grep -q '^# anisotropic support (model.md §10, §20): fixed frame K_f = \\[\\[12000, -800\\]' '$work/an/basin.csv'"
check "anisotropic support: the attractors are the balanced states equilibria calls stable" \
  "grep -q '^# attractors of the settle test at omega = 1100 rad/s: balanced 1, balanced 2$' '$work/an/basin.csv' && [ \$('$bin' equilibria '$aniso' | grep -c '^balanced [12]: .*; stable') -eq 2 ]"
check "anisotropic support: no nan or inf" "! grep -v '^#' '$work/an/basin.csv' | grep -qiE 'nan|inf'"

# --- bad input: exit 2, nothing written -------------------------------------------------------
bad() {  # name, then the arguments; -o inside an empty directory
  local name=$1
  shift
  local dir=$work/bad.$RANDOM
  mkdir -p "$dir"
  (cd "$dir" && "$bin" basin "$@" -o out >"$work/out" 2>"$work/err")
  local code=$?
  if [ $code -ne 2 ]; then fail "$name: exit $code, expected 2 ($(head -c 200 "$work/err"))"; return; fi
  if [ -n "$(ls -A "$dir")" ]; then fail "$name: wrote $(ls -A "$dir")"; return; fi
  pass "$name ($(head -c 150 "$work/err" | tr '\n' ' '))"
}
bad "zero t-end"            "$scene" --t-end 0
bad "grid of one cell"      "$scene" --grid 1
bad "grid not a number"     "$scene" --grid 4y4
bad "ramp through zero"     "$scene" --ramp 100:-10:50
bad "fixed balls on two"    "$scene" --fixed 1
bad "fixed wrong count"     "$work/ring3.toml" --fixed 1,2
bad "others unknown"        "$work/ring3.toml" --others random
bad "settle radius 0"       "$scene" --settle-radius 0
bad "scene t_end <= 0"      "$src/tests/scenes/invalid/64-simulate-zero-t-end.toml"
bad "coulomb-set balls on an unround race (not integrated yet)" "$src/tests/scenes/composed/oval_coulomb_set.toml"
finish
