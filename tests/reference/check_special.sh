#!/bin/sh
# Runs the C++ analyzer's continuation in one parameter and checks its special points
# (LP, BP, HB) against the mpmath reference (mp_special.py --compare). Exit status: that
# of the comparison (0 pass, 1 mismatch, 2 bad input); 1 also if the analyzer fails.
#
#   check_special.sh BINARY SCENE PARAM FROM TO [--set NAME=VALUE ...] [--rtol 1e-8]
#
# The analyzer starts from the scene's value of PARAM, so FROM goes to it as an override:
#   BINARY continue SCENE --param PARAM --to TO --all -o TMPDIR --set PARAM=FROM [--set ...]
# and the reference reads TMPDIR/special_PARAM.csv. --set options go to both programs
# (an explicit --set PARAM=... would fight FROM: refused); --rtol only to the reference.
# PYTHON overrides the interpreter (default /usr/bin/python3; needs only mpmath).
set -u
if [ $# -lt 5 ]; then
  echo "usage: $0 BINARY SCENE PARAM FROM TO [--set NAME=VALUE ...] [--rtol R]" >&2
  exit 2
fi
bin=$1
scene=$2
param=$3
from=$4
to=$5
shift 5
here=$(cd "$(dirname "$0")" && pwd)
python=${PYTHON:-/usr/bin/python3}

sets=""
rtol=""
while [ $# -gt 0 ]; do
  case $1 in
    --set|--set=*)
      if [ "$1" = --set ]; then
        [ $# -ge 2 ] || { echo "$0: --set needs NAME=VALUE" >&2; exit 2; }
        kv=$2; shift 2
      else
        kv=${1#--set=}; shift
      fi
      case $kv in
        "$param"=*) echo "$0: --set $kv: $param is the continued parameter (use FROM)" >&2; exit 2 ;;
      esac
      sets="$sets --set $kv" ;;
    --rtol) [ $# -ge 2 ] || { echo "$0: --rtol needs a value" >&2; exit 2; }
            rtol="--rtol $2"; shift 2 ;;
    --rtol=*) rtol="--rtol ${1#--rtol=}"; shift ;;
    *) echo "$0: unknown option $1" >&2; exit 2 ;;
  esac
done

tmp=$(mktemp -d "${TMPDIR:-/tmp}/abu_special.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM

# $sets is split on purpose (NAME=VALUE never contains spaces).
# shellcheck disable=SC2086
if ! "$bin" continue "$scene" --param "$param" --to "$to" --all -o "$tmp" --set "$param=$from" $sets; then
  echo "check_special: '$bin continue $scene --param $param --to $to' failed" >&2
  exit 1
fi
csv="$tmp/special_$param.csv"
if [ ! -f "$csv" ]; then
  echo "check_special: the analyzer wrote no $csv" >&2
  exit 1
fi
# shellcheck disable=SC2086
"$python" "$here/mp_special.py" --compare "$csv" "$scene" --param "$param" --from "$from" --to "$to" $sets $rtol
