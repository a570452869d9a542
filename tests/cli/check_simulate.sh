#!/usr/bin/env bash
# The command-line contract of `stability-scan simulate` (model.md §15): the CSV's
# columns, no NaN, the summary JSON's keys, the chart, bad input (exit 2, one message,
# nothing written), Ctrl-C keeps what was computed (exit 130), any n.
#   check_simulate.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
scene=$src/data/scenes/default.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"

# --- a constant-speed run from balls at rest ------------------------------------------------
"$bin" simulate "$scene" --balls 2,4 --t-end 0.05 --every 1e-4 -o "$work/run" --summary "$work/run/summary.json" 2>"$work/run.err"
check "simulate exits 0" "[ $? -eq 0 ]"
header=$(grep -v '^#' "$work/run/simulation.csv" | head -1)
check "csv header is the documented one" \
  "[ '$header' = 't,omega,q1,q2,beta1,beta2,dq1,dq2,dbeta1,dbeta2,q_abs,x_fixed,y_fixed,beta_rel1,beta_rel2' ]"
check "501 samples (t = 0 .. 0.05 every 1e-4)" "[ \$(grep -v '^#' '$work/run/simulation.csv' | tail -n +2 | wc -l) -eq 501 ]"
check "no nan or inf in the csv" "! grep -v '^#' '$work/run/simulation.csv' | grep -qiE 'nan|inf'"
check "steps and evaluations reported" "grep -q '^# steps [0-9]*, rejected [0-9]*, rhs evaluations [0-9]*, jacobian evaluations' '$work/run/simulation.csv'"
check "stiff coulomb scene takes the implicit method" "grep -q '^# method: bsimp' '$work/run/simulation.csv'"
check "the chart is written" "[ -s '$work/run/simulation.png' ]"
check "summary json has the documented keys" "/usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/run/summary.json'))
need = ['outcome', 't_end', 'state_end', 'max_q_abs', 't_max_q_abs', 'settle_time', 'stalled']
sys.exit(0 if all(k in s for k in need) and len(s['state_end']) == 8 and s['t_end'] == 0.05 else 1)\""
check "no temporaries left" "[ -z \"\$(ls -A '$work/run' | grep tmp)\" ]"

# --- run-up through omega_n, 3 balls, from a perturbed equilibrium ---------------------------
"$bin" simulate "$scene" --ramp 200:300:1000 --t-end 0.12 --balls 2,4 --no-chart -o "$work/ramp" \
  --summary "$work/ramp.json" 2>"$work/ramp.err"
check "ramp exits 0" "[ $? -eq 0 ]"
check "ramp passes omega_n once" "/usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/ramp.json'))
sys.exit(0 if len(s['t_omega_n']) == 1 and abs(s['t_omega_n'][0] - (s['omega_n'] - 200) / 1000) < 1e-12 else 1)\""
sed 's/^count = 11/count = 3/' "$src/data/scenes/ring11.toml" >"$work/ring3.toml"
"$bin" simulate "$work/ring3.toml" --from-equilibrium balanced:1 --perturb 1e-3 --t-end 0.01 \
  --no-chart -o "$work/n3" --summary "$work/n3.json" 2>"$work/n3.err"
check "3 balls from a perturbed balanced sample exits 0" "[ $? -eq 0 ] && [ -s '$work/n3.json' ]"
"$bin" simulate "$scene" --from-equilibrium together:1 --t-end 0.01 --no-chart -o "$work/tog" 2>"$work/tog.err"
check "two balls from a perturbed equilibrium exits 0" "[ $? -eq 0 ]"
# A tiny start: --perturb 1e-200 (and a subnormal one) made GSL's bsimp, whose runaway test
# weighs a change by |y_i|, reject every step down to t = 1e-192 s and then fail with a false
# "right-hand side not finite" (exit 3). Components below 1e-3 of their absolute tolerance
# are now integrated as 0 and the run says how many: it starts at the equilibrium itself and
# stays balanced (|q| at rounding, 1e-15 L), with bsimp as with rk8pd.
for eps in 1e-200 1e-310; do
  for m in bsimp rk8pd; do
    "$bin" simulate "$scene" --from-equilibrium balanced --perturb $eps --t-end 0.05 --method $m --no-chart \
      -o "$work/tiny$eps$m" --summary "$work/tiny$eps$m.json" 2>"$work/tiny.err"
    check "tiny start: --perturb $eps with $m exits 0, balanced, the start below resolution counted" \
      "[ $? -eq 0 ] && /usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/tiny$eps$m.json'))
sys.exit(0 if s['outcome'] == 'balanced' and s['start_below_resolution'] > 0 else 1)\" && grep -q 'integrated as 0' '$work/tiny.err'"
  done
