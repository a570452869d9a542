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
  /usr/bin/python3 "$here/composed_stick_reference.py" "$scenes/composed/$scene.toml" --json "$out/$scene.json"
done
