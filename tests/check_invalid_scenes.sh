#!/usr/bin/env bash
# Usage: check_invalid_scenes.sh BINARY SCENE_DIR
#
# For every SCENE_DIR/*.toml (whose first line is `# expect: line=N key=KEY rule=TEXT`)
# runs `BINARY equilibria SCENE --format csv -o WORK/out.csv` from a fresh empty
# directory WORK and checks the CLI contract for bad input: exit code exactly 2, a
# non-empty stderr naming the scene path, line N (as PATH:N:, unless N = 0) and KEY, and nothing written (WORK stays
# empty, so neither out.csv nor a stray file in the working directory appears).
# Prints one line per scene and a final count; exits 1 if any scene fails, 2 on misuse.
set -u

if [ "$#" -ne 2 ]; then
  echo "usage: $0 BINARY SCENE_DIR" >&2
  exit 2
fi

# Absolute paths: the binary runs from inside its temp directory.
binary=$1
case "$binary" in
  */*) binary="$(cd "$(dirname "$binary")" && pwd)/$(basename "$binary")" ;;
esac
if ! scene_dir=$(cd "$2" 2>/dev/null && pwd); then
  echo "$0: no such directory: $2" >&2
  exit 2
fi

# stdout/stderr go to a separate directory so that WORK holds only what the binary wrote.
capture=$(mktemp -d) || exit 2
work=""
trap 'rm -rf "$capture" ${work:+"$work"}' EXIT

# A hanging binary must not hang the test suite.
run=()
if command -v timeout >/dev/null 2>&1; then run=(timeout 60); fi

total=0
failed=0
shopt -s nullglob
scenes=("$scene_dir"/*.toml)
shopt -u nullglob
if [ "${#scenes[@]}" -eq 0 ]; then
  echo "$0: no *.toml scenes in $scene_dir" >&2
  exit 2
fi

for scene in "${scenes[@]}"; do  # glob expansion is sorted
  total=$((total + 1))
  name=$(basename "$scene")
  problems=()

  expect=$(head -n 1 "$scene")
  if [[ "$expect" =~ ^"# expect: line="([0-9]+)" key="([^ ]*)" rule=". ]]; then
    line=${BASH_REMATCH[1]}
    key=${BASH_REMATCH[2]}
  else
    line=0
    key=""
    problems+=("first line is not '# expect: line=N key=KEY rule=TEXT'")
  fi

  rm -rf "$work"
  work=$(mktemp -d) || exit 2
  (cd "$work" && "${run[@]}" "$binary" equilibria "$scene" --format csv -o "$work/out.csv") \
    >"$capture/stdout" 2>"$capture/stderr" </dev/null
  code=$?

  [ "$code" -eq 2 ] || problems+=("exit code $code, expected 2")
  if [ ! -s "$capture/stderr" ]; then
    problems+=("stderr is empty")
  else
    err=$(cat "$capture/stderr")
    [[ "$err" == *"$scene"* ]] || problems+=("stderr does not name the scene path")
    # line=0: the rule is about the whole file (a missing table or key) and names no line.
    if [ "$line" -gt 0 ] && [[ "$err" != *"$scene:$line:"* ]]; then
      problems+=("stderr does not name line $line")
    fi
    # Look for the key outside the path: `ball` or `rolling` may be part of the file name.
    rest=${err//"$scene"/}
    if [ -n "$key" ] && [[ "$rest" != *"$key"* ]]; then
      problems+=("stderr does not name key '$key'")
    fi
  fi
  written=$(cd "$work" && find . -mindepth 1 | head -n 5 | tr '\n' ' ')
  [ -z "$written" ] && [ ! -e "$work/out.csv" ] || problems+=("wrote files: $written")

  if [ "${#problems[@]}" -eq 0 ]; then
    echo "ok    $name"
  else
    failed=$((failed + 1))
    msg=$(printf '%s; ' "${problems[@]}")
    echo "FAIL  $name: ${msg%; }"
    echo "      stderr: $(head -c 300 "$capture/stderr" | tr '\n' ' ')"
  fi
done

echo "$((total - failed)) of $total invalid scenes rejected correctly ($failed failed)"
[ "$failed" -eq 0 ]