done
# Memory known before the work: a run's samples and CSV text are estimated before it starts
# (printed and in the JSON); 11 balls, 2e5 samples: the peak (whole process, /usr/bin/time)
# stays below it. Before, 1.9e7 samples of 11 balls were accepted and the run was killed by
# the kernel at 24 GB; now a run estimated above 80 % of MemAvailable is refused up front.
ring11=$src/data/scenes/ring11.toml
balls11=0,0.5,1,1.5,2,2.5,3,3.5,4,4.5,5
if [ -z "${ASAN_OPTIONS:-}" ]; then  # under the sanitizers the shadow memory is not the program's
  /usr/bin/time -f %M -o "$work/mem.kb" "$bin" simulate "$ring11" --balls $balls11 --t-end 0.2 --every 1e-6 \
    --no-chart -o "$work/mem" --summary "$work/mem.json" 2>"$work/mem.err"
  estimate=$(/usr/bin/python3 -c "import json; print(int(json.load(open('$work/mem.json'))['memory_estimate']))")
  peak=$(($(tail -1 "$work/mem.kb") * 1024))
  check "11 balls, 2e5 samples: peak $((peak / 1000000)) MB below the printed estimate $((estimate / 1000000)) MB" \
    "[ $peak -lt $estimate ] && grep -q 'memory: at most about' '$work/mem.err'"
fi
available=$(awk '/^MemAvailable:/ {print $2 * 1024}' /proc/meminfo)
# 2 344 bytes a sample for 11 balls (simulation.hpp); the 2e7-sample cap must not come first.
t_end=$(/usr/bin/python3 -c "print(f'{1.5 * $available / 2344 * 1e-6:.6g}')")
if /usr/bin/python3 -c "import sys; sys.exit(0 if 1.5 * $available / 2344 < 2e7 else 1)"; then
  mkdir -p "$work/huge"
  (cd "$work/huge" && "$bin" simulate "$ring11" --balls $balls11 --t-end "$t_end" --every 1e-6 -o out \
    --summary s.json 2>"$work/huge.err")
  check "a run estimated at 1.5 times MemAvailable: exit 2 naming --every and the figures, nothing written" \
    "[ $? -eq 2 ] && grep -q -- '--every: the run would hold about' '$work/huge.err' && [ -z \"\$(ls -A '$work/huge')\" ]"
else
  echo "skip (MemAvailable above 31 GB: the 2e7-sample cap refuses first)"
fi

printf 't,omega\n0,100\n0.01,150\n0.02,150\n' >"$work/profile.csv"
"$bin" simulate "$src/data/scenes/ring11.toml" --speed-profile "$work/profile.csv" --t-end 0.02 \
  --balls 0,0.5,1,1.5,2,2.5,3,3.5,4,4.5,5 --no-chart -o "$work/n11" 2>"$work/n11.err"
check "11 balls with a speed profile" "[ \$(grep -v '^#' '$work/n11/simulation.csv' | head -1 | tr ',' '\n' | wc -l) -eq 42 ]"

# --- bad input: exit 2, one message, nothing written -----------------------------------------
bad() {  # name, then the arguments; -o inside an empty directory
  local name=$1
  shift
  local dir=$work/bad.$RANDOM
  mkdir -p "$dir"
  (cd "$dir" && "$bin" simulate "$@" -o out --summary s.json >"$work/out" 2>"$work/err")
  local code=$?
  if [ $code -ne 2 ]; then fail "$name: exit $code, expected 2 ($(head -c 200 "$work/err"))"; return; fi
  if [ -n "$(ls -A "$dir")" ]; then fail "$name: wrote $(ls -A "$dir")"; return; fi
  if ! head -1 "$work/err" | grep -q '^stability-scan: '; then fail "$name: no message: $(cat "$work/err")"; return; fi
  pass "$name: exit 2 ($(head -1 "$work/err" | cut -c1-100))"
}
printf '0,100\n0.5,200\n0.4,300\n' >"$work/decreasing.csv"
printf '0,100\n0.5,-20\n' >"$work/negative.csv"
bad "negative t-end"              "$scene" --balls 2,4 --t-end -1
bad "zero t-end"                  "$scene" --balls 2,4 --t-end 0
bad "ramp through omega <= 0"     "$scene" --balls 2,4 --ramp 100:-5:10
bad "ramp down to omega = 0"      "$scene" --balls 2,4 --ramp 100:0:10
bad "ramp with zero acceleration" "$scene" --balls 2,4 --ramp 100:200:0
bad "malformed ramp"              "$scene" --balls 2,4 --ramp 100:200
bad "state of the wrong length"   "$scene" --from-state 0,0,1,2,0,0,0
bad "non-numeric state"           "$scene" --from-state 0,0,1,2,0,0,0,x
bad "ball angles of the wrong count" "$scene" --balls 1,2,3
bad "profile not increasing in t" "$scene" --balls 2,4 --speed-profile "$work/decreasing.csv"
bad "profile with omega <= 0"     "$scene" --balls 2,4 --speed-profile "$work/negative.csv"
bad "missing profile file"        "$scene" --balls 2,4 --speed-profile "$work/nosuch.csv"
bad "no start"                    "$scene"
bad "two starts"                  "$scene" --balls 2,4 --from-equilibrium balanced
bad "unknown equilibrium"         "$scene" --from-equilibrium sideways
bad "perturb without equilibrium" "$scene" --balls 2,4 --perturb 1e-3
bad "unknown method"              "$scene" --balls 2,4 --method euler
bad "rtol out of range"           "$scene" --balls 2,4 --rtol 0
bad "rtol below double rounding"  "$scene" --balls 2,4 --rtol 1e-17
# The summary named as the run's own chart: refused before any work (it would be overwritten
# by the chart, and the JSON said written).
mkdir -p "$work/clash"
(cd "$work/clash" && "$bin" simulate "$scene" --balls 2,4 --t-end 0.01 -o out --summary out/simulation.png \
  >"$work/out" 2>"$work/err")
