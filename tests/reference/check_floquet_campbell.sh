#!/bin/sh
# Usage: check_floquet_campbell.sh BINARY SCENE
# The Campbell view of `BINARY sweep SCENE --param omega` on an anisotropic support
# (docs/model.md §10.15) against floquet_campbell_reference.py (independent J(t), scipy
# monodromy, harmonics by FFT of the integrated Floquet solution) at two speeds: one inside
# the window between the support's principal critical speeds (step 5: 225 rad/s) and one far
# above (step 32: 900 rad/s); every row's fixed-frame eigenvalue to 1e-7 omega, zeta to 1e-7,
# shares to 1e-6. Also: the CSV's rows per speed are the modes of every balanced state, and
# --units rpm gives the same rows with `speed` in rpm.
set -eu
binary=$1; scene=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$binary" sweep "$scene" --param omega --from 100 --to 1100 --steps 40 --no-chart -o "$tmp/a"
test -s "$tmp/a/campbell_omega.csv"
"$binary" sweep "$scene" --units rpm --param omega --from 954.9296585513721 --to 10504.226244065092 --steps 40 \
  --no-chart -o "$tmp/rpm"
/usr/bin/python3 - "$tmp/a/campbell_omega.csv" "$tmp/rpm/campbell_omega.csv" <<'PY'
import csv, math, sys
def rows(p):
    return list(csv.DictReader(l for l in open(p) if not l.startswith("#")))
a, b = rows(sys.argv[1]), rows(sys.argv[2])
assert len(a) == len(b) and a, (len(a), len(b))
for x, y in zip(a, b):
    assert abs(float(x["omega"]) - float(y["omega"])) <= 1e-9 * float(x["omega"]), (x["omega"], y["omega"])
    assert abs(float(y["speed"]) - float(x["omega"]) * 30 / math.pi) <= 1e-9 * float(y["speed"]), y
    assert abs(float(x["whirl_frequency"]) - float(y["whirl_frequency"])) <= 1e-6 * float(x["omega"]), (x, y)
print(f"ok: {len(a)} Campbell rows, rad/s and rpm agree")
PY
/usr/bin/python3 "$(dirname "$0")/floquet_campbell_reference.py" "$scene" "$tmp/a/campbell_omega.csv" 5
exec /usr/bin/python3 "$(dirname "$0")/floquet_campbell_reference.py" "$scene" "$tmp/a/campbell_omega.csv" 32
