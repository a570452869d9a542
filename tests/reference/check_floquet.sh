#!/bin/sh
# Usage: check_floquet.sh BINARY SCENE [--rtol R]
# The balanced state's Floquet multipliers of `BINARY equilibria SCENE --format json`
# against the independent 30-digit Radau IIA monodromy of mp_floquet.py (docs/model.md §10.7).
set -eu
binary=$1; scene=$2; shift 2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$binary" equilibria "$scene" --format json --no-periodic-orbits -o "$tmp/out.json"
exec /usr/bin/python3 "$(dirname "$0")/mp_floquet.py" "$scene" --json "$tmp/out.json" "$@"
