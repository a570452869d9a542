#!/usr/bin/env bash
# Usage: check_shaft.sh BINARY SOURCE_DIR
#
# The flexible-shaft commands (docs/model.md §18.10-§18.12):
# 1. The rigid reduction from the command line: tests/scenes/shaft/one_node.toml is the
#    default rigid scene as a one-node shaft (a disc on a bearing, plus a tilt pair). Its
#    equilibria must be the rigid scene's (ball angles to 1e-10 rad: both come from the same
#    closed forms, polished), every listed eigenvalue must be a rigid eigenvalue or one of
#    the four tilt eigenvalues of (18.9.1), computed here from the quadratic, to 1e-10 of its
#    modulus (the acceptance's rigid-reduction tolerance; the rigid ones are the analyzer's refined
#    values, good to ~1e-15, and the shaft's are refined at their own eigenvalue, model.md
#    §19.5: measured at most 1e-15 relative, so 1e-10 leaves room for the printed digits and
#    a condition number of 1e5), with residual <= 1e-10, and the verdicts must agree with
#    the rigid analyzer's.
# 2. data/scenes/shaft.toml: table, CSV and JSON, every spectrum converged, no NaN.
# 3. sweep --param omega on the one-node scene with viscous balls (one_node_viscous.toml): the tilt modes' fixed-frame whirl frequencies
#    (signed: forward > 0) are the imaginary parts of the roots mu of (18.9.1), to 1e-8
#    relative, at every speed where they are among the rightmost (this checks the frame
#    conversion and the forward/backward choice of (16.2.1)); CSV and PNG written.
# 4. Commands that do not handle shafts refuse them, exit 2, nothing written; --set k= and a
#    map over the rigid rotor's k (a shaft scene has none) too.
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
work=$(mktemp -d) || exit 2
trap 'rm -rf "$work"' EXIT
fail=0
ok() { echo "ok    $1"; }
bad() { echo "FAIL  $1"; fail=1; }

one="$src/tests/scenes/shaft/one_node.toml"
"$bin" equilibria "$src/data/scenes/default.toml" --format json > "$work/rigid.json" || bad "rigid equilibria"
if "$bin" equilibria "$one" --format json --eigenvalues 10 > "$work/one.json"; then
  python3 - "$work/rigid.json" "$work/one.json" <<'PY' && ok "one-node shaft = rigid rotor + tilt pair (equilibria, eigenvalues, verdicts)" || bad "one-node reduction"
import cmath, json, sys
r = json.load(open(sys.argv[1])); s = json.load(open(sys.argv[2]))
# (18.9.1): I_d mu^2 + (c_psi - i w I_p) mu + k_psi = 0; lambda = mu - i w and its conjugate.
Id, Ip, kp, cp, w = 1.0e-4, 1.5e-4, 50.0, 0.01, 900.0
b = cp - 1j * w * Ip
tilt = []
for sg in (1, -1):
    mu = (-b + sg * cmath.sqrt(b * b - 4 * Id * kp)) / (2 * Id)
    tilt += [mu - 1j * w, (mu - 1j * w).conjugate()]
assert len(r["equilibria"]) == len(s["equilibria"]), "equilibrium count"
checked, worst = 0, 0.0
for er, es in zip(r["equilibria"], s["equilibria"]):
    assert er["family"] == es["family"] and er["pattern"] == es["pattern"], (er["family"], es["family"])
    for k in range(2):
        d = abs(cmath.exp(1j * er["beta%d" % (k + 1)]) - cmath.exp(1j * es["beta"][k]))
        assert d < 1e-10, ("beta", d)
    assert abs(er["q_abs"] - es["q_abs"]) <= 1e-10 * max(er["q_abs"], 1e-12), ("q_abs", er["q_abs"], es["q_abs"])
    assert (er["stability"] == "stable") == (es["verdict"] == "stable"), (er["stability"], es["verdict"])
    assert es["spectrum"]["status"] == "converged", es["spectrum"]["reason"]
    rigid = [complex(x["re"], x["im"]) for x in er["eigenvalues"]]
    for x in es["spectrum"]["eigenvalues"]:
        z = complex(x["re"], x["im"])
        dist = min(abs(z - v) for v in rigid + tilt) / abs(z)
        assert dist <= 1e-10, ("eigenvalue", z, dist)
        assert x["residual"] <= 1e-10, ("residual", z, x["residual"])
        worst = max(worst, dist)
        checked += 1
assert checked >= 6, checked
print("      %d eigenvalues matched (1e-10 relative), largest difference %.2g of the modulus" % (checked, worst))
PY
else
  bad "one-node equilibria exit code"
fi

for fmt in table csv json; do
  if "$bin" equilibria "$src/data/scenes/shaft.toml" --format $fmt > "$work/shaft.$fmt" 2> "$work/err"; then
    if grep -qi 'nan' "$work/shaft.$fmt"; then bad "shaft.toml --format $fmt has NaN"; else ok "shaft.toml --format $fmt"; fi
  else
    bad "shaft.toml --format $fmt exit code"
  fi
