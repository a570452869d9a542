#!/usr/bin/env bash
# Builds everything (Release, warnings as errors) and runs the whole test suite:
# Catch2 unit tests, the invalid-scene contract, the CLI contract and the 40-digit
# reference comparisons. The special-point checks against mpmath (label "slow", minutes
# each) are left to .ci/run. Extra arguments go to ctest (e.g. -R reference).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DABU_WERROR=ON >/dev/null
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)" -LE slow "$@"
