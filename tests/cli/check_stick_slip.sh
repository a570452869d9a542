#!/bin/bash
# coulomb-set stick-slip through the command line (model.md §14.5-§14.8), on
# tests/scenes/stickslip/runup.toml (not in data/; its stick set at 800 rad/s is 9.5 % of
# the torus): simulate writes the stick columns and the stick_slip summary with the end point
# inside the set; basin ends every cell with every ball stuck inside the set (0 outside),
# the same bytes on 1 and 2 threads.
set -u
exe=$1
src=$2
scene=$src/tests/scenes/stickslip/runup.toml
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$exe" simulate "$scene" --t-end 2 --balls 1,2.5 --no-chart --quiet -o "$d/sim" --summary "$d/sim.json" || fail "simulate exit $?"
head=$(grep -v '^#' "$d/sim/simulation.csv" | head -1)
[[ $head == *",beta_rel2,stick1,stick2" ]] || fail "stick columns not appended: $head"
grep -q '"in_stick_set": true' "$d/sim.json" || fail "end point not reported inside the stick set"
grep -q '"all_stuck": true' "$d/sim.json" || fail "not every ball stuck at the end"
# the last row: both balls stuck
last=$(tail -1 "$d/sim/simulation.csv")
[[ $last == *",1,1" ]] || fail "last row not stuck: $last"

for t in 1 2; do
  "$exe" basin "$scene" --t-end 3 --grid 5 --threads $t --no-chart --quiet -o "$d/b$t" || fail "basin exit $? on $t threads"
done
cmp -s "$d/b1/basin.csv" "$d/b2/basin.csv" || fail "basin bytes depend on the thread count"
grep -q '"outside_stick_set": 0' "$d/b1/basin.json" || fail "end points outside the stick set"
grep -q '"stuck_cells": 25' "$d/b1/basin.json" || fail "not every cell stuck: $(grep stick_slip "$d/b1/basin.json")"
# every row's in_stick_set column is 1
awk -F, '!/^#/ && NR > 1 && $1 != "i" && $NF != 1 { bad = 1 } END { exit bad }' "$d/b1/basin.csv" || fail "a row outside the set"
echo PASS
