#!/usr/bin/env bash
# Usage: check_specification.sh BINARY SOURCE_DIR
# Balls and race as an engineer specifies them (docs/model.md §1.1), on the command line:
#  1. data/scenes/engineer.toml (diameter, density, f, surface_radius) gives the same
#     `equilibria` bytes (table, CSV, JSON; header and parameter lines aside) as the same
#     scene written with mass, radius, mu, race_radius, whose values this script computes
#     from (1.1.1)-(1.1.3) itself;
#  2. `--set r=...` changes the output when f is given (mu = f / r), and changes nothing
#     but the header of the direct-form scene (r enters nothing there, model.md §1);
#  3. the derived values are in every header: the CSV comment, the table, JSON parameters;
#     a direct-form scene's header has no such line (its bytes are unchanged).
set -u
bin=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail=0
check() { if [ "$1" = ok ]; then echo "ok    $2"; else echo "FAIL  $2"; fail=1; fi; }

eng="$src/data/scenes/engineer.toml"
# The direct form: m = rho pi d^3/6, r = d/2, mu = f/r, l = R_s - r, printed with repr
# (shortest round trip), so the parser reads the same doubles back.
/usr/bin/python3 - "$eng" > "$work/direct.toml" <<'PY'
import math, sys, tomllib
s = tomllib.load(open(sys.argv[1], "rb"))
out = ["rolling = true", "[rotor]"] + [f"{k} = {v!r}" for k, v in s["rotor"].items()]
for b in s["ball"]:
    d, rho, R = b["diameter"], b.get("density", 7850.0), b["surface_radius"]
    r = d / 2
    m = rho * 4.0 / 3.0 * math.pi * r * r * r   # (1.1.1), in the order the model evaluates it
    out += ["[[ball]]", f"mass = {m!r}", f"radius = {r!r}", f"race_radius = {R - r!r}"]
fr = s["friction"]
mu = fr["f"] / (s["ball"][0]["diameter"] / 2)
out += ["[friction]", f'law = "{fr["law"]}"', f"mu = {mu!r}", f"kappa = {fr['kappa']!r}", "[speed]", f"omega = {s['speed']['omega']!r}"]
print("\n".join(out))
PY
body() {  # the output without what names the scene and its parameters
  grep -v -e '^#' -e '"parameters"' -e '"command"' -e '"scene"' -e '^balls as specified' "$1"
}
for fmt in table csv json; do
  "$bin" equilibria "$eng" --format $fmt > "$work/e.$fmt" 2> "$work/e.err" || check no "engineer scene runs ($fmt): $(cat "$work/e.err")"
  "$bin" equilibria "$work/direct.toml" --format $fmt > "$work/d.$fmt" 2> "$work/d.err" || check no "direct scene runs ($fmt)"
  if cmp -s <(body "$work/e.$fmt") <(body "$work/d.$fmt"); then check ok "engineer form = direct form ($fmt)"; else
    check no "engineer form = direct form ($fmt)"; diff <(body "$work/e.$fmt") <(body "$work/d.$fmt") | head -5; fi
done
grep -q '^# derived from the specification (model.md §1.1): m1=rho1\*pi\*(2\*r1)^3/6=' "$work/e.csv" && check ok "CSV header shows the derivation" || check no "CSV header shows the derivation"
grep -q '^balls as specified (model.md §1.1): .*mu2=f2/r2=0.00125' "$work/e.table" && check ok "table header shows mu = f/r" || check no "table header shows mu = f/r"
grep -q '"parameters": ".* rho1=7850 R_s1=0.05 .*f1=5e-06' "$work/e.json" && check ok "JSON parameters name rho, R_s, f" || check no "JSON parameters name rho, R_s, f"
grep -q -e 'specification' -e 'R_s1' "$work/d.csv" && check no "direct form header unchanged" || check ok "direct form header unchanged"

"$bin" equilibria "$eng" --format csv --set r=0.005 > "$work/e5.csv" 2> "$work/e.err" || check no "--set r runs"
if cmp -s <(body "$work/e.csv") <(body "$work/e5.csv"); then check no "--set r=0.005 changes the engineer scene's output"; else
  check ok "--set r=0.005 changes the engineer scene's output"; fi
grep -q 'mu1=f1/r1=0.001 ' "$work/e5.csv" && check ok "--set r=0.005 gives mu = f/r = 0.001" || check no "--set r=0.005 gives mu = f/r = 0.001"
"$bin" equilibria "$work/direct.toml" --format csv --set r=0.005 > "$work/d5.csv" 2> "$work/d.err" || check no "--set r runs (direct)"
if cmp -s <(body "$work/d.csv") <(body "$work/d5.csv"); then check ok "--set r changes nothing in the direct form"; else
  check no "--set r changes nothing in the direct form"; fi

[ $fail -eq 0 ] && echo "all passed"
exit $fail
