#!/usr/bin/env bash
# The coulomb cycles of the default scene (docs/model.md §17.11-§17.15): `continue --cycles`
# from its Hopf point at omega_H = 249.93374 rad/s on the stiff (Radau) route, a few orbits
# (the branch cut short on purpose: exit 3, the orbits written); the CSV: 8 multipliers, the
# six fast ones below 1e-308 with their ln|mu|, the trivial one within 1e-8 of 1, unstable
# (subcritical Hopf point); with `reference`, the last orbit against the independent scipy
# Radau single shooting (period, the two slow multipliers, Liouville's sum of all eight, to
# 1e-6 relative; ~1 min of CPU: ctest cycles_coulomb_reference, label "slow").
#   check_coulomb_cycles.sh BINARY SOURCE_DIR [reference]
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
mode=${3:-contract}
scene=$src/data/scenes/default.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"

"$bin" continue "$scene" --set omega=249 --param omega --to 251 --from-equilibrium balanced --cycles --dry off \
  --cycle-steps 4 -o "$work/c" >/dev/null 2>"$work/c.err"
check "a coulomb cycle branch out of steps exits 3" "[ $? -eq 3 ]"
check "... saying where and why" "grep -q 'numerical failure: cycle 1.*ran out of steps' '$work/c.err'"
csv=$work/c/cycles_omega.csv
check "... its orbits written" "[ \$(grep -v '^#' '$csv' | tail -n +2 | wc -l) -ge 4 ]"
check "... the stiff route said in the csv" "grep -q '^# cycle 1: stiff route: 16 shooting intervals of' '$csv'"
check "... the chart over the equilibria" "[ -s '$work/c/cycles_omega.png' ]"
check "no nan or inf in the csv" "! grep -v '^#' '$csv' | grep -qiE 'nan|inf'"
/usr/bin/python3 - "$csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))
bad = []
for r in rows:
    lm = [float(r[f"mult_logmod{k}"]) for k in range(1, 9)]
    if any(a < b - 1e-12 for a, b in zip(lm, lm[1:])): bad.append(f"point {r['point']}: not sorted by modulus")
    if sum(1 for l in lm if l < -700) != 6: bad.append(f"point {r['point']}: not six multipliers below 1e-300")
    if float(r["trivial_distance"]) > 1e-8: bad.append(f"point {r['point']}: trivial multiplier off 1")
    if r["stable"] != "0": bad.append(f"point {r['point']}: a subcritical Hopf's cycle called stable")
print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
check "six multipliers below 1e-300, sorted, trivial within 1e-8 of 1, unstable" "[ $? -eq 0 ]"
# An independent integrator (GSL bsimp, adaptive, rtol 1e-11: simulate, model.md §15) from the
# last orbit's x(0) over its period T must come back to x(0): the scaled difference (q / L,
# beta, dq / (L omega_H), dbeta / omega_H, L = (U + sum m l) / M; the scaling of model.md §17.2)
# at most 1e-6. Measured 1.6e-8; bsimp's own spread between rtol 1e-10 and 1e-12 reaches 4.4e-7
# (dq1). A period error dT shows as |f| dT ~ omega_H dT: this also checks T to ~1e-7 relative.
read -r omega period state < <(/usr/bin/python3 - "$csv" <<'PY'
import csv, sys
r = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))[-1]
print(r["omega"], r["period"], ",".join(r[k] for k in ("q1_0","q2_0","beta1_0","beta2_0","dq1_0","dq2_0","dbeta1_0","dbeta2_0")))
PY
)
"$bin" simulate "$scene" --set omega="$omega" --from-state="$state" --t-end "$period" --method bsimp --rtol 1e-11 \
  --every "$period" -o "$work/s" >/dev/null 2>&1
check "simulate from the last orbit's x(0) over its period runs" "[ $? -eq 0 ]"
/usr/bin/python3 - "$work/s/simulation.csv" "$state" "$period" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))
x0 = [float(v) for v in sys.argv[2].split(",")]
end = rows[-1]
if abs(float(end["t"]) - float(sys.argv[3])) > 1e-9 * float(sys.argv[3]):
    print("the simulation did not end at T"); sys.exit(1)
xT = [float(end[k]) for k in ("q1","q2","beta1","beta2","dq1","dq2","dbeta1","dbeta2")]
L = (6.0e-7 + 2 * 3.3e-5 * 0.018) / 0.12   # data/scenes/default.toml
w = 2 * 3.141592653589793 / float(sys.argv[3])
D = [L, L, 1, 1, L * w, L * w, w, w]
d = max(abs(a - b) / s for a, b, s in zip(xT, x0, D))
print(f"periodicity under bsimp: scaled |x(T) - x(0)| = {d:.2e}")
sys.exit(0 if d <= 1e-6 else 1)
PY
check "... and comes back to x(0) within 1e-6 (scaled)" "[ $? -eq 0 ]"
# The first orbit does not depend on the parameter box's scaling: with --to 252 (and 300) its
# Newton used to stall at the stiff route's noise (~1e-6 scaled, model.md §17.9) and the branch
# had no orbit at all, while 251 and 255 worked.
"$bin" continue "$scene" --set omega=249 --param omega --to 252 --from-equilibrium balanced --cycles --dry off \
  --cycle-steps 2 -o "$work/c252" >/dev/null 2>"$work/c252.err"
check "--to 252: out of steps (exit 3), not a failed first orbit" \
  "[ $? -eq 3 ] && grep -q 'ran out of steps' '$work/c252.err' && ! grep -q 'did not converge' '$work/c252.err'"
check "... its orbits written" "[ \$(grep -v '^#' '$work/c252/cycles_omega.csv' | tail -n +2 | wc -l) -ge 3 ]"
if [ "$mode" = reference ]; then
  /usr/bin/python3 "$src/tests/reference/coulomb_cycle_reference.py" "$scene" "$csv" --rtol 1e-6
  check "the last orbit against the independent Radau reference to 1e-6" "[ $? -eq 0 ]"
fi
finish
