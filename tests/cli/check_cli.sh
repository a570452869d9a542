#!/usr/bin/env bash
# The command-line contract of stability-scan: output formats, atomic files,
# bad arguments rejected with exit code 2 and nothing written, same bytes on a re-run.
#   check_cli.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
scene=$src/data/scenes/default.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"

# --- equilibria: CSV shape -------------------------------------------------------------
"$bin" equilibria "$scene" --format csv >"$work/eq.csv" 2>"$work/eq.err"
check "equilibria csv exits 0" "[ $? -eq 0 ]"
header=$(grep -v '^#' "$work/eq.csv" | head -1)
expected="family,pattern,member,q1,q2,beta1,beta2,residual,spectral_abscissa,stable,n_structural_zero"
for k in 1 2 3 4 5 6 7 8; do expected="$expected,re$k,im$k"; done
check "csv header is the documented one" "[ \"$header\" = \"$expected\" ]"
check "default scene has 6 equilibria" "[ $(grep -v '^#' "$work/eq.csv" | tail -n +2 | wc -l) -eq 6 ]"
check "every row has 27 fields" "[ -z \"\$(grep -v '^#' "$work/eq.csv" | awk -F, 'NF != 27')\" ]"
check "no nan or inf in the csv" "! grep -v '^#' '$work/eq.csv' | grep -qiE 'nan|inf'"
check "families in order balanced, together, opposite" \
  "[ \"\$(grep -v '^#' '$work/eq.csv' | tail -n +2 | cut -d, -f1 | uniq | tr '\n' ' ')\" = 'balanced together opposite ' ]"
check "angles in [0, 2pi)" "grep -v '^#' '$work/eq.csv' | tail -n +2 | awk -F, '\$6 < 0 || \$6 >= 6.283185307179586 || \$7 < 0 || \$7 >= 6.283185307179586 {exit 1}'"

# --- other formats, -o -----------------------------------------------------------------
"$bin" equilibria "$scene" --format json >"$work/eq.json"
check "json is valid" "/usr/bin/python3 -m json.tool '$work/eq.json' >/dev/null"
"$bin" equilibria "$scene" >"$work/eq.txt"
check "table names every family" "grep -q 'balanced 1' '$work/eq.txt' && grep -q 'together 2' '$work/eq.txt' && grep -q 'opposite 1' '$work/eq.txt'"
"$bin" equilibria "$scene" --format csv -o "$work/sub/eq.csv"
check "-o writes the file (creating the directory)" "[ -s '$work/sub/eq.csv' ]"
check "-o leaves no temporary behind" "[ \$(ls -A '$work/sub' | wc -l) -eq 1 ]"
check "-o file has the same rows as stdout" "diff <(grep -v '^#' '$work/eq.csv') <(grep -v '^#' '$work/sub/eq.csv') >/dev/null"
"$bin" equilibria "$scene" --format csv --set omega=150 --set mu=0.01 >"$work/set.csv"
check "--set changes the parameters in the header" "grep -q 'omega=150' '$work/set.csv' && grep -q 'mu1=0.01' '$work/set.csv'"

