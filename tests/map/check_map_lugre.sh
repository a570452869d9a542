#!/usr/bin/env bash
# `map` of a LuGre scene (model.md §12.8): the same bytes for 1 and 2 threads; every cell's
# equilibria and spectral abscissae equal what `sweep` gives at the cell's parameters (the
# sweep is checked against the 90-digit reference, reference_lugre/sweep_*), so a cell
# judged by another law's linearization would differ by O(1); no fold/Hopf boundaries.
#   check_map_lugre.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
scene=$src/tests/scenes/lugre/two_balls.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"
rows() { grep -v '^#' "$1" | tail -n +2; }
X=omega:150:900:6
Y=sigma0:1e-3:200:5:log
map() { "$bin" map "$scene" --x "$X" --y "$Y" --no-chart --quiet --long "$@"; }

map --threads 1 -o "$work/t1"
check "1-thread map exits 0" "[ $? -eq 0 ]"
map --threads 2 -o "$work/t2"
check "2-thread map exits 0" "[ $? -eq 0 ]"
check "long csv: 1 and 2 threads give the same bytes" "cmp -s '$work/t1/map_omega_sigma0.csv' '$work/t2/map_omega_sigma0.csv'"
check "summary: 1 and 2 threads give the same bytes" "cmp -s '$work/t1/summary_omega_sigma0.csv' '$work/t2/summary_omega_sigma0.csv'"
check "the header says how a LuGre cell is judged" "grep -q '^# friction lugre (model.md §12.8)' '$work/t1/summary_omega_sigma0.csv'"
check "no boundary file (continuation of LuGre branches not implemented)" "[ ! -e '$work/t1/boundary_omega_sigma0.csv' ]"
check "no nan or inf" "! rows '$work/t1/map_omega_sigma0.csv' | grep -qiE 'nan|inf'"

# Cells against `sweep --param omega` at each sigma0 of the map: the same equilibria
# (family, member, |q|) and abscissae to 1e-9 relative (both are (12.10) with c = 1 in long
# double; the sweep's routes are cross-checked).
long=$work/t1/map_omega_sigma0.csv
ok=1
for s0 in $(rows "$long" | cut -d, -f4 | sort -u); do
  "$bin" sweep "$scene" --param omega --from 150 --to 900 --steps 5 --set sigma0="$s0" -o "$work/sw" >/dev/null 2>&1 || ok=0
  /usr/bin/python3 - "$long" "$work/sw/sweep_omega.csv" "$s0" <<'PY' || ok=0
import csv, sys
long_path, sweep_path, s0 = sys.argv[1], sys.argv[2], float(sys.argv[3])
read = lambda p: list(csv.DictReader(l for l in open(p) if not l.startswith("#")))
cells = [r for r in read(long_path) if float(r["sigma0"]) == s0]
sweep = read(sweep_path)
bad = 0
for r in cells:
    w = float(r["omega"])
    ref = [s for s in sweep if float(s["omega"]) == w and s["family"] == r["family"] and s["member"] == r["member"]
           and (r["family"] != "aligned" or s["pattern"] == r["pattern"])]
    if len(ref) != 1:
        print(f"sigma0={s0} omega={w} {r['family']} {r['pattern']} {r['member']}: {len(ref)} sweep rows"); bad += 1; continue
    a, b = float(r["spectral_abscissa"]), float(ref[0]["spectral_abscissa"])
    if abs(a - b) > 1e-9 * max(abs(b), 1e-300) or int(r["stable"]) != int(ref[0]["stable"]):
        print(f"sigma0={s0} omega={w} {r['family']}: map abscissa {a} stable {r['stable']}, sweep {b} {ref[0]['stable']}"); bad += 1
n = sum(1 for s in sweep)
if len(cells) != n:
    print(f"sigma0={s0}: {len(cells)} map rows, {n} sweep rows"); bad += 1
sys.exit(1 if bad else 0)
PY
done
check "every cell's equilibria and abscissae equal the sweep's (1e-9)" "[ $ok -eq 1 ]"
finish
