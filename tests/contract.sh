# Helpers of the command-line contract scripts (sourced by tests/cli/check_cli.sh,
# tests/map/check_map.sh, tests/map/check_mpi.sh): one named check per line, a count of
# failures, the exit status from it.
fails=0
pass() { echo "ok   $1"; }
fail() { echo "FAIL $1"; fails=$((fails + 1)); }
check() { if eval "$2"; then pass "$1"; else fail "$1"; fi; }
finish() {
  echo "$fails failure(s)"
  [ "$fails" -eq 0 ]
}
# Finished tile files of a map's tile directory $1 (temporaries are *.part).
tile_count() { ls "$1" 2>/dev/null | grep -c '^tile'; }
# Waits up to 20 s until tile directory $1 holds at least $2 finished tiles.
wait_for_tiles() {
  for _ in $(seq 2000); do
    [ "$(tile_count "$1")" -ge "$2" ] && return 0
    sleep 0.01
  done
  return 1
}