# --- sweep -------------------------------------------------------------------------------
"$bin" sweep "$scene" --param omega --from 100 --to 1000 --steps 30 -o "$work/sweep" 2>"$work/sweep.err"
check "sweep exits 0" "[ $? -eq 0 ]"
check "sweep writes csv, png and the views (campbell, summary)" "[ \"\$(ls '$work/sweep' | tr '\n' ' ')\" = 'campbell_omega.csv campbell_omega.png summary_omega.json sweep_omega.csv sweep_omega.png ' ]"
check "png is a PNG" "[ \"\$(head -c 8 '$work/sweep/sweep_omega.png' | od -An -tx1 | tr -d ' \n')\" = '89504e470d0a1a0a' ]"
check "sweep csv has 31 distinct steps" "[ \$(grep -v '^#' '$work/sweep/sweep_omega.csv' | tail -n +2 | cut -d, -f1 | sort -u | wc -l) -eq 31 ]"
check "sweep csv ends exactly at --to" "grep -v '^#' '$work/sweep/sweep_omega.csv' | cut -d, -f2 | grep -qx 1000"
"$bin" sweep "$scene" --param mu --from 1e-4 --to 1e-1 --steps 6 --log --no-chart -o "$work/mu"
check "log sweep of mu, no chart" "[ -s '$work/mu/sweep_mu.csv' ] && [ ! -e '$work/mu/sweep_mu.png' ]"
"$bin" sweep "$scene" --param omega --from 100 --to 1000 --steps 30 -o "$work/sweep2" 2>/dev/null
check "same input, same bytes (csv)" "cmp -s <(grep -v '^# command' '$work/sweep/sweep_omega.csv') <(grep -v '^# command' '$work/sweep2/sweep_omega.csv')"

# --- continue ------------------------------------------------------------------------
"$bin" continue "$scene" --set omega=200 --param omega --to 400 -o "$work/cont" 2>"$work/cont.err"
check "continue exits 0" "[ $? -eq 0 ]"
check "continue writes branch, special points and chart" \
  "[ \"\$(ls '$work/cont' | tr '\n' ' ')\" = 'bifurcation_omega.png branch_omega.csv campbell_omega.csv campbell_omega.png special_omega.csv summary_omega.json ' ]"
check "special points: LP and HB found between 200 and 400 rad/s" \
  "grep -q '^[0-9]*,LP,' '$work/cont/special_omega.csv' && grep -q '^[0-9]*,HB,' '$work/cont/special_omega.csv'"
check "branch csv has the tracked-eigenvalue columns" "grep -v '^#' '$work/cont/branch_omega.csv' | head -1 | grep -q ',n_unstable,re1,im1,'"
check "no nan in the continuation csvs" "! grep -v '^#' '$work/cont/branch_omega.csv' '$work/cont/special_omega.csv' | grep -qi nan"
# Values not defined at a point are empty fields, never a sentinel 0 (README, Outputs):
# frequency only on HB rows, lyapunov only on located HB rows; both set there.
fields() {  # CSV, then a Python condition on row r (a dict by header name): 0 if it holds for every row
  /usr/bin/python3 -c 'import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#")))
sys.exit(0 if rows and all(eval(sys.argv[2], {"r": r}) for r in rows) else 1)' "$1" "$2"
}
check "special points: frequency and lyapunov empty off HB rows" \
  "fields '$work/cont/special_omega.csv' 'r[\"label\"] == \"HB\" or (r[\"frequency\"] == \"\" and r[\"lyapunov\"] == \"\")'"
check "special points: HB rows have a positive frequency and a lyapunov coefficient" \
  "fields '$work/cont/special_omega.csv' 'r[\"label\"] != \"HB\" or (float(r[\"frequency\"]) > 0 and r[\"lyapunov\"] != \"\")'"
check "plots address columns by name (no positional using N:)" "! grep -nE 'using +[0-9]|column\\([0-9]' '$src/plots/bifurcation.gp' '$src/plots/boundary.gp'"
"$bin" continue "$scene" --set omega=200 --param omega --to 400 --from-equilibrium balanced --no-chart -o "$work/cb"
check "--from-equilibrium balanced continues only balanced branches" \
  "fields '$work/cb/branch_omega.csv' 'r[\"family\"] == \"balanced\"'"
"$bin" continue "$scene" --set omega=200 --param omega --to 400 --param2 mu --to2 0.004 -o "$work/c2" 2>/dev/null
check "two-parameter run writes the boundary csv and chart" "[ -s '$work/c2/boundary_omega_mu.csv' ] && [ -s '$work/c2/boundary_omega_mu.png' ]"
check "boundary: frequency empty on fold curves, positive on Hopf curves" \
  "fields '$work/c2/boundary_omega_mu.csv' '(r[\"frequency\"] == \"\") if r[\"kind\"] == \"LP\" else float(r[\"frequency\"]) > 0'"
