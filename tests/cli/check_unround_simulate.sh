#!/usr/bin/env bash
# `simulate` on an unround race (docs/model.md §11.12, §15.6-§15.7):
#  1. an oval race (default rotor, viscous balls, eps_2 = 1e-6): the run from the round
#     race's balanced angles ends in `equilibrium`, and its end state equals the state
#     `equilibria --format json` prints for that member to the settle tolerance (1e-3 in
#     the scaled distance of §15.2: |q - q*| / L, wrapped angles) -- and in fact to 1e-6;
#  2. the eccentric race (order 1) ends at |q| = d (the exact (11.4.4)) to 1e-6 relative;
#  3. a run-up on the oval race runs and ends in `equilibrium` too;
#  4. --from-equilibrium on an unround race is refused (exit 2), nothing written;
#  5. a zero-amplitude race gives the round scene's simulation byte for byte.
#   check_unround_simulate.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"

viscous() { sed -e 's/law = "coulomb".*/law = "viscous"/' -e 's/^mu = 0.002.*/d = 1.0e-3/' -e '/^kappa/d' "$src/data/scenes/default.toml"; }
{ viscous; printf '\n[race]\nunroundness = [{ order = 2, amplitude = 1e-6, phase = 0.0 }]\n'; } >"$work/oval.toml"
{ viscous; printf '\n[race]\nunroundness = [{ order = 1, amplitude = 2e-4, phase = 0.7 }]\n'; } >"$work/ecc.toml"
{ viscous; printf '\n[race]\nunroundness = [{ order = 2, amplitude = 0.0, phase = 0.0 }]\n'; } >"$work/zero.toml"
viscous >"$work/round.toml"
start=(--balls 2.1003,4.1829 --t-end 40 --every 0.05 --rtol 1e-10 --no-chart --quiet)

"$bin" simulate "$work/oval.toml" "${start[@]}" --summary "$work/oval.json" -o "$work/oval" 2>"$work/oval.err"
check "oval: simulate exits 0" "[ $? -eq 0 ]"
"$bin" equilibria "$work/oval.toml" --format json >"$work/eq.json" 2>/dev/null
check "oval: equilibria exits 0" "[ $? -eq 0 ]"
cmp_out=$(/usr/bin/python3 - "$work/oval.json" "$work/eq.json" <<'PY'
import json, math, sys
s = json.load(open(sys.argv[1])); e = json.load(open(sys.argv[2]))
if s["outcome"] != "equilibrium":
    print(f"outcome {s['outcome']}"); sys.exit(1)
k = s["unround_equilibrium"]["member"]
eq = e["equilibria"][k - 1]
x = s["state_end"]
M = 0.12 + 2 * 3.3e-5
L = (6e-7 + 2 * 3.3e-5 * 0.018) / M          # the displacement scale of model.hpp
d = max(abs(x[0] - eq["q1"]), abs(x[1] - eq["q2"])) / L
for i in range(2):
    d = max(d, abs(math.remainder(x[2 + i] - eq["beta"][i], 2 * math.pi)))
print(f"member {k} ({eq['stability']}), scaled distance {d:.3g}, |q| {math.hypot(x[0], x[1]):.6g} vs {eq['q_abs']:.6g}")
sys.exit(0 if d <= 1e-6 and eq["stability"] == "stable" else 1)
PY
)
check "oval: end state = the equilibria state ($cmp_out)" "[ $? -eq 0 ]"
check "oval: the CSV has no balanced reference angles" "! grep -q '^# balanced reference angles' '$work/oval/simulation.csv'"

"$bin" simulate "$work/ecc.toml" "${start[@]}" --summary "$work/ecc.json" -o "$work/ecc" 2>/dev/null
qd=$(/usr/bin/python3 -c 'import json,math,sys; s=json.load(open(sys.argv[1])); x=s["state_end"]; d=0.018*2e-4; q=math.hypot(x[0],x[1]); print(s["outcome"], q, abs(q-d)/d)' "$work/ecc.json")
check "eccentric race: |q| = d ($qd)" "/usr/bin/python3 -c 'import sys; a=sys.argv[1:]; sys.exit(0 if a[0]==\"equilibrium\" and float(a[2]) <= 1e-6 else 1)' $qd"

"$bin" simulate "$work/oval.toml" --balls 2.1003,4.1829 --ramp 700:900:400 --t-end 40 --every 0.05 --no-chart --quiet \
  --summary "$work/ramp.json" -o "$work/ramp" 2>/dev/null
check "oval run-up exits 0" "[ $? -eq 0 ]"
check "oval run-up ends in equilibrium" "grep -q '\"outcome\": \"equilibrium\"' '$work/ramp.json'"

"$bin" simulate "$work/oval.toml" --from-equilibrium balanced -o "$work/fe" 2>"$work/fe.err"
check "--from-equilibrium on an unround race: exit 2" "[ $? -eq 2 ]"
check "--from-equilibrium: nothing written" "[ ! -e '$work/fe' ]"

short=(--balls 2.1,4.2 --t-end 0.5 --no-chart --quiet)
(cd "$work" && "$bin" simulate zero.toml "${short[@]}" -o z >/dev/null 2>&1 && "$bin" simulate round.toml "${short[@]}" -o r >/dev/null 2>&1)
sed -i '/^# command:\|^# scene:/d' "$work/z/simulation.csv" "$work/r/simulation.csv"
check "zero-amplitude race = round scene (simulation.csv)" "cmp -s '$work/z/simulation.csv' '$work/r/simulation.csv'"
finish
