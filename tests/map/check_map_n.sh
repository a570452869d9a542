#!/usr/bin/env bash
# The contract of `stability-scan map` for n balls (model.md
# §13.8): an n = 3 map whose every cell agrees with `equilibria` at the cell's
# parameters; the ball count as an axis (`n:2:5:4` on a [balls] ring), its n = 2 row
# against the two-ball path, capacity and 2^n aligned equilibria; the same bytes on 1 and
# 2 threads and after a kill and --resume; charts; bad ball-count axes refused (exit 2, nothing written).
#   check_map_n.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$here/../contract.sh"
ring=$src/data/scenes/ring11.toml
sed 's/^count = 11 /count = 3 /' "$ring" >"$work/ring3.toml"
sed 's/^count = 11 /count = 2 /' "$ring" >"$work/ring2.toml"
check "the n = 3 and n = 2 ring scenes were made" "grep -q '^count = 3 ' '$work/ring3.toml' && grep -q '^count = 2 ' '$work/ring2.toml'"
q() { "$bin" map "$@" --no-boundaries --quiet --long; }

# --- n = 3: every cell against `equilibria` ----------------------------------------------
# Below and above omega_n (~250 rad/s): the balanced set unstable, then stable.
X=omega:150:900:3
Y=mu:1e-3:1e-2:2:log
q "$work/ring3.toml" --x $X --y $Y --no-chart --threads 1 -o "$work/n3a"
check "n = 3 map exits 0" "[ $? -eq 0 ]"
q "$work/ring3.toml" --x $X --y $Y --threads 2 -o "$work/n3b"
check "n = 3 map with charts exits 0" "[ $? -eq 0 ]"
for f in map_omega_mu.csv summary_omega_mu.csv; do
  check "n = 3 $f: 1 and 2 threads give the same bytes" "cmp -s '$work/n3a/$f' '$work/n3b/$f'"
done
for f in stability vibration fraction; do
  check "n = 3 writes ${f}_omega_mu.png and .svg" "[ -s '$work/n3b/${f}_omega_mu.png' ] && [ -s '$work/n3b/${f}_omega_mu.svg' ]"
done
check "n = 3 summary header" "grep -v '^#' '$work/n3a/summary_omega_mu.csv' | head -1 | grep -q \
  '^ix,iy,omega,mu,balls,capacity,U,balanced_exists,balanced_samples,balanced_stable_fraction,normal_abscissa_max,aligned,aligned_stable,n_stable,best_family,best_pattern,best_member,best_q_abs,degenerate$'"
check "no nan or inf" "! grep -v '^#' '$work/n3a/map_omega_mu.csv' | grep -qiE 'nan|inf'"
/usr/bin/python3 "$here/compare_map_n.py" equilibria "$work/n3a/map_omega_mu.csv" "$work/n3a/summary_omega_mu.csv" \
  "$bin" "$work/ring3.toml" omega mu
check "n = 3 cells agree with equilibria --format csv" "[ $? -eq 0 ]"
check "the balanced set is unstable below omega_n and stable above" \
  "grep -v '^#' '$work/n3a/summary_omega_mu.csv' | awk -F, 'NR > 1 && \$3 == 150 && \$10 != 0 {e=1} NR > 1 && \$3 == 900 && \$10 != 1 {e=1} END {exit e}'"

# --- the ball count as an axis -----------------------------------------------------------
NX=omega:400:900:2
q "$ring" --x $NX --y n:2:5:4 --no-chart --threads 1 -o "$work/na"
check "--y n:2:5:4 exits 0" "[ $? -eq 0 ]"
q "$ring" --x $NX --y n:2:5:4 --threads 2 -o "$work/nb"
check "--y n:2:5:4 with charts exits 0" "[ $? -eq 0 ]"
for f in map_omega_n.csv summary_omega_n.csv; do
  check "n axis $f: 1 and 2 threads give the same bytes" "cmp -s '$work/na/$f' '$work/nb/$f'"
done
check "n axis: charts written" "[ -s '$work/nb/stability_omega_n.png' ] && [ -s '$work/nb/fraction_omega_n.png' ] && [ -s '$work/nb/vibration_omega_n.png' ]"
check "n axis: 8 summary rows" "[ \$(grep -v '^#' '$work/na/summary_omega_n.csv' | tail -n +2 | wc -l) -eq 8 ]"
check "n axis: the held mass is stated" "grep -q 'per-ball mass 3.3e-05 kg held' '$work/na/summary_omega_n.csv'"
check "n axis: beta1..beta5 columns, empty beyond a row's count" \
  "grep -v '^#' '$work/na/map_omega_n.csv' | head -1 | grep -q ',beta5$' && grep -v '^#' '$work/na/map_omega_n.csv' | awk -F, '\$5 == 2 && \$16 != \"\" {e=1} END {exit e}'"