done
python3 - "$work/shaft.json" <<'PY' && ok "shaft.toml JSON: spectra converged, balanced states stable, q = 0 there" || bad "shaft.toml JSON"
import json, sys
d = json.load(open(sys.argv[1]))
assert d["frame"] == "rotating" and d["shaft"]["nodes"] == 13, d["shaft"]
for e in d["equilibria"]:
    assert e["spectrum"]["status"] == "converged"
    assert all(s["nconv"] == s["requested"] for s in e["spectrum"]["shifts"])
    if e["family"] == "balanced":
        assert e["q_abs"] == 0 and e["max_deflection"] == 0 and e["verdict"] == "stable", e
PY

# Very soft undamped bearings (1 N/m, no damping): the rigid whirl at omega in the rotating
# frame is nearly defective (condition ~3e4), and the two mirror balanced states, whose
# spectra are the same, came out "stable" (Re -1.8e-9) and "undetermined" (Re +7.4e-11)
# from a bound of residual times |lambda| (1.4e-10) that left out the condition. The bound
# now includes it (model.md §19.3): both are undetermined, and say why.
sed 's/^stiffness = 5.0e7 .*/stiffness = 1.0/; s/^damping = 500.0 .*/damping = 0.0/' "$src/data/scenes/shaft.toml" \
  > "$work/soft_bearings.toml"
"$bin" equilibria "$work/soft_bearings.toml" --format json > "$work/soft.json" 2> "$work/err"
python3 - "$work/soft.json" <<'PY' && ok "soft bearings: mirror balanced states get the same verdict, undetermined by the eigenvalue's condition" || bad "soft bearings mirror verdicts"
import json, re, sys
d = json.load(open(sys.argv[1]))
balanced = [e for e in d["equilibria"] if e["family"] == "balanced"]
assert len(balanced) == 2, balanced
for e in balanced:
    assert e["verdict"] == "undetermined", e["verdict_text"]
    c = float(re.search(r"condition ([0-9.e+-]+) times", e["verdict_text"]).group(1))
    assert c > 1e3, e["verdict_text"]
PY

if "$bin" sweep "$src/tests/scenes/shaft/one_node_viscous.toml" --param omega --from 200 --to 2000 --steps 18 -o "$work/camp" 2> "$work/err"; then
  [ -s "$work/camp/campbell_shaft_omega.png" ] || [ -n "${ABU_NO_CHART_CHECK:-}" ] || bad "Campbell PNG missing"
  python3 - "$work/camp/campbell_shaft_omega.csv" <<'PY' && ok "Campbell: tilt whirl frequencies = Im mu of (18.9.1), signed" || bad "Campbell tilt frequencies"
import cmath, csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
Id, Ip, kp, cp = 1.0e-4, 1.5e-4, 50.0, 0.01
found = 0
for w in sorted({float(r["omega"]) for r in rows}):
    b = cp - 1j * w * Ip
    mus = [(-b + sg * cmath.sqrt(b * b - 4 * Id * kp)) / (2 * Id) for sg in (1, -1)]
    here = [r for r in rows if float(r["omega"]) == w]
    for mu in mus:
        # the tilt mode's row: its rotating-frame eigenvalue is mu - i w or its conjugate
        lam = [mu - 1j * w, (mu - 1j * w).conjugate()]
        match = [r for r in here if min(abs(complex(float(r["re"]), float(r["im"])) - l) for l in lam) <= 1e-8 * abs(mu)]
        for r in match:
            whirl = float(r["whirl"])
            assert abs(whirl - mu.imag) <= 1e-8 * abs(mu), (w, whirl, mu.imag)
            assert r["direction"] == ("forward" if mu.imag > 0 else "backward")
            found += 1
assert found >= 8, found
print("      %d tilt rows checked" % found)
PY
else
  bad "Campbell sweep exit code: $(head -c 300 "$work/err")"
fi

for cmd in "continue $one --param omega --to 1000 -o $work/c" "map $one --x omega:100:1000:3 --y k:1e4:1e5:3 -o $work/m" \
           "sweep $one --param mu --from 1e-3 --to 1e-2 --steps 3 -o $work/w" \
           "equilibria $one --set k=1e4"; do
  mkdir -p "$work/empty" && (cd "$work/empty" && "$bin" $cmd > "$work/out" 2> "$work/err")
  code=$?
  if [ "$code" -eq 2 ] && [ -z "$(ls -A "$work/empty")" ] && [ ! -e "$work/c" ] && [ ! -e "$work/m" ] && [ ! -e "$work/w" ]; then
    ok "refused (exit 2): ${cmd%% *} ... $(head -c 110 "$work/err" | tr '\n' ' ')"
  else
    bad "${cmd%% *}: exit $code, $(head -c 200 "$work/err")"
  fi
done
exit $fail
