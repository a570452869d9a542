#!/usr/bin/env bash
# The command-line contract of a shaft with anisotropic bearings (docs/model.md §18.19,
# docs/cli.md): `simulate` runs it (CSV without NaN naming the bearings' K_f and C_f, a run-up),
# `basin` too (tests/cli/check_basin_shaft.py), every other command refuses it (exit 2, one
# message naming the part and the two commands, nothing written), and anisotropic bearings with an unround race or coulomb-set balls are refused by all.
#   check_shaft_aniso.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
four=$src/tests/scenes/shaft/aniso_four_elements.toml
one=$src/tests/scenes/shaft/one_node_aniso.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"

"$bin" simulate "$four" --balls 0.5,2 --t-end 0.02 --every 1e-3 --no-chart -o "$work/run" --summary "$work/run.json" \
  2>"$work/run.err"
check "simulate on anisotropic bearings exits 0" "[ $? -eq 0 ]"
check "21 samples, no nan or inf" "[ \$(grep -v '^#' '$work/run/simulation.csv' | tail -n +2 | wc -l) -eq 21 ] && ! grep -v '^#' '$work/run/simulation.csv' | grep -qiE 'nan|inf'"
check "the csv names each bearing's K_f and C_f" \
  "[ \$(grep -c '^# anisotropic bearing at node [04] (model.md §18.19): K_f \[\[' '$work/run/simulation.csv') -eq 2 ]"
check "the summary has the shaft's end state" "/usr/bin/python3 -c \"
import json, sys
s = json.load(open('$work/run.json'))
sys.exit(0 if s['status'] == 'completed' and len(s['shaft']['x_end']) == 44 else 1)\""
"$bin" simulate "$one" --ramp 300:900:3000 --t-end 0.25 --balls 2,4 --no-chart --quiet -o "$work/ramp" 2>"$work/ramp.err"
check "a run-up on an anisotropic bearing exits 0 with one restart" "[ $? -eq 0 ] && grep -q 'restarts 1$' '$work/ramp/simulation.csv'"

# --- every other command: exit 2, one message, nothing written -----------------------------------
refused() {  # name, expected text, then the command line; run inside an empty directory
  local name=$1 text=$2
  shift 2
  local dir=$work/bad.$RANDOM
  mkdir -p "$dir"
  (cd "$dir" && "$bin" "$@" >"$work/out" 2>"$work/err")
  local code=$?
  if [ $code -ne 2 ]; then fail "$name: exit $code, expected 2 ($(head -c 200 "$work/err"))"; return; fi
  if [ -n "$(ls -A "$dir")" ]; then fail "$name: wrote $(ls -A "$dir")"; return; fi
  if ! head -1 "$work/err" | grep -q "^stability-scan: .*$text"; then fail "$name: message: $(head -c 300 "$work/err")"; return; fi
  pass "$name: exit 2 ($(head -1 "$work/err" | cut -c1-120))"
}
what="anisotropic bearings on a flexible shaft (model.md §18.19): only .simulate. and .basin. analyse"
refused "equilibria" "$what" equilibria "$four" --format csv -o out.csv
refused "sweep" "$what" sweep "$four" --param omega --from 100 --to 900 --steps 4 -o out
refused "map" "$what" map "$four" --x omega:100:900:4 --y U:1e-5:1e-4:3 -o out
refused "continue" "$what" continue "$four" --param omega --to 900 -o out
sed 's/^law = "viscous"/law = "coulomb-set"\nmu = 0.002/; /^d = /d' "$four" >"$work/set.toml"
printf '\n[race]\nsurface_unroundness = [{ order = 2, amplitude = 2e-5, phase = 1.0 }]\n' | cat "$four" - >"$work/unround.toml"
refused "simulate with coulomb-set balls" "anisotropic bearings .* together with a LuGre or coulomb-set law" \
  simulate "$work/set.toml" --balls 0.5,2 -o out
refused "equilibria on an unround race" "anisotropic bearings .* together with an unround race" \
  equilibria "$work/unround.toml" --format csv -o out.csv
refused "simulate on an unround race" "anisotropic bearings .* together with an unround race" \
  simulate "$work/unround.toml" --balls 0.5,2 -o out
finish
