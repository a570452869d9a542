#!/bin/sh
# Usage: check_lugre.sh BINARY SCENE [--at-balls B1,..,BN] [--set-samples S] [--set omega=V] [--rtol R]
# Runs `BINARY equilibria SCENE --format csv` (with --at-balls / --set-samples passed on)
# and checks every row against the LuGre mpmath reference (mp_lugre.py --compare).
# Exit 0 pass, 1 fail, 2 bad input.
set -u
[ "$#" -ge 2 ] || { echo "usage: $0 BINARY SCENE [--at-balls ..] [--set-samples S] [--rtol R]" >&2; exit 2; }
binary=$1
scene=$2
shift 2
pass=""
set_omega=""
rtol=1e-8
while [ "$#" -gt 0 ]; do
  case "$1" in
    --at-balls|--set-samples) pass="$pass $1 $2"; shift 2 ;;
    --set) pass="$pass --set $2"; set_omega="--set $2"; shift 2 ;;
    --rtol) rtol=$2; shift 2 ;;
    *) echo "$0: unknown option $1" >&2; exit 2 ;;
  esac
done
here=$(cd "$(dirname "$0")" && pwd)
out=$(mktemp) || exit 2
trap 'rm -f "$out"' EXIT
# shellcheck disable=SC2086
"$binary" equilibria "$scene" --format csv -o "$out" $pass || { echo "$0: $binary failed ($?)" >&2; exit 1; }
# shellcheck disable=SC2086
/usr/bin/python3 "$here/mp_lugre.py" --compare "$out" "$scene" --rtol "$rtol" $set_omega
