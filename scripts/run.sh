#!/usr/bin/env bash
# The main job: builds stability-scan (Release) and sweeps the default scene over
# omega from 0.2 omega_n to 8 omega_n, writing out/default/sweep_omega.csv and
# out/default/sweep_omega.png. Extra arguments go to the sweep (e.g. --steps 2000).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
# The same configuration as scripts/run.sh and scripts/test.sh (Ninja: it compiles the
# tests' and the CLI's files while the library's last files still compile).
source scripts/configure.sh
cmake --build build -j"$(nproc)" --target stability-scan
# omega_n = sqrt(7500 / 0.120066) = 249.93 rad/s for the default scene.
build/stability-scan sweep data/scenes/default.toml --param omega --from 50 --to 2000 --steps 780 \
  -o out/default "$@"
