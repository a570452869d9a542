#!/usr/bin/env bash
# `map` on a flexible-shaft scene (docs/model.md §18.13, guide §15.1): the balanced state's
# stability over two parameters.
# 1. The same bytes on 1 and 2 threads; an interrupted run resumed equals a fresh run.
# 2. One map cell equals `equilibria` at that cell's parameters (a scene file written with
#    the cell's bearing stiffness and speed): the spectral abscissa over the balanced states,
#    its frequency, the verdict and the covered rectangle, to 1e-9 relative. Both take the
#    balanced angles from the same closed form (model.md §13.2, through rigid equivalents
#    with different supports: rounding only) and run the same ARPACK ladder, so they agree
#    to rounding; 1e-9 leaves room for the slow ball modes near 0 (|lambda| ~ 1e-4 1/s,
#    resolved to ~1e-8 relative, the residual column of `equilibria`).
# 3. A cell without a balanced state (U above the balls' capacity m l sum = 6.58e-4 kg m)
#    says so (state no_balanced_state, verdict none, empty numbers); no NaN anywhere.
# 4. Bad axes: the rigid rotor's k, c, M_r (a shaft scene has none), a bearing number out of
#    range, a negative bearing stiffness, bearings that no longer hold the shaft (k = 0 on
#    both), an unknown name: exit 2, the rule named, nothing written.
# 5. Stability changes along omega (`sweep --param omega`, crossings_shaft_omega.csv, model.md
#    §18.14): on the one-node shaft tests/scenes/shaft/one_node_viscous.toml (a disc on an
#    isotropic bearing: the rigid rotor plus a tilt pair that is damped at every speed,
#    (18.9.1)) the crossing speed and its rotating-frame frequency equal the Hopf point of the
#    rigid analyzer's `continue` on the equivalent rigid scene to 1e-8 relative (the
#    acceptance tolerance against an independent computation; both are solved to ~1e-12);
#    two sweep grids (different brackets) give the same crossing to 1e-10 relative.
#   check_shaft_map.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"
scene="$src/data/scenes/shaft.toml"
csv=shaft_map_omega_bearing_k.csv

# --- threads and resume ---------------------------------------------------------------------
args=(--x omega:500:4000:6 --y bearing_k:1e6:1e8:3:log --quiet)
"$bin" map "$scene" "${args[@]}" --threads 1 -o "$work/t1" 2>"$work/t1.err"
check "map on shaft.toml exits 0" "[ $? -eq 0 ] && [ -s '$work/t1/$csv' ]"
[ -n "${ABU_NO_CHART_CHECK:-}" ] || check "the chart is written" "[ -s '$work/t1/shaft_map_omega_bearing_k.png' ]"
"$bin" map "$scene" "${args[@]}" --threads 2 --no-chart -o "$work/t2" 2>/dev/null
check "2 threads give the same bytes as 1" "cmp -s '$work/t1/$csv' '$work/t2/$csv'"
check "no NaN or inf in the CSV" "! grep -qiE 'nan|inf' '$work/t1/$csv'"
check "every cell has a verdict and converged" \
  "[ \$(grep -v '^#' '$work/t1/$csv' | tail -n +2 | grep -c ',2,converged,\(stable\|unstable\),') -eq 18 ]"

