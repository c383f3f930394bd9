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
# runs when one takes < 2 s, else 1), NAME (file stem of the outputs, default scaling),
# MESHES (several meshes, separated by spaces, instead of MESH; then KMAX defaults to 0).
#
# BFF=path/to/bff-command-line (Boundary First Flattening's command line) adds BFF side by
# side: at each level compare also writes the subdivided mesh as OBJ (--write-mesh, into a
# temporary folder removed at the end), and benchmark/whole_process.py times two whole
# processes on that OBJ, reading and writing included: icm_param FILE -o OUT.obj --cones 0
# --json --quiet (method icm_param_whole, with its seconds_parameterize; ICM_PARAM, default
# build/examples/icm_param) and BFF FILE OUT.obj $BFF_ARGS (method bff; BFF's default is the
# free-boundary flattening of a disk without cones, the counterpart of --cones 0). Their rows
# go into the series beside compare's (a failure or timeout is a row with its status; a mesh
# compare finds is not a disk gets rows "skipped: not a disk", BFF would fill its holes or
# cut it), and the table ends with ICM / BFF per size. With BFF, METHODS defaults to icm_free_boundary.
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
kmax="${KMAX:-$([ -n "${MESHES:-}" ] && echo 0 || echo 3)}"
bff="${BFF:-}"
icm_param="${ICM_PARAM:-$root/build/examples/icm_param}"
methods="${METHODS:-$([ -n "$bff" ] && echo icm_free_boundary || echo icm_free_boundary,lscm)}"
time_limit="${TIME_LIMIT:-3600}"
name="${NAME:-scaling}"
python="${PYTHON:-/usr/bin/python3}"
[ -x "$python" ] || python="python3"

if [ -n "${MESHES:-}" ]; then
  if [ -n "$mesh" ]; then
    echo "scaling.sh: give MESH or MESHES, not both" >&2
    exit 2
  fi
  read -r -a meshes <<< "$MESHES"
elif [ -z "$mesh" ]; then
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
[ -n "${MESHES:-}" ] || meshes=("$mesh")
if [ ! -x "$compare" ]; then
  echo "scaling.sh: $compare is not an executable; build it first:" >&2
  echo "  cmake -S $root -B $root/build -DCMAKE_BUILD_TYPE=Release && cmake --build $root/build --target compare" >&2
  exit 2
fi
for m in "${meshes[@]}"; do
  if [ ! -f "$m" ]; then
    echo "scaling.sh: $m: no such file" >&2
    exit 2
  fi
done
for tool in ${bff:+"$bff" "$icm_param"}; do
  if [ ! -x "$tool" ]; then
    echo "scaling.sh: $tool is not an executable (BFF=$bff needs it)" >&2
    exit 2
  fi
done
tmp=""
if [ -n "$bff" ]; then
  tmp="$(mktemp -d "${TMPDIR:-/tmp}/icm_scaling.XXXXXX")"
  trap 'rm -rf "$tmp"' EXIT
  # Which BLAS each side runs on (Debian's alternatives decide libblas.so.3).
  for tool in "$icm_param" "$bff"; do
    blas="$(ldd "$tool" 2>/dev/null | awk '$1 == "libblas.so.3" { print $3 }')"
    echo "scaling.sh: $(basename "$tool"): libblas.so.3 -> ${blas:+$(readlink -f "$blas")}" >&2
  done
fi

mkdir -p "$outdir"
series="$outdir/$name.jsonl"
: > "$series"

runs_opt=()
if [ -n "${RUNS:-}" ]; then runs_opt=(--runs "$RUNS"); fi

# Prints the rows of JSON lines on stdin as progress lines.
progress() {
  "$python" -c '
import json, sys
for line in sys.stdin:
    if line.strip():
        r = json.loads(line)
        print("scaling.sh:   {faces} faces  {method}: {status}, {seconds} s, {peak_rss_mb} MB".format(**r),
              file=sys.stderr)
'
}

