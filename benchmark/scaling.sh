#!/usr/bin/env bash
# Scaling series: time and peak memory of the parameterizers against the number of faces.
#
#   benchmark/scaling.sh [COMPARE [OUTDIR [MESH]]]
#
#   COMPARE  the compare binary            (default: build/benchmark/compare)
#   OUTDIR   where the results go          (default: doc/figures)
#   MESH     the base mesh, a disk         (default: lion-head.off from the shared mesh set)
#
# Environment: KMIN, KMAX (Loop subdivision levels, default 0..3: lion-head's 16.7k faces
# times 4^K, 1.07M faces at K=3), METHODS (default icm_free_boundary,lscm), TIME_LIMIT
# (seconds per run, default 3600), RUNS (passed as --runs when set; compare's default is 3
# runs when one takes < 2 s, else 1), NAME (file stem of the outputs, default scaling).
#
# For every level K it runs `compare --subdivide K --json` and appends the JSON lines to
# OUTDIR/NAME.jsonl as soon as the level is done, then writes OUTDIR/NAME.md (the table
# faces | method | seconds | peak MB | Newton its | status, also printed) and, when
# python3-matplotlib is installed, the log-log plot OUTDIR/NAME.svg.
# Default paths are relative to the repository root; given paths to the current directory.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"

compare="${1:-$root/build/benchmark/compare}"
outdir="${2:-$root/doc/figures}"
mesh="${3:-}"
kmin="${KMIN:-0}"
kmax="${KMAX:-3}"
methods="${METHODS:-icm_free_boundary,lscm}"
time_limit="${TIME_LIMIT:-3600}"
name="${NAME:-scaling}"
python="${PYTHON:-/usr/bin/python3}"
[ -x "$python" ] || python="python3"

if [ -z "$mesh" ]; then
  for candidate in \
      "${ICM_MESH_DIR:-/nonexistent}/lion-head.off" \
      "$root/examples/data/lion-head.off" \
      "$root/../shared/data/meshes/lion-head.off"; do
    if [ -f "$candidate" ]; then mesh="$candidate"; break; fi
  done
  if [ -z "$mesh" ]; then
    echo "scaling.sh: lion-head.off not found; give a mesh: $0 COMPARE OUTDIR MESH" >&2
    exit 2
  fi
fi
if [ ! -x "$compare" ]; then
  echo "scaling.sh: $compare is not an executable; build it first:" >&2
  echo "  cmake -S $root -B $root/build -DCMAKE_BUILD_TYPE=Release && cmake --build $root/build --target compare" >&2
  exit 2
fi
if [ ! -f "$mesh" ]; then
  echo "scaling.sh: $mesh: no such file" >&2
  exit 2
fi

mkdir -p "$outdir"
series="$outdir/$name.jsonl"
: > "$series"

runs_opt=()
if [ -n "${RUNS:-}" ]; then runs_opt=(--runs "$RUNS"); fi

echo "scaling.sh: $(basename "$mesh"), Loop subdivision K=$kmin..$kmax, methods $methods," \
     "time limit ${time_limit}s per run -> $series" >&2
status=0
for ((k = kmin; k <= kmax; ++k)); do
  start=$(date +%s)
  echo "scaling.sh: K=$k ..." >&2
  # One level at a time, appended when it is done, so a long series can be watched and a
  # killed one keeps its finished levels.
  if ! out="$("$compare" --json --quiet --subdivide "$k" --methods "$methods" \
                --time-limit "$time_limit" "${runs_opt[@]}" "$mesh")"; then
    status=1
  fi
  printf '%s\n' "$out" >> "$series"
  printf '%s\n' "$out" | "$python" -c '
import json, sys
for line in sys.stdin:
    if line.strip():
        r = json.loads(line)
        print("scaling.sh:   {faces} faces  {method}: {status}, {seconds} s, {peak_rss_mb} MB".format(**r),
              file=sys.stderr)
'
  echo "scaling.sh: K=$k done in $(( $(date +%s) - start )) s" >&2
done

"$python" "$here/plot_scaling.py" "$series" --table "$outdir/$name.md" \
  --plot "$outdir/$name.svg" \
  --title "$(basename "$mesh" | sed 's/\.[^.]*$//'), Loop subdivision K=$kmin..$kmax"
exit $status