big=(--x omega:500:4000:24 --y bearing_k:1e6:1e8:3:log --quiet --no-chart)
"$bin" map "$scene" "${big[@]}" --threads 1 -o "$work/fresh" 2>/dev/null
"$bin" map "$scene" "${big[@]}" --threads 1 -o "$work/int" 2>/dev/null &
pid=$!
wait_for_tiles "$work/int/.shaft_map_omega_bearing_k.tiles" 3
kill -INT $pid
wait $pid
code=$?
check "SIGINT exits 130" "[ $code -eq 130 ]"
kept=$(tile_count "$work/int/.shaft_map_omega_bearing_k.tiles")
check "SIGINT keeps the finished tiles ($kept of 24)" "[ $kept -ge 3 ] && [ $kept -lt 24 ]"
check "nothing assembled after SIGINT" "[ ! -e '$work/int/$csv' ]"
"$bin" map "$scene" "${big[@]}" --threads 2 -o "$work/int" 2>"$work/refuse.err"
check "a second run without --resume is refused (exit 2)" "[ $? -eq 2 ] && grep -q -- '--resume' '$work/refuse.err'"
"$bin" map "$scene" "${big[@]}" --threads 2 --resume -o "$work/int" 2>/dev/null
check "resume exits 0" "[ $? -eq 0 ]"
check "resumed run equals the fresh run" "cmp -s '$work/fresh/$csv' '$work/int/$csv'"

# --- one cell = equilibria ------------------------------------------------------------------
for cell in "1800 2e7" "1000 5e7"; do
  set -- $cell
  "$bin" map "$scene" --x omega:$1:$1:1 --y bearing_k:$2:$2:1 --quiet --no-chart -o "$work/cell" --fresh 2>/dev/null
  sed -e "s/^stiffness = 5.0e7.*/stiffness = $2/" -e "s/^omega = 2500.0/omega = $1/" "$scene" > "$work/cell.toml"
  "$bin" equilibria "$work/cell.toml" --format json > "$work/cell.json" 2>/dev/null
  python3 - "$work/cell/$csv" "$work/cell.json" <<'PY'
import csv, json, sys
row = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))[0]
d = json.load(open(sys.argv[2]))
bal = [e for e in d["equilibria"] if e["family"] == "balanced"]
assert int(row["balanced"]) == len(bal) > 0, (row["balanced"], len(bal))
best, freq = None, None
for e in bal:
    for x in e["spectrum"]["eigenvalues"]:
        if not x["structural"] and (best is None or x["re"] > best):
            best, freq = x["re"], abs(x["im"])
rel = lambda a, b: abs(a - b) <= 1e-9 * max(abs(a), abs(b), 1e-300)
assert rel(float(row["spectral_abscissa"]), best), (row["spectral_abscissa"], best)
assert abs(float(row["frequency"]) - freq) <= 1e-9 * max(freq, 1.0), (row["frequency"], freq)
verdicts = {e["verdict"] for e in bal}
want = "unstable" if "unstable" in verdicts else "stable" if verdicts == {"stable"} else "undetermined"
assert row["verdict"] == want, (row["verdict"], verdicts)
c = bal[0]["spectrum"]["coverage"]
for k in ("real_min", "real_max", "imag_max"):
    assert rel(float(row["coverage_" + k]), max(e["spectrum"]["coverage"][k] for e in bal) if k == "real_min"
               else min(e["spectrum"]["coverage"][k] for e in bal)), k
print("      abscissa %.12g 1/s, frequency %.12g 1/s, %s" % (best, freq, want))
PY
  check "cell omega=$1 bearing_k=$2 equals equilibria" "[ $? -eq 0 ]"
done

# --- no balanced state ----------------------------------------------------------------------
"$bin" map "$scene" --x omega:2500:3000:2 --y U:1e-4:1e-3:2 --quiet --no-chart -o "$work/u" 2>/dev/null
check "U above capacity: state no_balanced_state, verdict none, empty numbers" \
  "grep -q '^2500,0.001,0,no_balanced_state,none,,,0,,,,,,0,0$' '$work/u/shaft_map_omega_U.csv' && ! grep -qi nan '$work/u/shaft_map_omega_U.csv'"

