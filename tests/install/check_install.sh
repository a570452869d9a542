#!/usr/bin/env bash
# The installed package (docs/install.md): `cmake --install` of the build tree
# into an empty prefix puts every part where GNUInstallDirs says; the installed program,
# moved elsewhere with its prefix, draws with its own gnuplot scripts (not the source
# tree's) and names ABU_PLOTS_DIR when the scripts are missing; examples/consumer
# configures against the prefix with find_package(abu CONFIG), builds, and prints the
# equilibria the installed stability-scan writes for the same scene, number for number.
#   check_install.sh BUILD_DIR SOURCE_DIR CXX_COMPILER [COMPILER_LAUNCHER]
set -u
build=$(cd "$1" && pwd)
src=$(cd "$2" && pwd)
cxx=$3
launcher=${4:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
. "$(dirname "$0")/../contract.sh"
unset ABU_PLOTS_DIR

# --- install into an empty prefix ------------------------------------------------------------
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log" 2>&1
check "cmake --install exits 0" "[ $? -eq 0 ]"
p=$work/prefix
check "bin/stability-scan" "[ -x '$p/bin/stability-scan' ]"
check "include/abu: the public headers" "[ -f '$p/include/abu/scan/scan.hpp' ] && [ -f '$p/include/abu/input/scene.hpp' ]"
check "every header of include/abu installed" \
  "[ \$(cd '$src/include' && find abu -name '*.hpp' | wc -l) -eq \$(cd '$p/include' && find abu -name '*.hpp' | wc -l) ]"
libdir=$(dirname "$(find "$p" -name libabu.a | head -1)")
check "libabu.a under lib" "[ -f '$libdir/libabu.a' ] && case '$libdir' in '$p'/lib*) true;; *) false;; esac"
check "abuConfig.cmake, abuConfigVersion.cmake, abuTargets.cmake" \
  "[ -f '$libdir/cmake/abu/abuConfig.cmake' ] && [ -f '$libdir/cmake/abu/abuConfigVersion.cmake' ] && [ -f '$libdir/cmake/abu/abuTargets.cmake' ]"
check "the exported targets name no path of the source or build tree" \
  "! grep -h -e '$src' -e '$build' '$libdir'/cmake/abu/*.cmake"
# Eigen is the one dependency the headers include; fmt, GSL, toml++ are $<LINK_ONLY:...>.
link_only() {
  local line
  line=$(grep 'INTERFACE_LINK_LIBRARIES' "$libdir/cmake/abu/abuTargets.cmake")
  grep -qF 'Eigen3::Eigen;' <<<"$line" && for dep in fmt::fmt GSL::gsl tomlplusplus::tomlplusplus; do
    grep -qF "<LINK_ONLY:$dep>" <<<"$line" || return 1
  done
}
check "the exported target links Eigen publicly, fmt, GSL and toml++ only at link time" link_only
check "share/abu/plots: every gnuplot script" \
  "[ \$(ls '$src'/plots/*.gp | wc -l) -eq \$(ls '$p'/share/abu/plots/*.gp | wc -l) ]"
check "share/abu/scenes/default.toml" "[ -f '$p/share/abu/scenes/default.toml' ]"
check "share/doc/abu: README.md, model.md, install.md" \
  "[ -f '$p/share/doc/abu/README.md' ] && [ -f '$p/share/doc/abu/model.md' ] && [ -f '$p/share/doc/abu/install.md' ]"

# --- the installed program, moved: its own scripts, relative to itself -----------------------
mv "$p" "$work/moved"
p=$work/moved
scene=$p/share/abu/scenes/default.toml
# Lines appended to the installed copy of sweep.gp leave a mark: they show which copy of
# the script was run.
printf "set print '%s'\nprint 'installed'\nunset print\n" "$work/installed-script-ran" >>"$p/share/abu/plots/sweep.gp"
(cd "$work" && "$p/bin/stability-scan" sweep "$scene" --param omega --from 100 --to 1000 --steps 4 -o "$work/sweep" \
  >"$work/sweep.out" 2>&1)
check "installed sweep (prefix moved) exits 0" "[ $? -eq 0 ]"
check "installed sweep draws its chart" "[ -s '$work/sweep/sweep_omega.png' ]"
check "... with the installed sweep.gp (found relative to the binary)" "[ -f '$work/installed-script-ran' ]"
mkdir "$work/noplots"
ABU_PLOTS_DIR=$work/noplots "$p/bin/stability-scan" sweep "$scene" --param omega --from 100 --to 1000 --steps 4 \
  -o "$work/sweep2" >"$work/sweep2.out" 2>&1
status=$?
check "ABU_PLOTS_DIR overrides: a directory without scripts fails the chart (exit 4, the CSVs written)" "[ $status -eq 4 ] && [ -s '$work/sweep2/sweep_omega.csv' ]"
check "... naming the script and ABU_PLOTS_DIR" "grep -q 'noplots/sweep.gp not found' '$work/sweep2.out' && grep -q ABU_PLOTS_DIR '$work/sweep2.out'"

# --- examples/consumer against the installed package ----------------------------------------
cmake -S "$src/examples/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$p" -DCMAKE_CXX_COMPILER="$cxx" \
  ${launcher:+-DCMAKE_CXX_COMPILER_LAUNCHER="$launcher"} >"$work/consumer.log" 2>&1
check "consumer configures with find_package(abu 0.1 CONFIG)" "[ $? -eq 0 ]" || cat "$work/consumer.log"
check "... finding the moved prefix's package" "grep -q '$p' '$work/consumer/CMakeCache.txt'"
cmake --build "$work/consumer" >>"$work/consumer.log" 2>&1
check "consumer builds and links against libabu.a" "[ $? -eq 0 ]" || tail -30 "$work/consumer.log"
"$work/consumer/abu_consumer" "$scene" >"$work/consumer.csv" 2>"$work/consumer.err"
check "consumer runs" "[ $? -eq 0 ]"
check "... and knows the library's version (ABU_VERSION from abu::abu)" \
  "head -1 '$work/consumer.csv' | grep -qF \"# abu \$('$p/bin/stability-scan' --version | awk '{print \$2}'),\""
"$p/bin/stability-scan" equilibria "$scene" --format csv >"$work/cli.csv"
check "the consumer's equilibria are the CLI's, every number" \
  "/usr/bin/python3 '$(dirname "$0")/compare_equilibria.py' '$work/consumer.csv' '$work/cli.csv'"
"$work/consumer/abu_consumer" "$scene" omega=150 >"$work/consumer150.csv" 2>&1
"$p/bin/stability-scan" equilibria "$scene" --format csv --set omega=150 >"$work/cli150.csv"
check "... also with an override (omega=150, below resonance)" \
  "/usr/bin/python3 '$(dirname "$0")/compare_equilibria.py' '$work/consumer150.csv' '$work/cli150.csv'"
"$work/consumer/abu_consumer" "$scene" omega=-1 >/dev/null 2>"$work/bad.err"
check "a bad override is the library's InputError (exit 2, names the key)" "[ $? -eq 2 ] && grep -q omega '$work/bad.err'"
finish
