#!/usr/bin/env bash
# The one configuration of build/ that scripts/run.sh, scripts/test.sh and .ci/run share, so
# that the second command compiles nothing the first compiled (Release, Ninja). Warnings are
# errors where ABU_WERROR=ON is in the environment (.ci/run sets it); a user's newer compiler
# with a new warning still builds. Sourced from the repository's root.
generator=(); [ -f build/CMakeCache.txt ] || generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DABU_WERROR="${ABU_WERROR:-OFF}" >/dev/null
