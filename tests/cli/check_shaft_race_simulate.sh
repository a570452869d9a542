#!/usr/bin/env bash
# `simulate` of balls on an unround race on a flexible shaft (docs/model.md §18.20), from the
# command line:
#  1. the four-element shaft with two viscous balls on an offset + oval race
#     (tests/scenes/shaft/race_four_elements.toml) from the balls at (0.5, 2) rad settles at one of
#     the race's equilibria on the shaft: the summary names `equilibrium` k, and `equilibria
#     --format json` lists member k as stable with the same |q| (to 1e-12: the same number) and,
#     at the end state, beta within the settle tolerance 1e-3 rad and |q| within 1e-3 L;
#  2. the CSV names the race and has no balanced reference angles; the JSON's state_end and
#     shaft.x_end agree;
#  3. a run-up onto 600 rad/s runs and ends in `equilibrium` too;
#  4. what stays refused (exit 2, nothing written, the message naming the combination):
#     --from-equilibrium, LuGre or coulomb-set balls on the race on a shaft.
#   check_shaft_race_simulate.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
race=$src/tests/scenes/shaft/race_four_elements.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"

"$bin" simulate "$race" --balls 0.5,2 --t-end 3 --every 2e-3 --no-chart -o "$work/run" --summary "$work/run.json" \
  2>"$work/run.err"
check "simulate on an unround race on a shaft exits 0" "[ $? -eq 0 ]"
"$bin" equilibria "$race" --format json >"$work/eq.json" 2>/dev/null
check "equilibria exits 0" "[ $? -eq 0 ]"
out=$(/usr/bin/python3 - "$work/run.json" "$work/eq.json" <<'PY'
import json, math, sys
s = json.load(open(sys.argv[1])); e = json.load(open(sys.argv[2]))
if s["outcome"] != "equilibrium":
    print(f"outcome {s['outcome']}"); sys.exit(1)
k = s["unround_equilibrium"]["member"]
eq = [x for x in e["equilibria"] if x["member"] == k][0]
x, L = s["state_end"], s["displacement_scale"]
dq = abs(math.hypot(x[0], x[1]) - eq["q_abs"]) / L
db = max(abs(math.remainder(x[2 + i] - eq["beta"][i], 2 * math.pi)) for i in range(2))
same = abs(s["unround_equilibrium"]["q_abs"] - eq["q_abs"]) <= 1e-12 * eq["q_abs"]
print(f"member {k} ({eq['verdict']}), | |q| - q* | / L = {dq:.2g}, beta {db:.2g} rad")
sys.exit(0 if eq["verdict"] == "stable" and same and dq <= 1e-3 and db <= 1e-3 else 1)
PY
)
check "the run ends at a stable equilibrium equilibria lists ($out)" "[ $? -eq 0 ]"
check "the text names the equilibrium" "grep -q 'outcome: equilibrium .* of the unround race on the shaft' '$work/run.err'"
check "the csv names the race" "grep -q '^# race, ball 2 (path radius' '$work/run/simulation.csv'"
check "the csv has no balanced reference angles" "! grep -v '^#' '$work/run/simulation.csv' | tail -n +2 | cut -d, -f14,15 | grep -q '[0-9]'"
check "no nan or inf in the csv" "! grep -v '^#' '$work/run/simulation.csv' | grep -qiE 'nan|inf'"
check "x_end's balancer node and balls are state_end's" "/usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/run.json')); x = s['shaft']['x_end']
sys.exit(0 if x[12:14] == s['state_end'][0:2] and x[20:22] == s['state_end'][2:4] else 1)\""

"$bin" simulate "$race" --balls 0.5,2 --ramp 300:600:600 --t-end 3 --every 2e-3 --no-chart --quiet \
  --summary "$work/ramp.json" -o "$work/ramp" 2>/dev/null
check "a run-up exits 0" "[ $? -eq 0 ]"
check "the run-up ends in equilibrium" "grep -q '\"outcome\": \"equilibrium\"' '$work/ramp.json'"

bad() {  # name, expected text of the message, then the arguments; -o inside an empty directory
  local name=$1 text=$2
  shift 2
  local dir=$work/bad.$RANDOM
  mkdir -p "$dir"
  (cd "$dir" && "$bin" simulate "$@" -o out --summary s.json >"$work/out" 2>"$work/err")
  local code=$?
  if [ $code -ne 2 ]; then fail "$name: exit $code, expected 2 ($(head -c 200 "$work/err"))"; return; fi
  if [ -n "$(ls -A "$dir")" ]; then fail "$name: wrote $(ls -A "$dir")"; return; fi
  if ! head -1 "$work/err" | grep -q "^stability-scan: .*$text"; then fail "$name: message: $(head -c 300 "$work/err")"; return; fi
  pass "$name: exit 2 ($(head -1 "$work/err" | cut -c1-110))"
}
sed 's/^law = "viscous"/law = "lugre"\nsigma0 = 150.0\nsigma1 = 0.05\nsigma2 = 0.0\nmu_c = 0.0021\nmu_s = 0.0042\nv_s = 0.6/; /^d = /d' "$race" >"$work/lugre.toml"
sed 's/^law = "viscous"/law = "coulomb-set"\nmu = 0.002/; /^d = /d' "$race" >"$work/set.toml"
bad "from an equilibrium"          "--from-equilibrium: not on a flexible shaft" "$race" --from-equilibrium 1
bad "LuGre on the race on a shaft" "an unround race, LuGre" "$work/lugre.toml" --balls 0.5,2
bad "coulomb-set on the race on a shaft" "an unround race, LuGre and coulomb-set" "$work/set.toml" --balls 0.5,2
finish
