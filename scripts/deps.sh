#!/usr/bin/env bash
# Installs the Debian packages the build, the tests and the charts need, if missing.
# Sourced by scripts/run.sh and scripts/test.sh; safe to run again (installs nothing
# when everything is there). Extra packages can be passed as arguments.
set -euo pipefail
# python3-gmpy2: mpmath's GMP backend (mpmath uses it when it can import gmpy2), the same
# digits with about 20 % less CPU in the mpmath references (docs/developers.md, CI).
packages=(cmake g++ make ninja-build pkg-config libeigen3-dev libgsl-dev libarpack2-dev libfmt-dev catch2 libcli11-dev
          libtomlplusplus-dev libnlopt-cxx-dev gnuplot-nox python3 python3-mpmath python3-gmpy2
          python3-dev pybind11-dev python3-numpy python3-scipy python3-pytest python3-sympy "$@")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
