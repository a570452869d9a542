#!/bin/sh
# `simulate` on composed machines (docs/model.md §20) against the independent fixed-frame
# Lagrangian of composed_simulation_reference.py: an unround race on an anisotropic support at
# constant speed and through a ramp (the support's angle theta(t) across the breakpoint), three
# balls with per-ball paths on an anisotropic support, and the anisotropic support alone on a
# round race. rtol 1e-10 in the C++ run; the samples must agree to 1e-7 (scaled: q / L, angles
# in rad) over 0.3 s (measured ~1e-10). Usage: check_composed_simulation.sh BINARY SCENES_DIR
set -eu
bin=$1
scenes=$2
here=$(dirname "$0")
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() {  # scene balls [--ramp R]
  scene=$1; balls=$2; shift 2
  "$bin" simulate "$scene" --balls "$balls" --t-end 0.3 --rtol 1e-10 -o "$out/run" --no-chart --quiet "$@"
  # (verdict_cache.py: in CI, a CSV byte-identical to one that passed earlier in the run passes.)
  /usr/bin/python3 "$here/verdict_cache.py" "$out/run/simulation.csv" -- \
    /usr/bin/python3 "$here/composed_simulation_reference.py" "$scene" --csv "$out/run/simulation.csv" --tol 1e-7 "$@"
}
run "$scenes/composed/oval_anisotropic.toml" 0.5,2.5
run "$scenes/composed/oval_anisotropic.toml" 0.5,2.5 --ramp 300:1100:4000
run "$scenes/composed/three_balls_oval_anisotropic.toml" 0.3,2.0,4.1
run "$scenes/anisotropic/ref_viscous.toml" 0.3,2.0
echo "composed simulation: all runs agree with the fixed-frame reference"
