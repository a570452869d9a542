#!/usr/bin/env bash
# Benchmarks (not tests): builds Release and prints, in one run so that the ratios are
# comparable on a noisy machine,
#  1. ns per equilibrium on the default scene, split by phase, against a plain dense QR;
#  2. the same with stiff friction (kappa = 1e6);
#  3. eigenvalue accuracy of each method against the 40-digit reference on every
#     reference scene (tests/scenes/reference) and the default scene;
#  4. the continuation of every branch of the default scene in omega (0.2 .. 8 omega_n) with
#     its special points, against sweep grids; and the whole `stability-scan continue`
#     process (median of 41 launches; ABU_BENCH_BEFORE=BINARY compares an older binary in
#     the same run; docs/benchmarks-continuation.md);
#  5. the 1000 x 1000 (omega, mu) stability map: cells/s and eigenproblems/s with 1 and all
#     threads, the fast decision's disagreement with full eigenvalues, the whole
#     `stability-scan map` run;
#  6. the numpy/scipy baseline (../shared/peers/numpy) on the same 1000 x 1000 map, and its
#     stability flags against the analyzer's;
#  7. the same comparison with stiff friction (kappa = 1e6), where the baseline's flags are
#     wrong in a third of the cells: the differing cells checked at 40 digits;
#  8. us per equilibrium against the number of balls (ring scene, n = 2 .. 12): the whole
#     analysis, the refined spectrum, a plain dense QR and numpy.linalg.eigvals on the same
#     Jacobians, numpy's worst error and wrong verdicts against the analyzer.
#     Also one n-ball map cell (CellAnalyzerN) per n against numpy's stacked eigvals of
#     the same cell's Jacobians, one core each;
#  9. why the map's characteristic-polynomial path stays two balls: how far the roots of
#     the exact degree-(2n+4) polynomial move when its coefficients are rounded to long
#     double (model.md §13.8);
# 10. `simulate`'s integrators against scipy's Radau, BDF, LSODA and DOP853 on the same
#     problems (coulomb kappa = 1e3 and 1e6, 1 s from a perturbed balanced state; a run-up
#     through omega_n): time to reach 1e-4, 1e-5, 1e-6 and 1e-9 error, the analyzer with free
#     steps and with its default 2000 samples by dense output (`bench_simulate`,
#     tests/benchmarks/bench_simulate_scipy.py); with ABU_BENCH_BEFORE=BINARY also the default
#     `simulate` runs of that older binary against this one (tests/benchmarks/
#     compare_simulate.py: wall time, instructions, sample and peak errors).
#     `scripts/bench.sh 10` runs this section only.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh python3-numpy python3-scipy
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
section10() {
  cmake --build build -j"$(nproc)" --target bench_simulate >/dev/null
  echo "## 10. simulate against scipy.integrate.solve_ivp (same problems, same reference, one core)"
  local res
  res=$(mktemp --suffix=.json)
  build/tests/benchmarks/bench_simulate data/scenes/default.toml --repeat 3 --json "$res"
  OPENBLAS_NUM_THREADS=1 /usr/bin/python3 tests/benchmarks/bench_simulate_scipy.py "$res" --timeout 60
  rm -f "$res"
  if [ -n "${ABU_BENCH_BEFORE:-}" ]; then
    cmake --build build -j"$(nproc)" --target stability-scan >/dev/null
    echo "## 10b. default simulate runs: $ABU_BENCH_BEFORE against build/stability-scan"
    /usr/bin/python3 tests/benchmarks/compare_simulate.py "$ABU_BENCH_BEFORE" build/stability-scan . --repeat 5 \
      --rtol 1e-8 --instructions
  fi
}
if [ "${1:-}" = 10 ]; then
  echo "# machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); build: Release, $(c++ --version | head -1)"
  section10
  exit 0
