#!/bin/sh
# Usage: check_lugre.sh BINARY SCENE [--at-balls B1,..,BN] [--set-samples S] [--set omega=V] [--rtol R]
# Runs `BINARY equilibria SCENE --format csv` (with --at-balls / --set-samples passed on)
# and checks every row against the LuGre mpmath reference (mp_lugre.py --compare).
# With --sweep-omega FROM:TO:STEPS it runs `BINARY sweep SCENE --param omega` instead
# (--set-samples passed on) and checks every value's rows (mp_lugre.py --compare-sweep).
# Exit 0 pass, 1 fail, 2 bad input.
set -u
[ "$#" -ge 2 ] || { echo "usage: $0 BINARY SCENE [--at-balls ..] [--set-samples S] [--rtol R]" >&2; exit 2; }
binary=$1
scene=$2
shift 2
pass=""
set_omega=""
rtol=1e-8
sweep=""
while [ "$#" -gt 0 ]; do
  case "$1" in
    --at-balls|--set-samples) pass="$pass $1 $2"; shift 2 ;;
    --set) pass="$pass --set $2"; set_omega="--set $2"; shift 2 ;;
    --rtol) rtol=$2; shift 2 ;;
    --sweep-omega) sweep=$2; shift 2 ;;
    *) echo "$0: unknown option $1" >&2; exit 2 ;;
  esac
done
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp) || exit 2
trap 'rm -f "$out"' EXIT
if [ -n "$sweep" ]; then
  dir=$(mktemp -d) || exit 2
  trap 'rm -f "$out"; rm -rf "$dir"' EXIT
  from=${sweep%%:*}; rest=${sweep#*:}; to=${rest%%:*}; steps=${rest#*:}
  # shellcheck disable=SC2086
  "$binary" sweep "$scene" --param omega --from "$from" --to "$to" --steps "$steps" -o "$dir" $pass \
    || { echo "$0: $binary sweep failed ($?)" >&2; exit 1; }
  # (verdict_cache.py: in CI, output byte-identical to one that passed earlier in the run passes.)
  /usr/bin/python3 "$here/verdict_cache.py" "$dir/sweep_omega.csv" -- \
    /usr/bin/python3 "$here/mp_lugre.py" --compare-sweep "$dir/sweep_omega.csv" "$scene" --rtol "$rtol"
  exit $?
fi
# shellcheck disable=SC2086
"$binary" equilibria "$scene" --format csv -o "$out" $pass || { echo "$0: $binary failed ($?)" >&2; exit 1; }
# shellcheck disable=SC2086
/usr/bin/python3 "$here/verdict_cache.py" "$out" -- /usr/bin/python3 "$here/mp_lugre.py" --compare "$out" "$scene" \
  --rtol "$rtol" $set_omega
