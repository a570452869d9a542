#!/usr/bin/env bash
# Benchmarks (not tests): builds Release and prints, in one run so that the ratios are
# comparable on a noisy machine,
#  1. ns per equilibrium on the default scene, split by phase, against a plain dense QR;
#  2. the same with stiff friction (kappa = 1e6);
#  3. eigenvalue accuracy of each method against the 40-digit reference on every
#     reference scene (tests/scenes/reference) and the default scene;
#  4. the continuation of every branch of the default scene in omega (0.2 .. 8 omega_n) with
#     its special points, against sweep grids; and the whole `stability-scan continue`
#     process (median of 21 runs);
#  5. the 1000 x 1000 (omega, mu) stability map: cells/s and eigenproblems/s with 1 and all
#     threads, the fast decision's disagreement with full eigenvalues, the whole
#     `stability-scan map` run;
#  6. the numpy/scipy baseline (../shared/peers/numpy) on the same 1000 x 1000 map, and the
#     ratio of throughputs.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh python3-numpy python3-scipy
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target bench_equilibria bench_continuation bench_map stability-scan >/dev/null
bench=build/tests/benchmarks/bench_equilibria
echo "# machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); build: Release, $(c++ --version | head -1)"
echo "## 1. default scene"
$bench timing data/scenes/default.toml --points 2000 --repeat 5
echo "## 2. stiff friction"
stiff=$(mktemp --suffix=.toml)
trap 'rm -f "$stiff" "$stiff.csv"' EXIT
sed 's/^kappa = 1.0e3 .*/kappa = 1.0e6/' data/scenes/default.toml >"$stiff"
$bench timing "$stiff" --points 2000 --repeat 5
echo "## 3. accuracy against the 40-digit reference"
$bench eigenvalues "$stiff.csv" data/scenes/default.toml tests/scenes/reference/*.toml
/usr/bin/python3 tests/benchmarks/bench_errors.py "$stiff.csv"
echo "## 4. continuation"
build/tests/benchmarks/bench_continuation data/scenes/default.toml --repeat 21
runs=()
for i in $(seq 21); do
  t0=$(date +%s%N)
  build/stability-scan continue data/scenes/default.toml --set omega=49.98625566927664 --param omega \
    --to 1999.4502267710656 --no-chart -o "$stiff.cont" 2>/dev/null
  runs+=($(( ($(date +%s%N) - t0) / 1000 )))
done
median=$(printf '%s\n' "${runs[@]}" | sort -n | sed -n 11p)
echo "whole process 'stability-scan continue' (parse, all branches, special points, CSVs; no chart): median $((median / 1000)).$(( (median % 1000) / 100 )) ms of 21"
rm -rf "$stiff.cont"
echo "## 5. stability map, 1000 x 1000"
build/tests/benchmarks/bench_map data/scenes/default.toml --nx 1000 --ny 1000 --sample 20
t0=$(date +%s%N)
build/stability-scan map data/scenes/default.toml --x omega:49.98625566927664:1999.4502267710656:1000 \
  --y mu:1e-4:1e-1:1000:log --quiet --no-boundaries -o "$stiff.map" >/dev/null 2>&1 || echo "(map command failed)"
map_ms=$(( ($(date +%s%N) - t0) / 1000000 ))
echo "whole 'stability-scan map' 1000 x 1000 with CSVs and charts: ${map_ms} ms"
rm -rf "$stiff.map"
peers=${ABU_PEERS:-../shared/peers/numpy}
if [ -f "$peers/stability_map.py" ]; then
  echo "## 6. numpy baseline, the same 1000 x 1000 coulomb map (stacked numpy.linalg.eigvals, one core)"
  (cd "$peers" && /usr/bin/python3 stability_map.py --nx 1000 --ny 1000 --law coulomb --out - | grep -E "eigenproblems per second|wall time|sign not trustworthy")
fi
