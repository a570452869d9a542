#!/bin/sh
# Usage: check_forced_orbits.sh BINARY SCENE [--rtol R]
# The periodic orbits of the non-balanced states in `BINARY equilibria SCENE --format json`
# against the independent single-shooting solver forced_orbit_reference.py (docs/model.md §10.14).
set -eu
binary=$1; scene=$2; shift 2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$binary" equilibria "$scene" --format json -o "$tmp/out.json"
exec /usr/bin/python3 "$(dirname "$0")/forced_orbit_reference.py" "$scene" --json "$tmp/out.json" "$@"