fi
cmake --build build -j"$(nproc)" --target bench_equilibria bench_continuation bench_map stability-scan >/dev/null
bench=build/tests/benchmarks/bench_equilibria
echo "# machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); build: Release, $(c++ --version | head -1)"
echo "## 1. default scene"
$bench timing data/scenes/default.toml --points 2000 --repeat 5
echo "## 2. stiff friction"
stiff=$(mktemp --suffix=.toml)
trap 'rm -rf "$stiff" "$stiff.csv" "$stiff.map" "$stiff.np.csv"' EXIT
sed 's/^kappa = 1.0e3 .*/kappa = 1.0e6/' data/scenes/default.toml >"$stiff"
$bench timing "$stiff" --points 2000 --repeat 5
echo "## 3. accuracy against the 40-digit reference"
$bench eigenvalues "$stiff.csv" data/scenes/default.toml tests/scenes/reference/*.toml
/usr/bin/python3 tests/benchmarks/bench_errors.py "$stiff.csv"
echo "## 4. continuation"
# The whole process too: launches of `stability-scan continue` (median wall and CPU time);
# ABU_BENCH_BEFORE=/path/to/an/older/stability-scan adds that binary, launched in turn with
# this one, for a before/after comparison on the same machine state.
before=()
[ -n "${ABU_BENCH_BEFORE:-}" ] && before=(--process "$ABU_BENCH_BEFORE")
build/tests/benchmarks/bench_continuation data/scenes/default.toml --repeat 21 "${before[@]}" \
  --process build/stability-scan --launches 41
echo "## 5. stability map, 1000 x 1000"
build/tests/benchmarks/bench_map data/scenes/default.toml --nx 1000 --ny 1000 --sample 20
omega_grid=omega:49.98625566927664:1999.4502267710656   # 0.2 .. 8 omega_n, the baseline's grid
t0=$(date +%s%N)
build/stability-scan map data/scenes/default.toml --x $omega_grid:1000 --y mu:1e-4:1e-1:1000:log --no-boundaries \
  --long -o "$stiff.map" 2>&1 | tail -1
map_ms=$(( ($(date +%s%N) - t0) / 1000000 ))
echo "whole 'stability-scan map' 1000 x 1000, $(nproc) threads, CSVs (long + summary) and 4 charts: ${map_ms} ms"
peers=${ABU_PEERS:-../shared/peers/numpy}
peers=$(cd "$peers" 2>/dev/null && pwd || true)
if [ -n "$peers" ] && [ -f "$peers/stability_map.py" ]; then
  echo "## 6. numpy baseline, the same 1000 x 1000 coulomb map (stacked numpy.linalg.eigvals, one core)"
  (cd "$peers" && /usr/bin/python3 stability_map.py --nx 1000 --ny 1000 --law coulomb --out "$stiff.np.csv" |
    grep -E "eigenproblems per second|wall time|sign not trustworthy")
  /usr/bin/python3 tests/benchmarks/compare_numpy_map.py "$stiff.np.csv" "$stiff.map/map_omega_mu.csv" \
    --binary build/stability-scan --scene data/scenes/default.toml --verify 3
  echo "## 7. stiff coulomb (kappa = 1e6), 300 x 300: stability flags of the baseline against the analyzer"
  (cd "$peers" && /usr/bin/python3 stability_map.py --nx 300 --ny 300 --law coulomb --kappa 1e6 --out "$stiff.np.csv" |
    grep -E "eigenproblems per second|sign not trustworthy")
  build/stability-scan map data/scenes/default.toml --set kappa=1e6 --x $omega_grid:300 --y mu:1e-4:1e-1:300:log \
    --no-boundaries --no-chart --long --quiet --fresh -o "$stiff.map"
  /usr/bin/python3 tests/benchmarks/compare_numpy_map.py "$stiff.np.csv" "$stiff.map/map_omega_mu.csv" \
    --binary build/stability-scan --scene data/scenes/default.toml --verify 5
  rm -f "$stiff.np.csv"
  echo "## 7b. the whole 'map' command, 300 x 300 with its charts, against the baseline's computation (alternating)"
  for run in 1 2 3; do
    (cd "$peers" && /usr/bin/python3 stability_map.py --nx 300 --ny 300 --law coulomb --out - | grep "wall time")
    for chart in "" --no-chart; do
      rm -rf "$stiff.map"
      /usr/bin/time -f "map 300 x 300 ${chart:-with charts}: %e s wall, %U s user, %S s sys" build/stability-scan map \
        data/scenes/default.toml --x $omega_grid:300 --y mu:1e-4:1e-1:300:log --no-boundaries $chart --quiet \
        -o "$stiff.map"
    done
  done
fi
rm -rf "$stiff.map"
echo "## 8. cost per equilibrium against the number of balls (ring scene, n = 2 .. 12), against numpy on the same Jacobians"
# bench_n times the analyzer (1 thread) and writes every equilibrium's double Jacobian and
# eigenvalues; bench_n_numpy.py times stacked numpy.linalg.eigvals on those matrices (one
# thread), scores them and prints the table.
cmake --build build -j"$(nproc)" --target bench_n >/dev/null
nbin=$(mktemp --suffix=.bin)
ncsv=$(mktemp --suffix=.csv)
build/tests/benchmarks/bench_n data/scenes/ring11.toml "$nbin" "$ncsv" --repeat 5
env -u OPENBLAS_CORETYPE -u OPENBLAS_L2_SIZE OPENBLAS_NUM_THREADS=1 \
  /usr/bin/python3 tests/benchmarks/bench_n_numpy.py "$nbin" "$ncsv" --repeat 5
rm -f "$nbin" "$ncsv"
echo "## 9. degree-(2n+4) polynomial: root sensitivity to one long-double rounding of the coefficients"
/usr/bin/python3 tests/benchmarks/polynomial_conditioning.py build/stability-scan data/scenes/ring11.toml --counts 2,3,4,6,12
section10
