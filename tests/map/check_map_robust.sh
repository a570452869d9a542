#!/usr/bin/env bash
# Maps under faults and hostile use (docs/robustness.md "Maps"): the tile
# directory is locked against a second writer, resume is keyed by content, a directory
# left without a manifest is not taken for an interrupted map, a map that cannot fit on
# the disk is refused up front.
#   check_map_robust.sh BINARY SOURCE_DIR
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
scene=$src/data/scenes/default.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"
RX=omega:150:600:800
RY=mu:1e-4:0.1:40:log
tiles=$work/m/.map_omega_mu.tiles

"$bin" map "$scene" --long --x "$RX" --y "$RY" --no-chart --no-boundaries --quiet -o "$work/whole" --threads 2

# --- a second writer is refused, naming the holder ----------------------------------------
"$bin" map "$scene" --long --x "$RX" --y "$RY" --no-chart --no-boundaries --quiet -o "$work/m" --threads 1 2>"$work/first.err" &
pid=$!
wait_for_tiles "$tiles" 2
"$bin" map "$scene" --long --x "$RX" --y "$RY" --no-chart --no-boundaries --quiet -o "$work/m" --fresh 2>"$work/second.err"
code=$?
check "a second map on the same tiles (--fresh) is refused with exit 2" "[ $code -eq 2 ]"
check "... naming the holder's PID ($(head -c 150 "$work/second.err"))" "grep -q \"PID $pid\" '$work/second.err'"
"$bin" map "$scene" --long --x "$RX" --y "$RY" --no-chart --no-boundaries --quiet -o "$work/m" --resume 2>/dev/null
check "... and so is a second writer with --resume" "[ $? -eq 2 ]"
wait $pid
check "the first map finishes with exit 0" "[ $? -eq 0 ]"
check "... with the bytes of an undisturbed run" "cmp -s '$work/whole/map_omega_mu.csv' '$work/m/map_omega_mu.csv' && cmp -s '$work/whole/summary_omega_mu.csv' '$work/m/summary_omega_mu.csv'"

# --- resume keyed by content, not by the spelling of the command --------------------------
rm -rf "$work/m"
"$bin" map "$scene" --long --x "$RX" --y "$RY" --no-chart --no-boundaries --quiet -o "$work/m" --threads 1 2>/dev/null &
pid=$!
wait_for_tiles "$tiles" 3
kill -TERM $pid
wait $pid
check "SIGTERM: exit 143" "[ $? -eq 143 ]"
(cd "$src/data" && "$bin" map ./scenes/../scenes/default.toml --long --x "$RX" --y "$RY" --no-chart --no-boundaries --quiet \
  -o "$work/m" --resume 2>"$work/resume.err")
check "resume with the scene path spelled differently: exit 0 ($(head -c 150 "$work/resume.err"))" "[ $? -eq 0 ]"
check "... the same rows as an uninterrupted run" \
  "cmp -s <(grep -v '^#' '$work/whole/map_omega_mu.csv') <(grep -v '^#' '$work/m/map_omega_mu.csv')"

# --- a directory without a manifest is not an interrupted map -----------------------------
rm -rf "$work/m"
mkdir -p "$tiles"
"$bin" map "$scene" --long --x "$RX" --y "$RY" --no-chart --no-boundaries --quiet -o "$work/m" 2>"$work/empty.err"
check "an empty tile directory (a failed first write) does not make the next run refuse" "[ $? -eq 0 ]"

# --- no stale outputs: a second, smaller map of the same axes in the same directory without
# --long, charts or boundaries left the first run's long CSV, boundary curves and charts
# beside its own summary; now they go with the commit, and another map's files stay.
"$bin" map "$scene" --x omega:50:2000:20 --y mu:1e-4:0.1:10:log --long --quiet -o "$work/stale" 2>/dev/null
"$bin" map "$scene" --x omega:50:2000:4 --y c:1:3:3 --no-chart --no-boundaries --quiet -o "$work/stale" 2>/dev/null
first=$(ls "$work/stale" | grep -c '_omega_mu\.')
"$bin" map "$scene" --x omega:50:2000:10 --y mu:1e-4:0.1:5:log --no-chart --no-boundaries --quiet -o "$work/stale" \
  2>/dev/null
check "a smaller rerun leaves no stale output of the same axes ($first files before), another map's kept" \
  "[ $? -eq 0 ] && [ $first -eq 8 ] && [ \"\$(ls '$work/stale' | grep '_omega_mu\.' | tr '\n' ' ')\" = \
  'summary_omega_mu.csv summary_omega_mu.json ' ] && [ -s '$work/stale/summary_omega_c.csv' ] && \
  [ -z \"\$(find '$work/stale' -name '.*')\" ]"

# --- too big for the disk: refused before any work ----------------------------------------
free_kb=$(df -Pk "$work" | awk 'NR == 2 {print $4}')
if [ "$free_kb" -lt 150000000 ]; then
  # with the long CSV (~0.9 kB a cell: 180 GB with its tiles); the summary alone would fit
  "$bin" map "$scene" --x omega:50:2000:20000 --y mu:1e-4:0.1:5000:log --long --no-chart --no-boundaries --quiet \
    -o "$work/big" 2>"$work/big.err"
  check "a map of 1e8 cells on a disk with $((free_kb / 1000000)) GB free: exit 2" \
    "[ $? -eq 2 ] && grep -q 'of disk' '$work/big.err' && [ ! -e '$work/big' ]"
else
  echo "skip (more than 150 GB free): the disk estimate"
fi

finish
