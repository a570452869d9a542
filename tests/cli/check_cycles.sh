#!/usr/bin/env bash
# The contract of `continue --cycles` (docs/model.md §17, docs/guide.md §8): bad input exit 2
# with nothing written; a cycle branch cut short exit 3 with its orbits written; the CSV's
# columns by name, multipliers sorted by modulus, no NaN; and, with a reference directory
# given, one orbit against the independent reference (tests/reference/cycle_reference.py).
#   check_cycles.sh BINARY SOURCE_DIR [reference]
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
mode=${3:-contract}
scene=$src/tests/scenes/cycles/viscous_ref.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"

if [ "$mode" = contract ]; then
  "$bin" continue "$src/tests/scenes/continuation_n/ring3_coulomb.toml" --param omega --to 100 --cycles -o "$work/n3" 2>"$work/n3.err"
  check "--cycles with three balls exits 2" "[ $? -eq 2 ]"
  check "... naming the option" "grep -q -- '--cycles' '$work/n3.err'"
  check "... nothing written" "[ ! -e '$work/n3' ] || [ -z \"\$(ls -A '$work/n3')\" ]"
  "$bin" continue "$scene" --param omega --to 50 --cycles --cycle-steps 0 -o "$work/z" 2>"$work/z.err"
  check "--cycle-steps 0 exits 2" "[ $? -eq 2 ]"
  check "... nothing written" "[ ! -e '$work/z' ] || [ -z \"\$(ls -A '$work/z')\" ]"
  "$bin" continue "$scene" --param omega --to 50 --cycles --cycle-floquet-rtol 0 -o "$work/t" 2>"$work/t.err"
  check "--cycle-floquet-rtol 0 exits 2" "[ $? -eq 2 ]"
  check "... naming the option and its range" "grep -q -- '--cycle-floquet-rtol: 0 must be in \[1e-15, 0.01\]' '$work/t.err'"
  check "... nothing written" "[ ! -e '$work/t' ] || [ -z \"\$(ls -A '$work/t')\" ]"
fi

# 6 steps: the branch is cut short on purpose (exit 3, the orbits kept).
"$bin" continue "$scene" --param omega --to 50 --from-equilibrium balanced --cycles --cycle-steps 6 -o "$work/c" \
  2>"$work/c.err"
check "a cycle branch out of steps exits 3" "[ $? -eq 3 ]"
check "... saying where and why" "grep -q 'numerical failure: cycle 1.*ran out of steps' '$work/c.err'"
csv=$work/c/cycles_omega.csv
check "... the orbits computed are written" "[ \$(grep -v '^#' '$csv' | tail -n +2 | wc -l) -eq 7 ]"
check "cycle_special_omega.csv written" "[ -s '$work/c/cycle_special_omega.csv' ]"
check "... its header is the documented one" \
  "[ \"\$(grep -v '^#' '$work/c/cycle_special_omega.csv' | head -1)\" = 'cycle,label,omega,period,amplitude,located' ]"
check "cycles_omega.png written" "[ -s '$work/c/cycles_omega.png' ]"
header=$(grep -v '^#' "$csv" | head -1)
expected="cycle,point,omega,period,amplitude,stable,trivial_distance,beta1_min,beta1_max,beta2_min,beta2_max"
for k in 1 2 3 4 5 6 7 8; do expected="$expected,mult_re$k,mult_im$k,mult_logmod$k"; done
expected="$expected,q1_0,q2_0,beta1_0,beta2_0,dq1_0,dq2_0,dbeta1_0,dbeta2_0"
check "cycles csv header is the documented one" "[ \"$header\" = \"$expected\" ]"
check "no nan or inf in the csv" "! grep -v '^#' '$csv' | grep -qiE 'nan|inf'"
/usr/bin/python3 - "$csv" <<'PY'
import csv, math, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))
bad = []
for r in rows:
    lm = [float(r[f"mult_logmod{k}"]) for k in range(1, 9)]
    if any(a < b - 1e-12 for a, b in zip(lm, lm[1:])): bad.append(f"point {r['point']}: not sorted by modulus")
    mods = [abs(complex(float(r[f"mult_re{k}"]), float(r[f"mult_im{k}"]))) for k in range(1, 9)]
    if any(abs(math.log(m) - l) > 1e-9 for m, l in zip(mods, lm) if m > 0): bad.append(f"point {r['point']}: logmod")
    if float(r["trivial_distance"]) > 1e-7: bad.append(f"point {r['point']}: trivial multiplier off 1")
print("\n".join(bad))
sys.exit(1 if bad else 0)
PY
check "multipliers sorted by modulus, logmod = ln|mu|, trivial multiplier within 1e-7 of 1" "[ $? -eq 0 ]"

if [ "$mode" = reference ]; then
  # 14 steps: the last orbit (amplitude ~3.7e-6 m) is far enough from the Hopf point that
  # the reference's single shooting is well conditioned (at ~1e-7 m its Newton stalls at
  # ~1e-10 scaled, the nontrivial multiplier being within 1e-6 of 1).
  "$bin" continue "$scene" --param omega --to 50 --from-equilibrium balanced --cycles --cycle-steps 14 \
    -o "$work/r" >/dev/null 2>"$work/r.err"
  /usr/bin/python3 "$src/tests/reference/cycle_reference.py" "$scene" "$work/r/cycles_omega.csv" --rtol 1e-6
  check "the last orbit against the independent reference to 1e-6" "[ $? -eq 0 ]"
  # The fast configuration of model.md §17.9 (4 times cheaper per orbit): the same branch,
  # its last orbit against the same reference to the same 1e-6 (every multiplier included).
  "$bin" continue "$scene" --param omega --to 50 --from-equilibrium balanced --cycles --cycle-steps 14 \
    --cycle-intervals 5 --cycle-rtol 1e-10 --cycle-newton-rtol 1e-4 --cycle-floquet-rtol 1e-8 \
    -o "$work/f" >/dev/null 2>"$work/f.err"
  /usr/bin/python3 "$src/tests/reference/cycle_reference.py" "$scene" "$work/f/cycles_omega.csv" --rtol 1e-6
  check "the fast configuration's last orbit against the independent reference to 1e-6" "[ $? -eq 0 ]"
fi
finish
