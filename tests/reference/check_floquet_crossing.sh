#!/bin/sh
# Usage: check_floquet_crossing.sh BINARY SCENE FROM TO STEPS [continue]
# The unit-circle crossings located by `BINARY sweep SCENE --param omega` (or, with
# `continue`, by `BINARY continue SCENE --param omega --to FROM` along the balanced branches
# from the scene's omega) on an anisotropic support against floquet_crossing_reference.py
# (independent J(t) and scipy monodromy): |ln max|rho|| <= 1e-9 at each located omega*, and a
# sign change over omega* (1 -+ 1e-4).
set -eu
binary=$1; scene=$2; from=$3; to=$4; steps=$5; mode=${6:-sweep}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ "$mode" = continue ]; then
  "$binary" continue "$scene" --param omega --to "$from" --no-chart -o "$tmp"
else
  "$binary" sweep "$scene" --param omega --from "$from" --to "$to" --steps "$steps" --no-chart -o "$tmp"
fi
exec /usr/bin/python3 "$(dirname "$0")/floquet_crossing_reference.py" "$scene" "$tmp/floquet_crossings_omega.csv" --tol 1e-9
