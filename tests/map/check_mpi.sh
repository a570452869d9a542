#!/usr/bin/env bash
# MPI maps: `mpirun -n 2` and `-n 3` write exactly the bytes of the
# single-process run, and an MPI run resumes the tiles of an interrupted single-process
# run. Loopback only (shared memory between ranks on this machine).
#   check_mpi.sh MPI_BINARY SOURCE_DIR MPIEXEC
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$2" && pwd)
mpiexec=$3
scene=$src/data/scenes/default.toml
work=$(mktemp -d)
pid=0
trap '[ "$pid" -gt 0 ] && kill -9 "$pid" 2>/dev/null; rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"
run_mpi() {  # ranks, args...
  local n=$1
  shift
  # Shared memory only, without single-copy (CMA needs ptrace rights containers often lack).
  "$mpiexec" --allow-run-as-root --oversubscribe --mca btl self,vader --mca btl_vader_single_copy_mechanism none \
    -n "$n" "$bin" "$@"
}
X=omega:150:600:300
Y=mu:1e-4:0.1:40:log
"$bin" map "$scene" --x "$X" --y "$Y" --quiet --long --no-chart -o "$work/one"
check "single process exits 0" "[ $? -eq 0 ]"
for n in 2 3; do
  run_mpi $n map "$scene" --x "$X" --y "$Y" --quiet --long --no-chart --threads 1 -o "$work/mpi$n"
  check "mpirun -n $n exits 0" "[ $? -eq 0 ]"
  for f in map_omega_mu.csv summary_omega_mu.csv boundary_omega_mu.csv; do
    check "mpirun -n $n: $f has the bytes of the single-process run" "cmp -s '$work/one/$f' '$work/mpi$n/$f'"
  done
done
# Interrupted on one process, finished on two ranks.
tiles=$work/cut/.map_omega_mu.tiles
"$bin" map "$scene" --x "$X" --y "$Y" --quiet --long --no-chart --no-boundaries --threads 1 -o "$work/cut" 2>/dev/null &
pid=$!
wait_for_tiles "$tiles" 3
kill -KILL $pid
wait $pid 2>/dev/null
n=$(tile_count "$tiles")
check "the single-process run was cut ($n of 38 tiles)" "[ $n -ge 3 ] && [ $n -lt 38 ]"
run_mpi 2 map "$scene" --x "$X" --y "$Y" --quiet --long --no-chart --no-boundaries --resume -o "$work/cut"
check "mpirun -n 2 --resume exits 0" "[ $? -eq 0 ]"
check "resumed across ranks: same bytes" "cmp -s '$work/one/map_omega_mu.csv' '$work/cut/map_omega_mu.csv'"
run_mpi 2 map "$scene" --x omega:1:2:0 --y "$Y" --quiet --long -o "$work/bad" 2>/dev/null
check "bad axis under mpirun: exit 2, nothing written" "[ $? -eq 2 ] && [ ! -e '$work/bad' ]"
# n balls, the ball count as an axis (model.md §13.8): the same bytes across ranks.
ring=$src/data/scenes/ring11.toml
"$bin" map "$ring" --x omega:150:900:20 --y n:2:4:3 --quiet --long --no-chart -o "$work/n1" --threads 1
for ranks in 2 3; do
  run_mpi $ranks map "$ring" --x omega:150:900:20 --y n:2:4:3 --quiet --long --no-chart -o "$work/n$ranks"
  for f in map_omega_n.csv summary_omega_n.csv; do
    check "n axis, mpirun -n $ranks: $f has the bytes of the single-process run" "cmp -s '$work/n1/$f' '$work/n$ranks/$f'"
  done
done

finish
