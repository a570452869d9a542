#!/usr/bin/env bash
# The Debian package (docs/install.md): `cpack -G DEB` in a configured and built build
# directory writes one .deb whose file list holds the program, the library, the CMake
# package, every gnuplot script and the documentation, under /usr, and whose control
# data names the shared libraries the program needs. Run by .ci/run.
#   check_deb.sh BUILD_DIR SOURCE_DIR
set -u
build=$(cd "$1" && pwd)
src=$(cd "$2" && pwd)
. "$(dirname "$0")/../contract.sh"

rm -f "$build"/abu-stability_*.deb
(cd "$build" && cpack -G DEB >"$build/cpack.log" 2>&1)
check "cpack -G DEB exits 0" "[ $? -eq 0 ]" || tail -20 "$build/cpack.log"
deb=$(ls "$build"/abu-stability_*.deb 2>/dev/null | head -1)
check "one .deb written" "[ -n '$deb' ] && [ -f '$deb' ]"
list=$(dpkg-deb -c "$deb" | awk '{print $6}')
has() { grep -qx "$1" <<<"$list"; }
check "./usr/bin/stability-scan" "has ./usr/bin/stability-scan"
check "libabu.a under ./usr/lib" "grep -q '^./usr/lib/.*libabu\.a$' <<<\"\$list\""
check "abuConfig.cmake under ./usr/lib/.../cmake/abu" "grep -q '^./usr/lib/.*cmake/abu/abuConfig\.cmake$' <<<\"\$list\""
check "./usr/include/abu/scan/scan.hpp" "has ./usr/include/abu/scan/scan.hpp"
for gp in "$src"/plots/*.gp; do
  check "./usr/share/abu/plots/$(basename "$gp")" "has ./usr/share/abu/plots/$(basename "$gp")"
done
check "./usr/share/doc/abu/install.md" "has ./usr/share/doc/abu/install.md"
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
check "Depends names libgsl, libfmt and libtomlplusplus" \
  "grep -q libgsl <<<\"\$depends\" && grep -q libfmt <<<\"\$depends\" && grep -q libtomlplusplus <<<\"\$depends\""
check "Recommends gnuplot" "dpkg-deb -f '$deb' Recommends | grep -q gnuplot"
finish