q "$work/ring2.toml" --x $NX --y mu:0.002:0.002:1 --no-chart -o "$work/two"
check "two-ball path on the n = 2 ring exits 0" "[ $? -eq 0 ]"
/usr/bin/python3 "$here/compare_map_n.py" ballcount "$work/na/summary_omega_n.csv" "$work/two/summary_omega_mu.csv" 3.3e-5 0.018
check "n axis: capacity, 2^n aligned, n = 2 row as the two-ball path" "[ $? -eq 0 ]"
# total_mass held: the same ring with total_mass = 3.63e-4 (m = total / n)
sed 's/^mass = 3.3e-5 .*/total_mass = 3.63e-4/' "$ring" >"$work/ring_total.toml"
q "$work/ring_total.toml" --x omega:900:900:1 --y n:2:4:3 --no-chart -o "$work/tot"
check "total_mass ring: capacity the same for every n" \
  "grep -v '^#' '$work/tot/summary_omega_n.csv' | tail -n +2 | cut -d, -f6 | awk '{ if (NR == 1) c = \$1; d = \$1 - c; if (d < 0) d = -d; if (d > 1e-12 * c) e = 1 } END {exit e}' && grep -q 'total mass 0.000363 kg held' '$work/tot/summary_omega_n.csv'"
# killed after a few tiles (one column each), then resumed: the bytes of an uninterrupted run
RX=omega:400:900:40
q "$ring" --x $RX --y n:2:6:5 --no-chart -o "$work/whole" --threads 2
"$bin" map "$ring" --x $RX --y n:2:6:5 --no-chart --no-boundaries --quiet --long -o "$work/cut" --threads 1 2>/dev/null &
pid=$!
wait_for_tiles "$work/cut/.map_omega_n.tiles" 3
kill -KILL $pid
wait $pid 2>/dev/null
n=$(tile_count "$work/cut/.map_omega_n.tiles")
check "n axis: the killed run left complete tiles and no output ($n of 40)" "[ $n -ge 3 ] && [ $n -lt 40 ] && [ ! -e '$work/cut/summary_omega_n.csv' ]"
q "$ring" --x $RX --y n:2:6:5 --no-chart -o "$work/cut" --resume --threads 2
check "n axis: killed + resumed gives the bytes of an uninterrupted run" \
  "cmp -s '$work/whole/summary_omega_n.csv' '$work/cut/summary_omega_n.csv' && cmp -s '$work/whole/map_omega_n.csv' '$work/cut/map_omega_n.csv'"

# --- bad ball-count axes: exit 2, the rule named, nothing written ------------------------
bad() {  # name, message fragment, scene, axes...
  local name=$1 text=$2 scene=$3
  shift 3
  rm -rf "$work/bad"
  "$bin" map "$scene" "$@" --quiet --long -o "$work/bad" >/dev/null 2>"$work/bad.err"
  local code=$?
  check "$name: exit 2 ($(head -c 120 "$work/bad.err" | tr '\n' ' '))" \
    "[ $code -eq 2 ] && grep -q -- \"$text\" '$work/bad.err' && [ ! -e '$work/bad' ]"
}
default=$src/data/scenes/default.toml
bad "n axis on a [[ball]] scene" "ring scene" "$default" --x omega:100:200:2 --y n:2:5:4
bad "non-integer FROM" "not an integer" "$ring" --x omega:100:200:2 --y n:2.5:5:4
bad "non-integer TO" "not an integer" "$ring" --x omega:100:200:2 --y n:2:5.0:4
bad "COUNT not TO - FROM + 1" "COUNT must be" "$ring" --x omega:100:200:2 --y n:2:5:3
bad "n below 2" "runs over" "$ring" --x omega:100:200:2 --y n:1:5:5
bad "n above 12" "runs over" "$ring" --x omega:100:200:2 --y n:2:13:12
bad "decreasing n" "runs over" "$ring" --x omega:100:200:2 --y n:5:2:4
bad "log n axis" "no 'log'" "$ring" --x omega:100:200:2 --y n:2:5:4:log
bad "both axes n" "only one axis" "$ring" --x n:2:3:2 --y n:2:5:4
bad "a ball index missing at the smallest count" "unknown parameter" "$ring" --x m3:1e-5:2e-5:2 --y n:2:5:4
bad "the other axis out of range" "must be > 0" "$ring" --x omega:-1:200:2 --y n:2:5:4

finish
