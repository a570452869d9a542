#!/usr/bin/env bash
# The contract of `stability-scan map`: the same bytes for 1 and N threads and
# for a killed-and-resumed run; the fast decision agrees with full eigenvalues; the CSVs
# are complete and consistent; bad axes are refused before any work; charts are written.
#   check_map.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
scene=$src/data/scenes/default.toml
work=$(mktemp -d)
trap '[ "$pid" -gt 0 ] && kill -9 "$pid" 2>/dev/null; rm -rf "$work"' EXIT
pid=0
. "$(dirname "$0")/../contract.sh"
rows() { grep -v '^#' "$1" | tail -n +2; }

# A small (omega, mu) map across the balancing speed, coulomb friction from the scene.
X=omega:150:600:40
Y=mu:1e-4:0.1:30:log
map() { "$bin" map "$scene" --x "$X" --y "$Y" --no-chart --no-boundaries --quiet --long "$@"; }

# --- threads: same bytes ---------------------------------------------------------------
map --threads 1 -o "$work/t1"
check "1-thread map exits 0" "[ $? -eq 0 ]"
map --threads 3 -o "$work/t3"
check "3-thread map exits 0" "[ $? -eq 0 ]"
check "long csv: 1 and 3 threads give the same bytes" "cmp -s '$work/t1/map_omega_mu.csv' '$work/t3/map_omega_mu.csv'"
check "summary: 1 and 3 threads give the same bytes" "cmp -s '$work/t1/summary_omega_mu.csv' '$work/t3/summary_omega_mu.csv'"
check "the tile directory is removed after success" "[ ! -e '$work/t1/.map_omega_mu.tiles' ]"
check "only the two csvs and the ranges json are written" "[ \"\$(ls -A '$work/t1' | tr '\n' ' ')\" = 'map_omega_mu.csv summary_omega_mu.csv summary_omega_mu.json ' ]"

# --- content ---------------------------------------------------------------------------
long=$work/t1/map_omega_mu.csv
summary=$work/t1/summary_omega_mu.csv
check "long header" "[ \"\$(grep -v '^#' '$long' | head -1)\" = 'ix,iy,omega,mu,family,member,stable,n_unstable,spectral_abscissa,q_abs,beta1,beta2,n_undecided' ]"
check "summary has one row per cell (1200)" "[ \$(rows '$summary' | wc -l) -eq 1200 ]"
check "every cell has a row in the long csv" "[ \$(rows '$long' | cut -d, -f1,2 | sort -u | wc -l) -eq 1200 ]"
check "no nan or inf" "! rows '$long' | grep -qiE 'nan|inf' && ! rows '$summary' | grep -qiE 'nan|inf'"
check "the header names the units" "grep -q 'omega \[rad/s\]' '$long' && grep -q 'q_abs \[m\]' '$long' && grep -q 'spectral_abscissa \[1/s\]' '$long'"
# stable <=> n_unstable = 0 <=> abscissa < 0, on every row.
check "stable, n_unstable and the abscissa agree on every row" \
  "rows '$long' | awk -F, '(\$7 == 1) != (\$8 == 0) || (\$7 == 1) != (\$9 < 0) {exit 1}'"
