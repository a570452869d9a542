#!/usr/bin/env bash
# Memory known before the work (docs/robustness.md "Memory and disk"): every command that can
# hold much estimates it before it starts, prints the estimate ("at most about X GB") and
# refuses up front, naming the option and the figures, what this machine cannot hold. The peak
# of the whole process (/usr/bin/time) stays below the printed estimate; an input estimated
# beyond the memory available is refused with exit 2 and nothing written.
#   check_memory.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"
cd "$work"
available=$(awk '/^MemAvailable:/ {print $2 * 1024}' /proc/meminfo)

# The printed estimate of a run's stderr ("... at most about 0.877 GB ..."), in kB.
estimate_kb() { sed -n 's/.*at most about \([0-9.e+-]*\) GB.*/\1/p' "$1" | tail -1 | awk '{printf "%d", $1 * 1e6}'; }
# peak_below NAME ERR_FILE TIME_FILE: the peak (kB, /usr/bin/time) below the printed estimate.
peak_below() {
  local est peak
  est=$(estimate_kb "$2")
  peak=$(tail -1 "$3")
  check "$1: peak $((peak / 1000)) MB below the printed estimate $((${est:-0} / 1000)) MB" \
    "[ -n '$est' ] && [ '${est:-0}' -gt 0 ] && [ $peak -lt ${est:-0} ]"
}
# Nine ring scenes of 8 and 12 balls: the balanced set's grid and its aligned states.
sed 's/^count = 11 /count = 8 /' "$src/data/scenes/ring11.toml" >ring8.toml
sed 's/^count = 11 /count = 12 /' "$src/data/scenes/ring11.toml" >ring12.toml

if [ -z "${ASAN_OPTIONS:-}" ]; then  # under the sanitizers the shadow memory is not the program's
  # equilibria: 8 balls, 20,000 samples per sheet (93,312 grid points), as JSON (the largest
  # text); 12 balls, 3,000 (2,048 grid points and 12,288 aligned bounds).
  /usr/bin/time -f %M -o eq8.kb "$bin" equilibria ring8.toml --set-samples 20000 --format json -o eq8.json 2>eq8.err
  check "equilibria, 8 balls, 20,000 samples: exit 0" "[ $? -eq 0 ]"
  peak_below "equilibria, 8 balls, JSON" eq8.err eq8.kb
  /usr/bin/time -f %M -o eq12.kb "$bin" equilibria ring12.toml --set-samples 3000 --format table -o eq12.txt 2>eq12.err
  peak_below "equilibria, 12 coulomb balls, table" eq12.err eq12.kb

  # sweep of 11 balls (every value's analysis held to the end): 21 values of ~2,500 states.
  /usr/bin/time -f %M -o sw11.kb "$bin" sweep "$src/data/scenes/ring11.toml" --param omega --from 100 --to 2000 \
    --steps 20 --no-chart -o sw11 2>sw11.err
  peak_below "sweep of 11 balls, 21 values" sw11.err sw11.kb
  # ... over mu, 101 values: each value's analysis written and dropped as it comes (held, as
  # before, it was ~45 MB a value).
  /usr/bin/time -f %M -o swmu.kb "$bin" sweep "$src/data/scenes/ring11.toml" --param mu --from 1e-4 --to 1e-2 \
    --steps 100 --no-chart -o swmu 2>swmu.err
  peak_below "sweep of 11 balls over mu, 101 values (streamed)" swmu.err swmu.kb
  check "... 101 values written" "[ \$(grep -v '^#' swmu/summary_mu.csv | tail -n +2 | wc -l) -eq 101 ]"

  # two balls over mu, 20,001 values (streamed: held, it was ~28 kB a value, 560 MB).
  /usr/bin/time -f %M -o sw2.kb "$bin" sweep "$src/data/scenes/default.toml" --param mu --from 1e-4 --to 1e-1 \
    --steps 20000 --log --no-chart -o sw2 2>sw2.err
  check "sweep of two balls over mu, 20,001 values: peak $(($(tail -1 sw2.kb) / 1000)) MB below 60 MB (20 MB + 2 kB a value)" \
    "[ $(tail -1 sw2.kb) -lt 60000 ] && [ \$(grep -v '^#' sw2/sweep_mu.csv | tail -n +2 | wc -l) -eq 120006 ]"

  # continue with cycles: 1,000 shooting intervals held along 40 orbits.
  /usr/bin/time -f %M -o cyc.kb "$bin" continue "$src/tests/scenes/cycles/viscous_ref.toml" --param omega --to 50 \
    --from-equilibrium balanced --cycles --cycle-steps 40 --cycle-intervals 1000 --no-chart -o cyc 2>cyc.err
  peak_below "continue --cycles, 1,000 intervals" cyc.err cyc.kb

  # basin: every cell recorded at 1 us over 2 s on two workers.
  /usr/bin/time -f %M -o basin.kb "$bin" basin "$src/data/scenes/viscous.toml" --grid 4 --every 1e-6 --t-end 2 \
    --threads 2 -o basin 2>basin.err
  peak_below "basin, 4 x 4 cells at every 1e-6 s" basin.err basin.kb
fi

# Refusals: exit 2 naming the option and the figures, nothing written.
refused() {  # NAME OPTION DIR then the command
  local name=$1 option=$2 dir=$3
  shift 3
  "$@" 2>refused.err
  local code=$?
  check "$name: exit 2 naming $option and the figures, nothing written ($(head -c 160 refused.err))" \
    "[ $code -eq 2 ] && grep -q -- '$option: .* would hold about .* GB' refused.err && [ ! -e '$dir' ]"
}
refused "basin at every 1e-9 s over 10 s" --every b1 "$bin" basin "$src/data/scenes/ring11.toml" --every 1e-9 \
  --t-end 10 --grid 4 -o b1
# 12 branches x 2 x 1,000,001 points x 2 x 1,648 bytes = 79 GB
if /usr/bin/python3 -c "import sys; sys.exit(0 if 79e9 > 0.8 * $available else 1)"; then
  refused "continue --max-steps 1000000 (two balls)" --max-steps c1 "$bin" continue "$src/data/scenes/default.toml" \
    --param omega --to 1000 --max-steps 1000000 -o c1
fi
# 530,432 states of 11 balls as JSON: about 13 GB
if /usr/bin/python3 -c "import sys; sys.exit(0 if 13e9 > 0.8 * $available else 1)"; then
  refused "equilibria of 11 balls, 100,000 samples per sheet" --set-samples e1.json "$bin" equilibria \
    "$src/data/scenes/ring11.toml" --set-samples 100000 --format json -o e1.json
else
  echo "skip (MemAvailable above 16 GB: 11 balls at 100,000 samples fit)"
fi
finish
