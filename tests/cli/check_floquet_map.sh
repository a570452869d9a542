#!/bin/sh
# Usage: check_floquet_map.sh BINARY SCENE
# A map on an anisotropic support (docs/model.md §10.12): the same bytes with 1 and 2
# threads; the summary has rho_abs_max, with |rho| < 1 exactly where the balanced state is
# stable, and no aligned states (they are periodic orbits there).
set -eu
binary=$1; scene=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
axes="--x omega:150:900:10 --y U:2e-7:1.4e-6:4"
"$binary" map "$scene" $axes --threads 1 --long --no-chart --quiet -o "$tmp/a"
"$binary" map "$scene" $axes --threads 2 --long --no-chart --quiet -o "$tmp/b"
cmp "$tmp/a/summary_omega_U.csv" "$tmp/b/summary_omega_U.csv"
cmp "$tmp/a/map_omega_U.csv" "$tmp/b/map_omega_U.csv"
/usr/bin/python3 - "$tmp/a/summary_omega_U.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
with_state = [r for r in rows if r["rho_abs_max"] != ""]
assert with_state, "no cell with a balanced state"
for r in with_state:
    stable = float(r["balanced_stable_fraction"]) == 1.0
    assert stable == (float(r["rho_abs_max"]) < 1.0), r
    assert r["aligned"] == "0", r
print(f"ok: {len(rows)} cells, {len(with_state)} with balanced states, 1 and 2 threads identical")
PY
