#!/usr/bin/env bash
# Runs icm_param on every case of the bad-input corpus (expected.tsv, written by generate.py)
# and checks the promise "a clear error, never a crash, hang or half-written file":
#   - every run ends within 10 s, under a 2 GB address-space limit, without a signal;
#   - the exit status is the expected one (0, or 1 for a refusal), and stderr holds the
#     expected reason;
#   - a refused input leaves the output files it was given byte-identical and no other file
#     (no temporary) behind; an accepted one writes an OBJ with texture coordinates.
#
# usage: run_corpus.sh ICM_PARAM CORPUS_DIR [--no-memory-limit]
# (--no-memory-limit for sanitizer builds, whose shadow memory needs a larger address space)
set -u
exe=$(realpath "$1")
corpus=$(realpath "$2")
memory_limit_kb=2097152
[ "${3:-}" = "--no-memory-limit" ] && memory_limit_kb=unlimited
time_limit=10

work=$(mktemp -d "${TMPDIR:-/tmp}/icm_corpus.XXXXXX")
trap 'rm -rf "$work"' EXIT

failures=0
cases=0
slowest=0
slowest_case=
fail() {
  echo "FAIL $1: $2"
  failures=$((failures + 1))
}

while IFS=$'\t' read -r file args expect message; do
  case "$file" in '#'*|'') continue ;; esac
  [ "$args" = "-" ] && args=
  [ "$message" = "-" ] && message=
  cases=$((cases + 1))
  name="$file${args:+ $args}"
  dir="$work/case$cases"
  mkdir -p "$dir"
  # The user's previous outputs: a refusal must leave them exactly as they are.
  printf 'previous OBJ of the user\n' >"$dir/out.obj"
  printf '<svg>previous</svg>\n' >"$dir/out.svg"
  start=$(date +%s%N)
  # shellcheck disable=SC2086 # the arguments of a case are split on purpose
  (cd "$dir" && ulimit -v "$memory_limit_kb" &&
    exec timeout -s KILL "$time_limit" "$exe" "$corpus/$file" -o out.obj --svg out.svg $args) \
    >"$work/stdout" 2>"$work/stderr"
  status=$?
  elapsed_ms=$((($(date +%s%N) - start) / 1000000))
  if [ "$elapsed_ms" -gt "$slowest" ]; then
    slowest=$elapsed_ms
    slowest_case=$name
  fi
  err=$(cat "$work/stderr")
  if [ "$status" -ge 124 ]; then
    fail "$name" "killed, crashed or timed out (status $status): $err"
    continue
  fi
  if [ "$status" -ne "$expect" ]; then
    fail "$name" "exit status $status, expected $expect: $err"
    continue
  fi
  if [ -n "$message" ] && ! grep -qF -- "$message" "$work/stderr"; then
    fail "$name" "stderr does not name the reason '$message': $err"
  fi
  listing=$(cd "$dir" && ls -A | tr '\n' ' ')
  if [ "$expect" -ne 0 ]; then
    [ "$(head -c 11 "$work/stderr")" = "icm_param: " ] || fail "$name" "the reason is not one icm_param line: $err"
    [ "$(wc -l <"$work/stderr")" -eq 1 ] || fail "$name" "more than one line on stderr: $err"
    [ "$(cat "$dir/out.obj")" = "previous OBJ of the user" ] || fail "$name" "out.obj was changed"
    [ "$(cat "$dir/out.svg")" = "<svg>previous</svg>" ] || fail "$name" "out.svg was changed"
    [ "$listing" = "out.obj out.svg " ] || fail "$name" "files left behind: $listing"
  else
    grep -q '^vt ' "$dir/out.obj" || fail "$name" "no texture coordinates in out.obj"
    grep -q '</svg>' "$dir/out.svg" || fail "$name" "out.svg is not a complete SVG"
    [ "$listing" = "out.obj out.svg " ] || fail "$name" "files left behind: $listing"
  fi
done <"$corpus/expected.tsv"

echo "$cases cases, $failures failures; slowest: $slowest ms ($slowest_case)"
[ "$cases" -ge 60 ] || { echo "FAIL: fewer than 60 cases"; exit 1; }
[ "$failures" -eq 0 ]
