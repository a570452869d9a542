#!/usr/bin/env bash
# The command-line contract of `stability-scan simulate` on a flexible shaft (docs/model.md
# §18.16, docs/cli.md): the rigid route's CSV with the shaft's columns, no NaN, the summary
# JSON's shaft block, the chart, a restart from the written end state, a run-up, bad input
# (exit 2, one message naming the option and the rule, nothing written), and the shaft
# combinations simulate still refuses (LuGre, coulomb-set; an unround race runs:
# check_shaft_race_simulate.sh).
#   check_shaft_simulate.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
one=$src/tests/scenes/shaft/one_node.toml
four=$src/tests/scenes/shaft/sim_four_elements.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"

# --- a constant-speed run of the four-element shaft -------------------------------------------
"$bin" simulate "$four" --balls 0.5,2,4 --t-end 0.05 --every 1e-3 -o "$work/run" --summary "$work/run.json" \
  2>"$work/run.err"
check "simulate on a shaft exits 0" "[ $? -eq 0 ]"
header=$(grep -v '^#' "$work/run/simulation.csv" | head -1)
check "csv header: the rigid columns, then max_deflection, max_deflection_node" \
  "[ '$header' = 't,omega,q1,q2,beta1,beta2,beta3,dq1,dq2,dbeta1,dbeta2,dbeta3,q_abs,x_fixed,y_fixed,beta_rel1,beta_rel2,beta_rel3,max_deflection,max_deflection_node' ]"
check "51 samples (t = 0 .. 0.05 every 1e-3)" "[ \$(grep -v '^#' '$work/run/simulation.csv' | tail -n +2 | wc -l) -eq 51 ]"
check "no nan or inf in the csv" "! grep -v '^#' '$work/run/simulation.csv' | grep -qiE 'nan|inf'"
check "the csv says it is the balancer node of a shaft" "grep -q '^# flexible shaft (model.md §18.16): 5 nodes, 46 states' '$work/run/simulation.csv'"
check "the derived line is the summary's rigid view, not k = 0" "grep -q '^# derived: the summary.s rigid view of the shaft .*M_r = 0.5 kg' '$work/run/simulation.csv'"
check "the lightly damped shaft takes the explicit method" "grep -q '^# method: rk8pd' '$work/run/simulation.csv'"
check "the chart is written" "[ -s '$work/run/simulation.png' ]"
check "stderr names the largest node deflection" "grep -q 'largest node deflection: .* m at node [0-4], t = ' '$work/run.err'"
check "summary json: the rigid keys and the shaft block" "/usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/run.json'))
sh = s['shaft']
ok = len(s['state_end']) == 10 and sh['nodes'] == 5 and sh['state_size'] == 46 and len(sh['x_end']) == 46
ok = ok and sh['max_deflection'] >= s['max_q_abs'] > 0 and 0 <= sh['max_deflection_node'] <= 4
ok = ok and s['t_omega_n'] == [] and s['t_end'] == 0.05
# the balancer node (3) of x_end is state_end's q; the balls follow the 20 shaft dofs
ok = ok and sh['x_end'][12:14] == s['state_end'][0:2] and sh['x_end'][20:23] == s['state_end'][2:5]
sys.exit(0 if ok else 1)\""
# The largest deflection in the CSV never exceeds the located one (it is a maximum over the run).
check "max_deflection column <= the located maximum" "/usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/run.json'))
rows = [l for l in open('$work/run/simulation.csv') if not l.startswith('#')]
col = rows[0].strip().split(',').index('max_deflection')
sys.exit(0 if max(float(r.split(',')[col]) for r in rows[1:]) <= s['shaft']['max_deflection'] else 1)\""

# --- a restart from the written end state continues the run --------------------------------------
state=$(/usr/bin/python3 -c "import json; print(','.join(repr(v) for v in json.load(open('$work/run.json'))['shaft']['x_end']))")
"$bin" simulate "$four" --from-state "$state" --t-end 0.01 --every 1e-3 --no-chart --quiet -o "$work/again" 2>"$work/again.err"
check "--from-state with the 46 values of x_end exits 0" "[ $? -eq 0 ]"
check "it starts where the run ended" "/usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/run.json'))
rows = [l for l in open('$work/again/simulation.csv') if not l.startswith('#')]
first = [float(v) for v in rows[1].split(',')[2:4]]
sys.exit(0 if first == s['state_end'][0:2] else 1)\""

