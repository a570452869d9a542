#!/usr/bin/env bash
# Benchmarks (not tests): builds Release and prints, in one run so that the ratios are
# comparable on a noisy machine,
#  1. ns per equilibrium on the default scene, split by phase, against a plain dense QR;
#  2. the same with stiff friction (kappa = 1e6);
#  3. eigenvalue accuracy of each method against the 40-digit reference on every
#     reference scene (tests/scenes/reference) and the default scene;
#  4. the numpy/scipy baseline (../shared/peers/numpy) solving 8x8 eigenproblems, for scale.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh python3-numpy python3-scipy
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target bench_equilibria stability-scan >/dev/null
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
peers=${ABU_PEERS:-../shared/peers/numpy}
if [ -f "$peers/stability_map.py" ]; then
  echo "## 4. numpy baseline: stacked numpy.linalg.eigvals, 300 x 300 map (coulomb)"
  (cd "$peers" && /usr/bin/python3 stability_map.py --nx 300 --ny 300 --law coulomb --out - | grep -E "eigenproblems per second|wall time")
fi