"$bin" continue "$scene" --set omega=200 --param omega --to 400 --max-steps 2 --no-chart -o "$work/cmx" 2>"$work/cmx.err"
check "a branch stopped early says so on stderr and in the csv" \
  "grep -q 'maximum number of steps' '$work/cmx.err' && grep -q 'maximum number of steps' '$work/cmx/branch_omega.csv'"
check "MX rows: frequency, re, im, lyapunov, converged empty" \
  "grep -q '^[0-9]*,MX,' '$work/cmx/special_omega.csv' && fields '$work/cmx/special_omega.csv' 'r[\"label\"] != \"MX\" or all(r[k] == \"\" for k in (\"frequency\", \"re\", \"im\", \"lyapunov\", \"converged\"))'"

# --- bad input: exit 2, message, nothing written ----------------------------------------
bad() {  # name, then the arguments; run in an empty directory with -o inside it
  local name=$1; shift
  local dir=$work/bad.$RANDOM
  mkdir -p "$dir"
  (cd "$dir" && "$bin" "$@" >"$work/out" 2>"$work/err")
  local rc=$?
  if [ $rc -ne 2 ]; then fail "$name: exit $rc, want 2"; return; fi
  if [ ! -s "$work/err" ]; then fail "$name: no message"; return; fi
  if [ -n "$(ls -A "$dir")" ]; then fail "$name: wrote $(ls -A "$dir")"; return; fi
  pass "$name: exit 2 ($(head -1 "$work/err" | cut -c1-90))"
}
bad "no subcommand"             equilibria
bad "unknown subcommand"        frobnicate "$scene"
bad "unknown format"            equilibria "$scene" --format xml -o out.csv
bad "missing scene file"        equilibria nosuch.toml -o out.csv
bad "--set unknown name"        equilibria "$scene" --set zeta=1 -o out.csv
bad "--set malformed"           equilibria "$scene" --set omega -o out.csv
bad "--set non-finite"          equilibria "$scene" --set omega=nan -o out.csv
bad "--set out of range"        equilibria "$scene" --set m=-1 -o out.csv
bad "--set law mismatch"        equilibria "$scene" --set d=1 -o out.csv
bad "sweep unknown param"       sweep "$scene" --param zeta --from 1 --to 2 --steps 3 -o o
bad "sweep steps 0"             sweep "$scene" --param omega --from 1 --to 2 --steps 0 -o o
bad "sweep absurd steps"        sweep "$scene" --param omega --from 1 --to 2 --steps 2000000000 -o o
bad "sweep crosses mass 0"      sweep "$scene" --param m --from 0 --to 1e-4 --steps 3 -o o
bad "sweep negative omega"      sweep "$scene" --param omega --from -100 --to 100 --steps 3 -o o
bad "sweep log through 0"       sweep "$scene" --param U --from 0 --to 1e-6 --steps 3 --log -o o
bad "sweep param not in law"    sweep "$scene" --param d --from 0 --to 1 --steps 3 -o o
bad "sweep r above l"           sweep "$scene" --param r --from 1e-3 --to 0.05 --steps 3 -o o
bad "sweep missing --to"        sweep "$scene" --param omega --from 1 --steps 3 -o o
bad "continue unknown param"    continue "$scene" --param zeta --to 1 -o o
bad "continue to an invalid value" continue "$scene" --param omega --to -5 -o o
bad "continue to the start value" continue "$scene" --param omega --to 900 -o o
bad "continue in r"             continue "$scene" --param r --to 2e-3 -o o
bad "continue bad ds"           continue "$scene" --param omega --to 1000 --ds 0 -o o
bad "continue ds-max too large" continue "$scene" --param omega --to 1000 --ds-max 2 -o o
bad "continue param2 = param"   continue "$scene" --param omega --to 1000 --param2 omega --to2 5 -o o
bad "continue bad from-state"   continue "$scene" --param omega --to 1000 --from-state 1,2,3 -o o
bad "continue both family and state" continue "$scene" --param omega --to 1000 --from-equilibrium balanced --from-state 0,0,1,2 -o o
cat >"$work/three.toml" <<'TOML'
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
[[ball]]
mass = 3.3e-5
race_radius = 0.018
radius = 1.0e-3
[friction]
law = "none"
[speed]
omega = 900.0
TOML
"$bin" equilibria "$work/three.toml" --format csv -o "$work/three.csv"
check "three balls: equilibria exits 0" "[ $? -eq 0 ]"
expected="family,pattern,member,q1,q2,beta1,beta2,beta3,residual,spectral_abscissa,stable,n_structural_zero"
for k in $(seq 10); do expected="$expected,re$k,im$k"; done
check "three balls: the header names every ball and all 10 eigenvalues" \
  "[ \"\$(grep -v '^#' '$work/three.csv' | head -1)\" = \"$expected\" ]"