# --- a run-up of the one-node shaft ---------------------------------------------------------------
"$bin" simulate "$one" --ramp 300:900:3000 --t-end 0.25 --balls 2,4 --no-chart -o "$work/ramp" \
  --summary "$work/ramp.json" 2>"$work/ramp.err"
check "run-up on a shaft exits 0" "[ $? -eq 0 ]"
check "one restart at the end of the ramp" "grep -q 'restarts 1$' '$work/ramp/simulation.csv'"
check "the largest |q| during the run-up is reported" "/usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/ramp.json'))
sys.exit(0 if s['max_q_abs_run_up'] is not None and s['max_q_abs_run_up'] > 0 else 1)\""

# --- Ctrl-C keeps what was computed; a run out of steps says where and why ------------------------
"$bin" simulate "$four" --balls 0.5,2,4 --t-end 1e4 --every 0.01 --no-chart --quiet -o "$work/int" \
  --summary "$work/int.json" 2>"$work/int.err" &
pid=$!
sleep 2
kill -INT $pid
wait $pid
code=$?
check "SIGINT exits 130" "[ $code -eq 130 ]"
check "SIGINT keeps the CSV" "[ \$(grep -v '^#' '$work/int/simulation.csv' | tail -n +2 | wc -l) -gt 1 ]"
check "SIGINT keeps the summary, status interrupted, x_end" "/usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/int.json'))
sys.exit(0 if s['status'] == 'interrupted' and len(s['shaft']['x_end']) == 46 else 1)\""
"$bin" simulate "$four" --balls 0.5,2,4 --t-end 0.01 --max-steps 10 --no-chart --quiet -o "$work/fail" 2>"$work/fail.err"
code=$?
check "step budget exceeded exits 3" "[ $code -eq 3 ]"
check "it says where and why" "grep -q 'numerical failure: at t = .* s: more than 10 steps' '$work/fail.err'"
check "the failed run keeps its CSV, no nan" "[ -s '$work/fail/simulation.csv' ] && ! grep -v '^#' '$work/fail/simulation.csv' | grep -qiE 'nan|inf'"

# --- bad input: exit 2, one message, nothing written ---------------------------------------------
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
bad "state of the wrong length"   "2 (4 N_nodes + n) = 2 (4 x 1 + 2) = 12 values" "$one" --from-state 0,0,1,2,0,0,0,0
bad "ball angles of the wrong count" "--balls: expected 2 ball angles" "$one" --balls 1,2,3
bad "from an equilibrium"         "--from-equilibrium: not on a flexible shaft.*--from-state" "$one" --from-equilibrium balanced
bad "perturb alone"               "--perturb" "$one" --balls 2,4 --perturb 1e-3
bad "no start"                    "exactly one start" "$one"
bad "negative t-end"              "--t-end.*> 0" "$one" --balls 2,4 --t-end -1
bad "rtol out of range"           "--rtol.*\\[1e-14, 0.1)" "$one" --balls 2,4 --rtol 0.5
bad "ramp through omega <= 0"     "ramp" "$one" --balls 2,4 --ramp 100:-5:10
sed 's/^law = "coulomb"/law = "lugre"\nsigma0 = 150.0\nsigma1 = 0.05\nsigma2 = 0.0\nmu_c = 0.0021\nmu_s = 0.0042\nv_s = 0.6/; /^mu = /d; /^kappa = /d' "$one" >"$work/lugre.toml"
sed 's/^law = "coulomb"/law = "coulomb-set"/; /^kappa = /d' "$one" >"$work/set.toml"
bad "a shaft with LuGre"          "LuGre.*flexible shaft" "$work/lugre.toml" --balls 2,4
bad "a shaft with coulomb-set"    "coulomb-set.*flexible shaft" "$work/set.toml" --balls 2,4
finish
