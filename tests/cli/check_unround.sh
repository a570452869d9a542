#!/usr/bin/env bash
# Usage: check_unround.sh BINARY SOURCE_DIR
# The unround race on the command line (docs/model.md §11):
#  1. a [race] whose amplitudes are all zero is the round race: `equilibria` output
#     (table, CSV, JSON) byte-identical to the same scene without [race];
#  2. an eccentric race (order 1, offset d = l eps) leaves the best stable state's
#     residual whirl |q| = d (JSON best_stable.q_abs) to 1e-12 relative;
#  3. the same run twice gives the same bytes; -o writes the file atomically;
#  4. `continue --param omega`, `basin` refuse an unround scene (exit 2 with the
#     reason), never computing the round race silently;
#  8. four balls: equilibria by multistart, JSON search.complete false with the reason;
#  6. `sweep` on a zero-amplitude race is the round scene's sweep byte for byte; an
#     unroundness sweep of the eccentric race leaves |q| = e d at every factor e (1e-12);
#     `continue --param unroundness` keeps |q| = e d along the branch of the balanced state;
set -u
bin=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
check() { if [ "$1" = ok ]; then echo "ok    $2"; else echo "FAIL  $2"; fail=1; fi; }

mkdir -p "$work/a" "$work/b"
cp "$src/data/scenes/default.toml" "$work/a/s.toml"
{ cat "$src/data/scenes/default.toml"; printf '\n[race]\nunroundness = [{ order = 2, amplitude = 0.0, phase = 0.3 }]\n'; } > "$work/b/s.toml"
for fmt in table csv json; do
  (cd "$work/a" && "$bin" equilibria s.toml --format $fmt > out.$fmt 2>&1)
  (cd "$work/b" && "$bin" equilibria s.toml --format $fmt > out.$fmt 2>&1)
  if cmp -s "$work/a/out.$fmt" "$work/b/out.$fmt"; then check ok "zero amplitude = round race ($fmt)"; else check no "zero amplitude = round race ($fmt)"; fi
done

{ cat "$src/data/scenes/default.toml"; printf '\n[race]\nunroundness = [{ order = 1, amplitude = 2e-4, phase = 0.7 }]\n'; } > "$work/ecc.toml"
"$bin" equilibria "$work/ecc.toml" --format json > "$work/ecc.json" || check no "eccentric race runs"
q=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["best_stable"]["q_abs"]["value"])' "$work/ecc.json")
if /usr/bin/python3 -c 'import sys; q=float(sys.argv[1]); d=0.018*2e-4; sys.exit(0 if abs(q-d) <= 1e-12*d else 1)' "$q"; then
  check ok "eccentric race: |q| = d ($q)"
else
  check no "eccentric race: |q| = d (got $q)"
fi
mkdir -p "$work/d1" "$work/d2"
(cd "$work/d1" && "$bin" equilibria ../ecc.toml --format csv -o e.csv) && (cd "$work/d2" && "$bin" equilibria ../ecc.toml --format csv -o e.csv)
if cmp -s "$work/d1/e.csv" "$work/d2/e.csv"; then check ok "deterministic CSV"; else check no "deterministic CSV"; fi