# Friction none, c > 0: 8 aligned patterns x 2 roots? Only where C|S| < U|K + iC|; the balanced
# samples carry 2 (n - 2) = 2 structural zeros each.
check "three balls: balanced samples have 2 structural zeros (friction none)" \
  "grep -v '^#' '$work/three.csv' | awk -F, '\$1 == \"balanced\" && \$12 != 2 {exit 1} \$1 == \"balanced\" {n++} END {exit n == 0}'"
"$bin" equilibria "$work/three.toml" --format json -o "$work/three.json"
check "three balls json: structural zeros have condition null, the others a number" \
  "/usr/bin/python3 -c 'import json, sys
eq = json.load(open(sys.argv[1]))[\"equilibria\"]
ev = [e for q in eq for e in q[\"eigenvalues\"]]
sys.exit(0 if any(e[\"structural\"] for e in ev) and all((e[\"condition\"] is None) == e[\"structural\"] for e in ev) else 1)' '$work/three.json'"
"$bin" sweep "$src/data/scenes/ring11.toml" --param n --from 2 --to 5 -o "$work/swn" 2>/dev/null
check "sweep --param n on a ring: exits 0" "[ $? -eq 0 ]"
check "sweep --param n: summary, long CSV and chart" "[ \"\$(ls '$work/swn' | tr '\n' ' ')\" = 'summary_n.csv summary_n.json summary_n.png sweep_n.csv ' ]"
check "sweep --param n: one summary row per ball count 2..5" \
  "[ \"\$(grep -v '^#' '$work/swn/summary_n.csv' | tail -n +2 | cut -d, -f3 | tr '\n' ' ')\" = '2 3 4 5 ' ]"
check "sweep --param n: 2^n aligned equilibria of the equal-ball ring" \
  "[ \"\$(grep -v '^#' '$work/swn/summary_n.csv' | tail -n +2 | cut -d, -f10 | tr '\n' ' ')\" = '4 8 16 32 ' ]"
bad "sweep --param n without a ring" sweep "$scene" --param n --from 2 --to 4 -o swn2
grep -q "ring" "$work/err" && pass "its message names the [balls] ring" || fail "sweep --param n message"
bad "sweep --param n to 13" sweep "$src/data/scenes/ring11.toml" --param n --from 2 --to 13 -o swn3
"$bin" continue "$work/three.toml" --param omega --to 1000 --no-chart -o "$work/c3" 2>/dev/null
check "three balls: continue exits 0" "[ $? -eq 0 ]"
check "three balls: continue writes branches, special points and the balanced set's envelope" \
  "[ \"\$(ls '$work/c3' | tr '\n' ' ')\" = 'branch_omega.csv envelope_omega.csv special_omega.csv ' ]"
bad "three balls: --from-state not supported yet" continue "$work/three.toml" --param omega --to 1000 --from-state 0,0,0,0,0 -o out
grep -q "not supported yet" "$work/err" && pass "three balls message says 'not supported yet'" || fail "three balls message"

finish