# The summary is a function of the long rows: family counts, n_stable, best |q|.
check "summary recomputed from the long rows matches" "diff <(rows '$long' | awk -F, '
  { k = \$1 \",\" \$2; n[k \",\" \$5]++; if (\$7 == 1) { s[k]++; if (!(k in b) || \$10 < b[k]) b[k] = \$10 } }
  END { for (k in s) print k, s[k], b[k] }' | sort) <(rows '$summary' | awk -F, '\$9 > 0 {print \$1 \",\" \$2, \$9, \$12}' | sort) >/dev/null"
check "family counts in the summary match the long rows" "diff <(rows '$long' | cut -d, -f1,2,5 | sort | uniq -c | awk '{print \$2, \$1}' | sort) \
  <(rows '$summary' | awk -F, '{ if (\$5) print \$1 \",\" \$2 \",balanced\", \$5; if (\$6) print \$1 \",\" \$2 \",together\", \$6; if (\$7) print \$1 \",\" \$2 \",opposite\", \$7 }' | sort) >/dev/null"
# model.md §7: the balanced state is unstable below omega_n (about 250 rad/s) and exists
# wherever U <= 2 m l; the map must show both a stable and an unstable balanced region.
check "balanced unstable below omega_n" "rows '$summary' | awk -F, '\$3 < 240 && \$8 == 1 {exit 1}'"
check "balanced stable somewhere above omega_n" "rows '$summary' | awk -F, '\$3 > 260 && \$8 == 1 {f=1} END {exit !f}'"

# --- the fast decision against full eigenvalues ------------------------------------------
map --method full -o "$work/full"
check "full-method map exits 0" "[ $? -eq 0 ]"
check "fast and full agree on stable and n_unstable everywhere" \
  "diff <(rows '$long' | cut -d, -f1-8) <(rows '$work/full/map_omega_mu.csv' | cut -d, -f1-8) >/dev/null"
# Both abscissas are accurate to ~1e-12 of the spectrum's scale (|lambda| up to ~1e3 1/s
# here): compare with that absolute-relative tolerance.
check "fast and full abscissas agree to 1e-9 relative (or 1e-12 absolute)" "paste -d, <(rows '$long' | cut -d, -f9) \
  <(rows '$work/full/map_omega_mu.csv' | cut -d, -f9) | awk -F, '{d = \$1 - \$2; if (d < 0) d = -d; a = \$2 < 0 ? -\$2 : \$2;
  if (d > 1e-9 * a + 1e-12) {print; exit 1}}' >/dev/null"

# --- interrupted and resumed -------------------------------------------------------------
# A map big enough to be caught in the middle (100 tiles on one thread), small enough for
# the sanitizer build.
RX=omega:150:600:800
RY=mu:1e-4:0.1:40:log
resume_map() { "$bin" map "$scene" --x "$RX" --y "$RY" --no-chart --no-boundaries --quiet --long "$@"; }
resume_map -o "$work/whole" --threads 2
tiles=$work/cut/.map_omega_mu.tiles
interrupt() {  # signal, then wait for the run to be cut after a few tiles
  rm -rf "$work/cut"
  # The binary itself in the background (a function would run in a subshell that the
  # signal would hit instead).
  "$bin" map "$scene" --x "$RX" --y "$RY" --no-chart --no-boundaries --quiet --long -o "$work/cut" --threads 1 \
    2>"$work/cut.err" &
  pid=$!
  wait_for_tiles "$tiles" 3
  kill "-$1" $pid
  wait $pid
  echo $?
}
code=$(interrupt KILL)
n=$(tile_count "$tiles")
check "killed run left complete tiles and no output ($n of 100)" "[ $n -ge 3 ] && [ $n -lt 100 ] && [ ! -e '$work/cut/map_omega_mu.csv' ]"
resume_map -o "$work/cut" 2>"$work/again.err"
check "without --resume the leftover tiles are not discarded silently (exit 2)" "[ $? -eq 2 ] && grep -q -- '--resume' '$work/again.err'"
resume_map -o "$work/cut" --resume
check "resumed run exits 0" "[ $? -eq 0 ]"
check "killed + resumed: same bytes as uninterrupted (long)" "cmp -s '$work/whole/map_omega_mu.csv' '$work/cut/map_omega_mu.csv'"
check "killed + resumed: same bytes as uninterrupted (summary)" "cmp -s '$work/whole/summary_omega_mu.csv' '$work/cut/summary_omega_mu.csv'"
code=$(interrupt INT)
check "Ctrl-C exits 130" "[ '$code' = 130 ]"
check "Ctrl-C says how to continue" "grep -q -- '--resume' '$work/cut.err'"
resume_map -o "$work/cut" --resume --threads 2
check "interrupted + resumed on 2 threads: same bytes" "cmp -s '$work/whole/map_omega_mu.csv' '$work/cut/map_omega_mu.csv'"
code=$(interrupt TERM)
"$bin" map "$scene" --x omega:150:600:799 --y "$RY" --no-chart --no-boundaries --quiet --long -o "$work/cut" --resume 2>"$work/other.err"
check "resuming a different map is refused (exit 2)" "[ $? -eq 2 ] && grep -q 'different map' '$work/other.err'"
resume_map -o "$work/cut" --fresh
check "--fresh starts over and gives the same bytes" "[ $? -eq 0 ] && cmp -s '$work/whole/map_omega_mu.csv' '$work/cut/map_omega_mu.csv'"

# --- progress ----------------------------------------------------------------------------
"$bin" map "$scene" --x "$X" --y "$Y" --no-chart --no-boundaries -o "$work/p" 2>"$work/p.err"
check "not a terminal: no progress line" "! grep -q 'tiles (' '$work/p.err'"
"$bin" map "$scene" --x "$X" --y "$Y" --no-chart --no-boundaries --progress -o "$work/p" 2>"$work/p.err"
check "--progress forces progress with an ETA" "grep -q 'tiles (' '$work/p.err' && grep -q 'ETA' '$work/p.err'"
"$bin" map "$scene" --x "$X" --y "$Y" --no-chart --no-boundaries --quiet --long -o "$work/p" 2>"$work/p.err"
check "--quiet: nothing on stderr" "[ ! -s '$work/p.err' ]"

# --- charts and boundaries ---------------------------------------------------------------
"$bin" map "$scene" --x omega:150:600:60 --y mu:1e-4:0.1:40:log --quiet -o "$work/c"
check "chart run exits 0" "[ $? -eq 0 ]"
check "without --long: the summary, no long csv" "[ -s '$work/c/summary_omega_mu.csv' ] && [ ! -e '$work/c/map_omega_mu.csv' ]"
# Each curve once: no two curves of the same kind share an end point (to 1e-6 of the
# map's extent; a curve from the bottom edge that reaches the top is the one the top edge
# would start again; distinct curves meet only at codimension-two points, of other kinds).
check "each boundary curve is written once" "/usr/bin/python3 - '$work/c/boundary_omega_mu.csv' <<'PY'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))
ends = {}
for r in rows:
    ends.setdefault(r['curve'], []).append(r)
pts = [(k, c[0]['kind'], float(e['omega']), float(e['mu'])) for k, c in ends.items() for e in (c[0], c[-1])]
bad = [(a, b) for i, a in enumerate(pts) for b in pts[i + 1:]
       if a[0] != b[0] and a[1] == b[1] and abs(a[2] - b[2]) < 1e-6 * 450 and abs(a[3] - b[3]) < 1e-6 * 0.1]
sys.exit(1 if bad else 0)
PY"
for f in stability_omega_mu.png stability_omega_mu.svg vibration_omega_mu.png vibration_omega_mu.svg boundary_omega_mu.csv; do
  check "writes $f" "[ -s '$work/c/$f' ]"
done
check "the balanced Hopf curve crosses the map" "grep -v '^#' '$work/c/boundary_omega_mu.csv' | grep -q ',HB,'"
# The map draws its charts from a compact binary grid; plots/map.gp run by hand on the
# summary CSV (the other route: gnuplot reads the columns and finds the geometry and the
# |q| range itself) must give the same pictures, byte for byte.
if command -v gnuplot >/dev/null; then
  (cd "$work/c" && gnuplot -e "summary='summary_omega_mu.csv'; curves='boundary_omega_mu.csv'; png_stability='s.png'; \
svg_stability='s.svg'; png_vibration='v.png'; svg_vibration='v.svg'; xname='omega'; xunit='rad/s'; yname='mu'; \
yunit='-'; logx='0'; logy='1'; title='$scene'" "$src/plots/map.gp")
  for f in stability:s vibration:v; do
    for e in png svg; do
      check "${f%%:*}.$e from the grid is the chart from the summary" \
        "cmp -s '$work/c/${f%%:*}_omega_mu.$e' '$work/c/${f##*:}.$e'"
    done
  done
fi

# --- bad input: exit 2, the rule named, nothing written ---------------------------------
bad() {  # name, expected message fragment, axes...
  local name=$1 text=$2
  shift 2
  rm -rf "$work/bad"
  "$bin" map "$scene" "$@" --quiet --long -o "$work/bad" >/dev/null 2>"$work/bad.err"
  local code=$?
  check "$name: exit 2 ($(head -c 110 "$work/bad.err" | tr '\n' ' '))" \
    "[ $code -eq 2 ] && grep -q -- '$text' '$work/bad.err' && [ ! -e '$work/bad' ]"
}
bad "missing N" "expected NAME:FROM:TO:N" --x omega:100:200 --y mu:0.001:0.01:5
bad "unknown name" "unknown parameter" --x zeta:100:200:5 --y mu:0.001:0.01:5
bad "FROM not a number" "is not a finite number" --x omega:abc:200:5 --y mu:0.001:0.01:5
bad "TO infinite" "is not a finite number" --x omega:100:inf:5 --y mu:0.001:0.01:5
bad "N = 0" "N must be in" --x omega:100:200:0 --y mu:0.001:0.01:5
bad "N not an integer" "is not an integer" --x omega:100:200:5.5 --y mu:0.001:0.01:5
bad "absurd N" "N must be in" --x omega:100:200:100000000 --y mu:0.001:0.01:5
bad "too many cells" "at most" --x omega:100:200:20000 --y mu:0.001:0.01:20000
bad "mass range through 0" "must be > 0" --x omega:100:200:5 --y m:-1e-5:1e-5:5
bad "speed range through 0" "must be > 0" --x omega:-100:200:5 --y mu:0.001:0.01:5
bad "negative friction" "must be >= 0" --x omega:100:200:5 --y mu:-0.01:0.01:5
bad "log axis through 0" "needs both ends > 0" --x omega:100:200:5 --y mu:0:0.01:5:log
bad "bad fifth field" "the fifth field" --x omega:100:200:5 --y mu:0.001:0.01:5:lin
bad "same parameter twice" "must differ" --x omega:100:200:5 --y omega:300:400:5
bad "parameter the law does not use" "does not use" --x omega:100:200:5 --y d:0.001:0.01:5
bad "ball radius" "does not enter" --x omega:100:200:5 --y r:0.0001:0.001:5
bad "race radius below the ball radius" "must be" --x omega:100:200:5 --y l:0.0001:0.01:5
bad "equal ends with N > 1" "are equal" --x omega:100:100:5 --y mu:0.001:0.01:5

finish
