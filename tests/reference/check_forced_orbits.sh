#!/bin/sh
# Usage: check_forced_orbits.sh BINARY SCENE [--stiff] [--rtol R] [--orbit K]
# The periodic orbits of the non-balanced states in `BINARY equilibria SCENE --format json`
# against the independent single-shooting solver forced_orbit_reference.py (docs/model.md §10.14),
# or with --stiff (first argument after SCENE) forced_orbit_stiff_reference.py (§10.19).
set -eu
binary=$1; scene=$2; shift 2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$binary" equilibria "$scene" --format json -o "$tmp/out.json"
script=forced_orbit_reference.py
if [ "${1:-}" = "--stiff" ]; then script=forced_orbit_stiff_reference.py; shift; fi
/usr/bin/python3 "$(dirname "$0")/$script" "$scene" --json "$tmp/out.json" "$@"
