#!/bin/sh
# `equilibria` on an unround race with an anisotropic support (docs/model.md §20.4): every
# periodic orbit of its JSON found again by single shooting on the independent fixed-frame
# Lagrangian (composed_orbit_reference.py): x(0) and all multipliers to 1e-6 (measured: x(0)
# already closes the reference's orbit to 1e-12, the multipliers agree to 6e-8, the limit of
# the reference's difference-quotient monodromy). Usage: check_composed_orbits.sh BINARY SCENES_DIR
set -eu
bin=$1
scenes=$2
here=$(dirname "$0")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for scene in oval_anisotropic three_balls_oval_anisotropic; do
  "$bin" equilibria "$scenes/composed/$scene.toml" --format json > "$out/$scene.json"
  /usr/bin/python3 "$here/verdict_cache.py" "$out/$scene.json" -- \
    /usr/bin/python3 "$here/composed_orbit_reference.py" "$scenes/composed/$scene.toml" --json "$out/$scene.json" --tol 1e-6
done
echo "composed orbits: every orbit agrees with the fixed-frame reference"