# Rows icm_param_whole and bff that say "skipped: not a disk" when compare's rows on stdin
# found the mesh is not one (exit 0), else nothing (exit 1).
not_a_disk() {
  "$python" -c '
import json, sys
for line in sys.stdin:
    r = json.loads(line) if line.strip() else {}
    if str(r.get("status", "")).startswith("skipped: not a disk"):
        for method in ("icm_param_whole", "bff"):
            print(json.dumps({"mesh": r["mesh"], "vertices": r["vertices"], "faces": r["faces"],
                              "method": method, "status": r["status"], "seconds": None,
                              "peak_rss_mb": None}))
        sys.exit(0)
sys.exit(1)
'
}

# The whole processes of icm_param and BFF on the OBJ that compare wrote: rows on stdout.
whole_processes() {
  local obj="$1" label="$2" bff_args=()
  read -r -a bff_args <<< "${BFF_ARGS:-}"
  "$python" "$here/whole_process.py" --method icm_param_whole --obj "$obj" --mesh "$label" \
    --time-limit "$time_limit" ${RUNS:+--runs "$RUNS"} --json-stdout --output "$tmp/icm_uv.obj" -- \
    "$icm_param" "$obj" -o "$tmp/icm_uv.obj" --cones 0 --json --quiet
  "$python" "$here/whole_process.py" --method bff --obj "$obj" --mesh "$label" \
    --time-limit "$time_limit" ${RUNS:+--runs "$RUNS"} --output "$tmp/bff_uv.obj" -- \
    "$bff" "$obj" "$tmp/bff_uv.obj" "${bff_args[@]}"
  rm -f "$tmp/icm_uv.obj" "$tmp/bff_uv.obj"
}

names="$(for m in "${meshes[@]}"; do basename "$m"; done | paste -sd' ')"
echo "scaling.sh: $names, Loop subdivision K=$kmin..$kmax, methods $methods${bff:+ + icm_param_whole, bff}," \
     "time limit ${time_limit}s per run -> $series" >&2
status=0
for m in "${meshes[@]}"; do
  label="$(basename "$m" | sed 's/\.[^.]*$//')"
  for ((k = kmin; k <= kmax; ++k)); do
    start=$(date +%s)
    echo "scaling.sh: $label K=$k ..." >&2
    write_opt=()
    if [ -n "$bff" ]; then write_opt=(--write-mesh "$tmp/mesh.obj"); rm -f "$tmp/mesh.obj"; fi
    # One level at a time, appended when it is done, so a long series can be watched and a
    # killed one keeps its finished levels.
    if ! out="$("$compare" --json --quiet --subdivide "$k" --methods "$methods" \
                  --time-limit "$time_limit" "${runs_opt[@]}" "${write_opt[@]}" "$m")"; then
      status=1
    fi
    if [ -n "$bff" ]; then
      if skipped="$(printf '%s\n' "$out" | not_a_disk)"; then
        # BFF's default flattens a disk; on other meshes it fills holes or cuts to 8 cones.
        out="$out"$'\n'"$skipped"
      elif [ -f "$tmp/mesh.obj" ]; then
        out="$out"$'\n'"$(whole_processes "$tmp/mesh.obj" "$label")" || status=1
      else
        echo "scaling.sh: compare wrote no mesh for $label K=$k; no BFF rows" >&2
        status=1
      fi
    fi
    out="$(printf '%s\n' "$out" | sed '/^$/d')"
    printf '%s\n' "$out" >> "$series"
    printf '%s\n' "$out" | progress
    echo "scaling.sh: $label K=$k done in $(( $(date +%s) - start )) s" >&2
  done
done

if [ ${#meshes[@]} -eq 1 ]; then
  title="$label, Loop subdivision K=$kmin..$kmax"
else
  title="${#meshes[@]} meshes, Loop subdivision K=$kmin..$kmax"
fi
"$python" "$here/plot_scaling.py" "$series" --table "$outdir/$name.md" \
  --plot "$outdir/$name.svg" --title "$title"
exit $status
