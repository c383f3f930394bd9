#!/bin/sh
# Parameterizes the bundled meshes with `python3 -m icm.batch` (doc/batch.md), each in a process
# of its own, and prints a line per mesh from OUTDIR/summary.jsonl:
#
#     PYTHONPATH=build/python sh examples/batch_example.sh [OUTDIR] [BATCH OPTION...]
#
# OUTDIR defaults to batch_out. The options go to icm.batch: by default a local Dask cluster of
# one single-threaded worker per core; `--serial` runs without Dask, `--scheduler tcp://HOST:8786`
# on an existing cluster whose workers see this directory at the same path. Run it again with
# `--resume` and the meshes already written are skipped. The exit status is icm.batch's.
set -u

python=${PYTHON:-/usr/bin/python3}
data=$(dirname "$0")/data
outdir=${1:-batch_out}
[ $# -gt 0 ] && shift

"$python" -m icm.batch "$data"/*.off -O "$outdir" "$@"
status=$?
[ -f "$outdir/summary.jsonl" ] || exit "$status"

"$python" - "$outdir/summary.jsonl" <<'EOF'
import json
import sys

with open(sys.argv[1], encoding="utf-8") as rows:
    for row in map(json.loads, rows):
        if row["status"] == "ok":
            print(f"{row['output']}: {row['charts']} chart(s), {row['cones']} cones, {row['seam_edges']} seam edges, "
                  f"log area distortion {row['log_area_distortion']:.4f}, {row['seconds']:.2f} s")
        else:
            print(f"{row['input']}: failed: {row['error']}")
EOF
exit "$status"
