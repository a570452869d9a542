#!/usr/bin/env bash
# Builds everything (Release; warnings are errors with ABU_WERROR=ON, as in .ci/run) and runs
# the whole test suite: Catch2 unit tests, the invalid-scene contract, the CLI contract and the
# 40-digit reference comparisons. The special-point checks against mpmath (label "slow", minutes
# each) are left to .ci/run. Extra arguments go to ctest (e.g. -R reference).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
# The same configuration as scripts/run.sh and scripts/test.sh (Ninja: it compiles the
# tests' and the CLI's files while the library's last files still compile).
source scripts/configure.sh
cmake --build build -j"$(nproc)"
ctest --test-dir build --output-on-failure -j"$(nproc)" -LE slow "$@"