check "summary at the chart's path: exit 2, nothing written, the option named" \
  "[ $? -eq 2 ] && [ -z \"\$(ls -A '$work/clash')\" ] && grep -q -- '--summary' '$work/err'"
bad "negative every"              "$scene" --balls 2,4 --every -1

# --- Ctrl-C keeps what was computed ----------------------------------------------------------
"$bin" simulate "$scene" --set mu=0 --method rk8pd --balls 2,4 --t-end 1e4 --every 0.1 --no-chart --quiet -o "$work/int" \
  --summary "$work/int.json" 2>"$work/int.err" &
pid=$!
sleep 2
kill -INT $pid
wait $pid
code=$?
check "SIGINT exits 130" "[ $code -eq 130 ]"
check "SIGINT keeps the CSV" "[ \$(grep -v '^#' '$work/int/simulation.csv' | tail -n +2 | wc -l) -gt 1 ]"
check "SIGINT keeps the summary, status interrupted" "grep -q '\"status\": \"interrupted\"' '$work/int.json'"

# --- a run that cannot finish: exit 3, where and why, samples kept ---------------------------
"$bin" simulate "$scene" --balls 2,4 --t-end 0.01 --max-steps 10 --no-chart --quiet -o "$work/fail" 2>"$work/fail.err"
code=$?
if [ $code -eq 3 ]; then
  pass "step budget exceeded exits 3 ($(grep -m1 'numerical failure' "$work/fail.err" | cut -c1-120))"
  check "failed run keeps its CSV" "[ -s '$work/fail/simulation.csv' ]"
else
  fail "step budget exceeded: exit $code, expected 3"
fi

# --- the scene's [simulate] table gives the same run as the flags; flags override it --------
cp "$scene" "$work/keys.toml"
printf 't,omega\n0,200\n0.05,300\n0.1,300\n' >"$work/keys_profile.csv"
cat >>"$work/keys.toml" <<'KEYS'

[simulate]
ramp = { omega0 = 200, omega1 = 300, alpha = 1000 }
t_end = 0.12
every = 1e-3
rtol = 1e-7
method = "bsimp"
balls = [2, 4.5]
KEYS
body() { grep -v -e '^# command' -e '^# scene' "$1"; }
"$bin" simulate "$work/keys.toml" --no-chart --quiet -o "$work/keys" 2>"$work/keys.err"
check "scene [simulate] run exits 0" "[ $? -eq 0 ]"
"$bin" simulate "$scene" --ramp 200:300:1000 --t-end 0.12 --every 1e-3 --rtol 1e-7 --method bsimp --balls 2,4.5 \
  --no-chart --quiet -o "$work/flags" 2>"$work/flags.err"
check "scene keys and flags give the same CSV" "cmp -s <(body '$work/keys/simulation.csv') <(body '$work/flags/simulation.csv')"
"$bin" simulate "$work/keys.toml" --t-end 0.05 --balls 1,3 --method rk8pd --no-chart --quiet -o "$work/over" 2>/dev/null
"$bin" simulate "$scene" --ramp 200:300:1000 --t-end 0.05 --every 1e-3 --rtol 1e-7 --method rk8pd --balls 1,3 \
  --no-chart --quiet -o "$work/over2" 2>/dev/null
check "flags override the scene's keys" "cmp -s <(body '$work/over/simulation.csv') <(body '$work/over2/simulation.csv')"
sed -i 's/^ramp = .*/speed_profile = "keys_profile.csv"/' "$work/keys.toml"
(cd / && "$bin" simulate "$work/keys.toml" --no-chart --quiet -o "$work/prof" 2>"$work/prof.err")
"$bin" simulate "$scene" --speed-profile "$work/keys_profile.csv" --t-end 0.12 --every 1e-3 --rtol 1e-7 --method bsimp \
  --balls 2,4.5 --no-chart --quiet -o "$work/prof2" 2>/dev/null
check "speed_profile is read relative to the scene file" \
  "cmp -s <(body '$work/prof/simulation.csv') <(body '$work/prof2/simulation.csv')"

finish