# (`basin` runs on an unround race: tests/cli/check_basin_unround.py.)
for cmd in "continue --param omega --to 1000 -o $work/co"; do
  "$bin" ${cmd%% *} "$work/ecc.toml" ${cmd#* } > /dev/null 2> "$work/err"
  rc=$?
  if [ $rc -eq 2 ] && grep -q "unround" "$work/err"; then check ok "${cmd%% *} refuses an unround scene"; else check no "${cmd%% *} refuses an unround scene (exit $rc: $(head -c 300 "$work/err"))"; fi
done
# 5. the search over the torus is complete (no unresolved leaf, index sum 0) on the
#    reference scenes: "every equilibrium" is then a claim the output makes.
for scene in "$src"/tests/scenes/unround/*.toml; do
  if "$bin" equilibria "$scene" 2> /dev/null | grep -q "unresolved, index sum 0: complete"; then
    check ok "complete search: $(basename "$scene")"
  else
    check no "complete search: $(basename "$scene")"
  fi
done

# 6. sweeps and continuation (model.md §11.10)
(cd "$work/a" && "$bin" sweep s.toml --param omega --from 300 --to 1200 --steps 6 --no-chart -o sw > /dev/null 2>&1)
(cd "$work/b" && "$bin" sweep s.toml --param omega --from 300 --to 1200 --steps 6 --no-chart -o sw > /dev/null 2>&1)
if [ -s "$work/a/sw/sweep_omega.csv" ] && diff -r "$work/a/sw" "$work/b/sw" > /dev/null; then
  check ok "sweep: zero amplitude = round race (bytes)"
else
  check no "sweep: zero amplitude = round race (bytes)"
fi
"$bin" sweep "$work/ecc.toml" --param unroundness --from 0.25 --to 2 --steps 7 --no-chart -o "$work/esw" > /dev/null 2>&1
if /usr/bin/python3 - "$work/esw/summary_unroundness.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))
d = 0.018 * 2e-4
bad = [r for r in rows if abs(float(r["best_q_abs"]) - float(r["unroundness"]) * d) > 1e-12 * float(r["unroundness"]) * d]
sys.exit(0 if len(rows) == 8 and not bad else 1)
PY
then check ok "unroundness sweep: eccentric race |q| = e d at 8 factors"; else check no "unroundness sweep: eccentric race |q| = e d at 8 factors"; fi
"$bin" continue "$work/ecc.toml" --param unroundness --to 2 --no-chart -o "$work/eco" > /dev/null 2>&1
if /usr/bin/python3 - "$work/eco/branch_unroundness.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))
d = 0.018 * 2e-4
# the branches on which |q| = e d holds at the first point off e = 0: the balanced states'
on = {r["branch"] for r in rows if float(r["unroundness"]) > 0 and abs(float(r["q_abs"]) - float(r["unroundness"]) * d) <= 1e-12 * float(r["unroundness"]) * d}
pts = [r for r in rows if r["branch"] in on]
ok = len(on) >= 1 and all(abs(float(r["q_abs"]) - float(r["unroundness"]) * d) <= 1e-12 * float(r["unroundness"]) * d + 1e-18 for r in pts)
ok = ok and max(float(r["unroundness"]) for r in pts) == 2.0
sys.exit(0 if ok else 1)
PY
then check ok "continuation: eccentric race |q| = e d along the balanced branch up to e = 2"; else check no "continuation: eccentric race |q| = e d along the balanced branch up to e = 2"; fi
# 7. a map over (omega, unroundness): the same bytes on 1 and 2 threads; the eccentric
#    race's design figure |q| = e d in every cell (model.md §11.10)
for t in 1 2; do
  "$bin" map "$work/ecc.toml" --x omega:400:1200:3 --y unroundness:0.5:1.5:3 --threads $t --quiet --no-chart -o "$work/map$t" > /dev/null 2>&1
done
if [ -s "$work/map1/summary_omega_unroundness.csv" ] && cmp -s "$work/map1/summary_omega_unroundness.csv" "$work/map2/summary_omega_unroundness.csv"; then
  check ok "unround map: 1 and 2 threads give the same bytes"
else
  check no "unround map: 1 and 2 threads give the same bytes"
fi
if /usr/bin/python3 - "$work/map1/summary_omega_unroundness.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))
d = 0.018 * 2e-4
ok = len(rows) == 9 and all(abs(float(r["best_q_abs"]) - float(r["unroundness"]) * d) <= 1e-12 * float(r["unroundness"]) * d for r in rows)
sys.exit(0 if ok else 1)
PY
then check ok "unround map: eccentric race |q| = e d in 9 cells"; else check no "unround map: eccentric race |q| = e d in 9 cells"; fi
# 8. n = 4 (model.md §11.11): not proven complete, and the output says so
sed 's/^count = 11 /count = 4 /' "$src/data/scenes/ring11.toml" > "$work/r4.toml"
printf '\n[race]\nunroundness = [{ order = 2, amplitude = 1e-6, phase = 0.3 }]\n' >> "$work/r4.toml"
if "$bin" equilibria "$work/r4.toml" --format json 2> /dev/null | /usr/bin/python3 -c '
import json, sys
d = json.load(sys.stdin)
s = d["search"]
sys.exit(0 if d["balls"] == 4 and s["complete"] is False and "not proven complete" in s["doubt"] and len(d["equilibria"]) > 0 else 1)'
then check ok "four balls: equilibria found, complete: false with the reason"; else check no "four balls: equilibria found, complete: false with the reason"; fi
exit $fail
