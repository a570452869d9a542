#!/bin/sh
# `equilibria` with coulomb-set balls on an unround race (docs/model.md §20.5): the stick set,
# V and V_E against an independent numpy grid with the stick condition from the force balance
# of a ball at rest on its path (composed_stick_reference.py). Usage: check_composed_stick.sh BINARY SCENES_DIR
set -eu
bin=$1
scenes=$2
here=$(dirname "$0")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for scene in runout_coulomb_set oval_coulomb_set; do
  "$bin" equilibria "$scenes/composed/$scene.toml" --format json > "$out/$scene.json"
  /usr/bin/python3 "$here/verdict_cache.py" "$out/$scene.json" -- \
    /usr/bin/python3 "$here/composed_stick_reference.py" "$scenes/composed/$scene.toml" --json "$out/$scene.json"
done
# `sweep` of the same scene over mu: its row at the scene's mu is the `equilibria` set (the same
# computation per value: V, V_E and the area equal to the last digit printed).
"$bin" sweep "$scenes/composed/runout_coulomb_set.toml" --param mu --from 1e-4 --to 2e-4 --steps 1 -o "$out/sweep" --no-chart
/usr/bin/python3 - "$out/sweep/sweep_stick_mu.csv" "$out/runout_coulomb_set.json" <<'PY'
import json, sys
rows = [l.rstrip("\n").split(",") for l in open(sys.argv[1]) if not l.startswith("#")]
col = {k: i for i, k in enumerate(rows[0])}
first = rows[1]
s = json.load(open(sys.argv[2]))["stick_set"]
got = [float(first[col[k]]) for k in ("area", "worst_q_abs", "worst_q_abs_any")]
want = [s["area"], s["worst_q_abs"], s["worst_q_abs_any"]]
ok = float(first[col["mu"]]) == 1e-4 and all(abs(g - w) <= 1e-12 * abs(w) for g, w in zip(got, want))
print("sweep row at mu = 1e-4:", got, "equilibria:", want, "agree" if ok else "MISMATCH")
sys.exit(0 if ok else 1)
PY
# `map` of the same scene (omega x mu): its cell at the scene's omega and mu is the `equilibria`
# set too (V, V_E and the area to 1e-12).
"$bin" map "$scenes/composed/runout_coulomb_set.toml" --x omega:800:900:2 --y mu:1e-4:2e-4:2 -o "$out/map" --no-chart --quiet
/usr/bin/python3 - "$out/map/summary_omega_mu.csv" "$out/runout_coulomb_set.json" <<'PY'
import json, sys
rows = [l.rstrip("\n").split(",") for l in open(sys.argv[1]) if not l.startswith("#")]
col = {k: i for i, k in enumerate(rows[0])}
cell = [r for r in rows[1:] if float(r[col["omega"]]) == 800 and float(r[col["mu"]]) == 1e-4][0]
s = json.load(open(sys.argv[2]))["stick_set"]
got = [float(cell[col[k]]) for k in ("area", "worst_q_abs", "worst_q_abs_any")]
want = [s["area"], s["worst_q_abs"], s["worst_q_abs_any"]]
ok = all(abs(g - w) <= 1e-12 * abs(w) for g, w in zip(got, want))
print("map cell at (800, 1e-4):", got, "equilibria:", want, "agree" if ok else "MISMATCH")
sys.exit(0 if ok else 1)
PY
