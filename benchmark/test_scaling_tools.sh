#!/usr/bin/env bash
# Tests of the BFF side-by-side's tools (ctest compare.write_mesh, scaling.whole_process):
#
#   benchmark/test_scaling_tools.sh write-mesh COMPARE MESH.off   compare --write-mesh
#   benchmark/test_scaling_tools.sh whole-process                 benchmark/whole_process.py
#
# write-mesh: the written OBJ and OFF read back with the vertices and faces of compare's row
# (after --subdivide 1: four times the faces of MESH), and wrong uses are refused with their
# message: a file name without .obj/.off/.ply, two meshes, no value (exit 2), a folder that
# does not exist (exit 1).
# whole-process: rows of a command that succeeds, fails, crashes, runs out of time or writes
# no output, each with its status, and the seconds_* of a command's JSON.
set -uo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
python="${PYTHON:-/usr/bin/python3}"
[ -x "$python" ] || python="python3"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/icm_test_scaling.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# expect_refusal CODE MESSAGE ARGS...: compare ARGS exits with CODE and says MESSAGE on stderr.
expect_refusal() {
  local code="$1" message="$2"
  shift 2
  "$compare" "$@" > "$tmp/out" 2> "$tmp/err"
  local got=$?
  [ "$got" -eq "$code" ] || fail "compare $*: exit $got, expected $code"
  grep -qF -- "$message" "$tmp/err" || fail "compare $*: no '$message' in: $(head -c 300 "$tmp/err")"
}

# field JSON KEY: the value of KEY in the JSON object JSON.
field() { "$python" -c 'import json, sys; print(json.loads(sys.argv[1])[sys.argv[2]])' "$1" "$2"; }

test_write_mesh() {
  compare="$1"
  local mesh="$2"
  local base_faces
  base_faces="$(awk 'NR == 2 { print $2; exit }' "$mesh")"
  for ext in obj off; do
    local row
    row="$("$compare" --json --quiet --runs 1 --methods icm_free_boundary --subdivide 1 \
                      --write-mesh "$tmp/m.$ext" "$mesh")" || fail "compare --write-mesh $tmp/m.$ext: exit $?"
    [ -f "$tmp/m.$ext" ] || { fail "compare --write-mesh $tmp/m.$ext: no file"; continue; }
    local v f
    if [ "$ext" = obj ]; then
      v="$(grep -c '^v ' "$tmp/m.obj")"
      f="$(grep -c '^f ' "$tmp/m.obj")"
    else
      read -r v f _ < <(grep -v '^#' "$tmp/m.off" | sed -n 2p)
    fi
    [ "$v" = "$(field "$row" vertices)" ] || fail "$ext: $v vertices, compare's row has $(field "$row" vertices)"
    [ "$f" = "$(field "$row" faces)" ] || fail "$ext: $f faces, compare's row has $(field "$row" faces)"
    [ "$f" = $((4 * base_faces)) ] || fail "$ext: $f faces after --subdivide 1, expected $((4 * base_faces))"
    [ "$(field "$row" status)" = ok ] || fail "$ext: status $(field "$row" status)"
  done
  # The OBJ written is a mesh compare reads again, with the same counts.
  local again
  again="$("$compare" --json --quiet --runs 1 --methods icm_free_boundary "$tmp/m.obj")"
  [ "$(field "$again" faces)" = $((4 * base_faces)) ] || fail "the written OBJ read back: $(field "$again" faces) faces"

  expect_refusal 2 "--write-mesh needs a file name ending in .obj, .off or .ply, not '$tmp/m.txt'" \
    --write-mesh "$tmp/m.txt" "$mesh"
  expect_refusal 2 "--write-mesh writes one mesh; 2 meshes given" --write-mesh "$tmp/two.obj" "$mesh" "$mesh"
  expect_refusal 2 "option --write-mesh needs a value" "$mesh" --write-mesh
  expect_refusal 1 "compare: --write-mesh $tmp/no/such/folder/m.obj:" --json --methods icm_free_boundary \
    --write-mesh "$tmp/no/such/folder/m.obj" "$mesh"
  [ ! -s "$tmp/out" ] || fail "a mesh that cannot be written still got rows: $(cat "$tmp/out")"
}

# whole ARGS...: the row whole_process.py prints for ARGS (on an OBJ of 2 vertices, 1 face).
whole() {
  "$python" "$here/whole_process.py" --method test --obj "$tmp/tri.obj" "$@"
}

# expect_status ROW STATUS: the row's status starts with STATUS.
expect_status() {
  local got
  got="$(field "$1" status)"
  case "$got" in "$2"*) ;; *) fail "status '$got', expected '$2...' in $1" ;; esac
}

test_whole_process() {
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$tmp/tri.obj"
  local row
  row="$(whole --runs 2 -- true)"
  expect_status "$row" ok
  [ "$(field "$row" faces)" = 1 ] && [ "$(field "$row" vertices)" = 3 ] || fail "counts of the OBJ: $row"
  [ "$(field "$row" runs)" = 2 ] || fail "--runs 2: $row"
  "$python" -c 'import json, sys; r = json.loads(sys.argv[1]); assert r["seconds"] >= 0 and r["peak_rss_mb"] > 0' \
    "$row" || fail "seconds and peak of: $row"
  expect_status "$(whole -- sh -c 'echo no such mesh >&2; exit 3')" "failed (exit code 3): no such mesh"
  expect_status "$(whole -- sh -c 'kill -SEGV $$')" "crashed (signal 11)"
  expect_status "$(whole --time-limit 0.5 -- sleep 30)" timeout
  expect_status "$(whole --output "$tmp/none.obj" -- true)" "failed: no output file"
  expect_status "$(whole -- "$tmp/no-such-program")" "failed: cannot start"
  expect_status "$("$python" "$here/whole_process.py" --method test --obj "$tmp/none.obj" -- true)" \
    "failed: cannot read"
  row="$(whole --json-stdout -- sh -c 'echo progress; echo "{\"status\": \"ok\", \"seconds_parameterize\": 0.25}"')"
  [ "$(field "$row" seconds_parameterize)" = 0.25 ] || fail "seconds_parameterize of the command's JSON: $row"
  expect_status "$(whole --json-stdout -- sh -c 'echo "{\"status\": \"failed: folded\"}"')" "failed: folded"
}

case "${1:-}" in
  write-mesh) test_write_mesh "$2" "$3" ;;
  whole-process) test_whole_process ;;
  *) echo "usage: $0 write-mesh COMPARE MESH.off | whole-process" >&2; exit 2 ;;
esac
[ "$failures" -eq 0 ] && echo "test_scaling_tools $1: passed" || exit 1
