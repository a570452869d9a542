#!/usr/bin/env bash
# Fuzzes the scene parser and --set (tests/fuzz/fuzz_scene.cpp) with libFuzzer under
# address + undefined sanitizers, for SECONDS of wall time (default 120) in JOBS processes
# (default: the number of cores) sharing one corpus, seeded with every scene in data/ and
# tests/scenes. Prints the executions each process reached; exits non-zero on a finding (the
# crashing input is left in build-fuzz/).
#   scripts/fuzz.sh [SECONDS] [JOBS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-120}
jobs=${2:-$(nproc)}
scripts/deps.sh clang-14 libclang-rt-14-dev
cmake -S . -B build-fuzz -DABU_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
cmake --build build-fuzz -j"$(nproc)" --target fuzz_scene
corpus=build-fuzz/corpus
mkdir -p "$corpus"
find data tests/scenes -name '*.toml' -exec cp {} "$corpus/" \;
# Seeds with --set lines after a NUL byte.
printf '%s\0omega=1e155\nm=0.02\nr=0.03\nl=0.2\n' "$(cat data/scenes/default.toml)" >"$corpus/with_sets"
# Seeds with option values after a second NUL byte (a list, a grid, a ramp, a parameter).
printf '%s\0omega=300\n\000mu2\n2, 4.5,1e-3\n40x30\n100:400:200\n1e308:1e-308:1e308\n' \
  "$(cat data/scenes/default.toml)" >"$corpus/with_values"
# The two toml++ 3.3 traps, guarded by src/input/toml_guard.cpp.
printf '[rotor]\nmass = 1\xc3\xa9\n' >"$corpus/nonascii_after_number"
printf '[# speed]\nomega = 1\n' >"$corpus/hash_in_header"
cd build-fuzz
# Each process reads the shared corpus again as the others add to it (libFuzzer's -reload);
# its own seed, so that the processes do not walk the same mutations.
for ((j = 1; j <= jobs; j++)); do
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    tests/fuzz/fuzz_scene -seed="$j" -max_total_time="$seconds" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
    -print_final_stats=1 corpus >"fuzz.$j.log" 2>&1 &
done
wait || true
status=0
for ((j = 1; j <= jobs; j++)); do
  echo "fuzz process $j:"
  grep -E '^(#[0-9]+ +DONE|==|SUMMARY|stat::number_of_executed_units)' "fuzz.$j.log" || true
  if ! grep -q 'stat::number_of_executed_units' "fuzz.$j.log" ||
    grep -qE '^==[0-9]+==ERROR|deadly signal|SUMMARY: (Address|Undefined)' "fuzz.$j.log"; then
    status=1
  fi
done
exit $status