# --- stability changes along omega = the rigid Hopf point ---------------------------------
one="$src/tests/scenes/shaft/one_node_viscous.toml"
cat > "$work/rigid.toml" <<'TOML'
# one_node_viscous.toml as a rigid rotor: the disc's mass, the bearing's k and c
rolling = true
[rotor]
mass = 0.12
stiffness = 7500.0
damping = 2.0
unbalance = 6.0e-7
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[friction]
law = "viscous"
d = 1.0e-3
[speed]
omega = 900.0
TOML
"$bin" continue "$work/rigid.toml" --param omega --to 50 --from-equilibrium balanced --no-chart -o "$work/rc" >/dev/null 2>&1
"$bin" sweep "$one" --param omega --from 100 --to 1000 --steps 10 --no-chart -o "$work/x1" >/dev/null 2>&1
"$bin" sweep "$one" --param omega --from 120 --to 900 --steps 7 --no-chart -o "$work/x2" >/dev/null 2>&1
python3 - "$work/rc/special_omega.csv" "$work/x1/crossings_shaft_omega.csv" "$work/x2/crossings_shaft_omega.csv" <<'PY'
import csv, sys
rows = lambda f: list(csv.DictReader(l for l in open(f) if not l.startswith("#")))
hopf = [r for r in rows(sys.argv[1]) if r["label"] == "HB" and r["family"] == "balanced"]
assert hopf, "no rigid Hopf point"
w, f = float(hopf[0]["omega"]), float(hopf[0]["frequency"])
for name in sys.argv[2:]:
    c = rows(name)
    assert len(c) == 1 and c[0]["status"] == "converged" and c[0]["change"] == "regains", c
    wc, fc = float(c[0]["omega"]), float(c[0]["im"])
    assert abs(wc - w) <= 1e-8 * w, (wc, w)
    assert abs(fc - f) <= 1e-8 * f, (fc, f)
    assert abs(float(c[0]["re"])) <= 1e-9 * abs(fc), c[0]["re"]
a, b = (float(rows(n)[0]["omega"]) for n in sys.argv[2:])
assert abs(a - b) <= 1e-10 * a, (a, b)
print("      crossing %.15g rad/s (rigid Hopf %.15g), Im lambda %.12g (rigid %.12g) 1/s" % (a, w, fc, f))
PY
check "one-node shaft: crossing = rigid Hopf point (1e-8), grid-independent (1e-10)" "[ $? -eq 0 ]"
"$bin" sweep "$scene" --param omega --from 300 --to 4000 --steps 12 --no-chart -o "$work/x3" >/dev/null 2>&1
check "shaft.toml: one crossing (regains, converged), no NaN" \
  "[ \$(grep -c ',regains,.*,converged$' '$work/x3/crossings_shaft_omega.csv') -eq 1 ] && ! grep -qi nan '$work/x3/crossings_shaft_omega.csv'"

# --- bad axes -------------------------------------------------------------------------------
for y in "k:1e4:1e5:3" "c:1:10:3" "M_r:1:2:2" "bearing3_k:1e6:1e7:2" "bearing_k:-1:1e7:3" "stiffness:1:2:2" \
         "bearing_c:10:10:3" "bearing_k:0:1e7:3"; do
  mkdir -p "$work/empty"
  (cd "$work/empty" && "$bin" map "$scene" --x omega:500:1000:2 --y "$y" -o out > /dev/null 2> "$work/err")
  code=$?
  check "--y $y refused (exit 2, nothing written): $(head -c 140 "$work/err" | tr '\n' ' ')" \
    "[ $code -eq 2 ] && [ -z \"\$(ls -A '$work/empty')\" ] && grep -q -- '--y' '$work/err'"
done
# ARPACK's options on a rigid scene's map: refused, not silently ignored.
mkdir -p "$work/empty2"
(cd "$work/empty2" && "$bin" map "$src/data/scenes/default.toml" --x omega:100:200:2 --y mu:0.001:0.002:2 \
   --eigenvalues 5 -o out > /dev/null 2> "$work/err")
code=$?
check "--eigenvalues on a rigid map refused (exit 2, nothing written)" \
  "[ $code -eq 2 ] && [ -z \"\$(ls -A '$work/empty2')\" ] && grep -q -- 'shaft' '$work/err'"
finish
