#!/usr/bin/env bash
# Builds everything (Release, warnings as errors) and runs the whole test suite:
# Catch2 unit tests, the invalid-scene contract, the CLI contract and the 40-digit
# reference comparisons. The special-point checks against mpmath (label "slow", minutes
# each) are left to .ci/run. Extra arguments go to ctest (e.g. -R reference).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
# Ninja on a new build directory: it compiles the tests' and the CLI's files while the
# library's last files still compile (make waits for the whole library first).
generator=(); [ -f build/CMakeCache.txt ] || generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DABU_WERROR=ON >/dev/null
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)" -LE slow "$@"
