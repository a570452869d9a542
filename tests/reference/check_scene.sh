#!/bin/sh
# Runs the C++ analyzer on a scene and checks its equilibria CSV against the mpmath
# reference (mp_reference.py --compare). Exit status: that of the comparison (0 pass,
# 1 mismatch, 2 bad input); 1 also if the analyzer itself fails.
#
#   check_scene.sh BINARY SCENE [--set NAME=VALUE ...] [--rtol 1e-8]
#
# --set options go to both the analyzer and the reference, --rtol only to the reference.
# PYTHON overrides the interpreter (default /usr/bin/python3; needs only mpmath).
set -u
if [ $# -lt 2 ]; then
  echo "usage: $0 BINARY SCENE [--set NAME=VALUE ...] [--rtol R]" >&2
  exit 2
fi
bin=$1
scene=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
python=${PYTHON:-/usr/bin/python3}

sets=""
rtol=""
while [ $# -gt 0 ]; do
  case $1 in
    --set) [ $# -ge 2 ] || { echo "$0: --set needs NAME=VALUE" >&2; exit 2; }
           sets="$sets --set $2"; shift 2 ;;
    --set=*) sets="$sets --set ${1#--set=}"; shift ;;
    --rtol) [ $# -ge 2 ] || { echo "$0: --rtol needs a value" >&2; exit 2; }
            rtol="--rtol $2"; shift 2 ;;
    --rtol=*) rtol="--rtol ${1#--rtol=}"; shift ;;
    *) echo "$0: unknown option $1" >&2; exit 2 ;;
  esac
done

tmp=$(mktemp -d "${TMPDIR:-/tmp}/abu_check.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT INT TERM
csv="$tmp/equilibria.csv"

# $sets is split on purpose (NAME=VALUE never contains spaces).
# shellcheck disable=SC2086
if ! "$bin" equilibria "$scene" --format csv -o "$csv" $sets; then
  echo "check_scene: '$bin equilibria $scene' failed" >&2
  exit 1
fi
# shellcheck disable=SC2086
# (verdict_cache.py: in CI, a CSV byte-identical to one that passed earlier in the run passes.)
"$python" "$here/verdict_cache.py" "$csv" -- "$python" "$here/mp_reference.py" --compare "$csv" "$scene" $sets $rtol
