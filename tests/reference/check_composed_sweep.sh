#!/bin/sh
# `sweep --param omega` on an unround race with an anisotropic support (docs/model.md §20.6):
# the periodic orbits at three values of the sweep (900, 1100, 1300 rad/s, 8 orbits each) found
# again by single shooting on the independent fixed-frame Lagrangian (composed_orbit_reference.py
# --sweep): x(0) closes the reference's orbit (to its 1e-12 scaled, at once) and every multiplier
# agrees to 2e-7 relative (measured 6e-8: the limit of the reference's difference-quotient
# monodromy). Usage: check_composed_sweep.sh BINARY SCENES_DIR
set -eu
bin=$1
scenes=$2
here=$(dirname "$0")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
scene=$scenes/composed/oval_anisotropic.toml
"$bin" sweep "$scene" --param omega --from 900 --to 1300 --steps 2 --no-chart -o "$out" 2> "$out/stderr"
/usr/bin/python3 "$here/verdict_cache.py" "$out/sweep_omega.csv" -- \
  /usr/bin/python3 "$here/composed_orbit_reference.py" "$scene" --sweep "$out/sweep_omega.csv" --values 3 --tol 2e-7
echo "composed sweep: every orbit at the three values agrees with the fixed-frame reference"
