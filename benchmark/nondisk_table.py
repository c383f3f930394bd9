#!/usr/bin/env python3
"""Short Markdown table of `compare --json` lines for surfaces that are not disks.

    benchmark/nondisk_table.py RESULTS.jsonl...

One row per (mesh, method): faces, genus / boundary loops, time, the log area distortion
(paper eq. 8 divided by the face count: the unweighted mean over faces of log^2(s_f / A_f)),
QC mean, flipped faces, and a note (ICM's cones, seams and charts and its metric, the cut
CGAL's methods ran on, or why a run failed). Rows of disk meshes (no "genus" key) are left out.
benchmark/tables.py uses table() for a generated section of doc/benchmarks.md.
"""

import json
import sys


def fmt(x, digits=3):
    if x is None:
        return ""
    if x != 0 and (abs(x) < 10 ** -digits or abs(x) >= 1e5):
        return f"{x:.2e}"
    return f"{x:.{digits}f}"


def seconds(x):
    if x is None:
        return ""
    return f"{x:.3g}" if x < 10 else f"{x:.1f}"


def note(r):
    """The cut CGAL's methods ran on, ICM's cones / seams / charts, or why a run failed."""
    status = r["status"]
    if status != "ok":
        if r["method"] == "arap" and "convex border" in status:
            # CGAL's ARAP returns ERROR_NON_CONVEX_BORDER from its MVC post-processor, which it
            # calls when its map is not one-to-one and which gives up when the map's border is
            # not a simple polygon (MVC_post_processor_3.h).
            return "failed: not one-to-one, border self-intersects (CGAL: requires a convex border)"
        return status
    metric = r.get("metric") or ""
    if r.get("fallback_reason") or metric.endswith(", fallback"):
        metric = metric.replace(", fallback", "") + " (fallback)"
    if r["method"] in ("icm", "icm_keep_overlaps"):
        text = f'{r["cones"]} cones, {r["seam_edges"]} seam edges, {r["charts"]} chart' + \
            ("s" if r["charts"] != 1 else "")
        if r.get("border_crossings"):
            text += f'; {r["border_crossings"]} border crossings'
        return text + f"; {metric}"
    if "cut" in r:
        return f'cut: {r["cut"]}'
    if "opened_faces" in r:
        return f'opened: {r["opened_faces"]} faces; {metric}'
    return ""


def table(rows):
    """The Markdown table of the rows of surfaces that are not disks, one line a row."""
    out = ["| mesh | faces | genus / loops | method | time (s) | log area distortion | QC mean "
           "| flips | note |",
           "|---|---:|---|---|---:|---:|---:|---:|---|"]
    last = None
    for r in rows:
        if "genus" not in r:
            continue
        first = r["mesh"] != last
        last = r["mesh"]
        topo = f'{r["genus"]} / {r["loops"]}'
        out.append("| {} | {} | {} | {} | {} | {} | {} | {} | {} |".format(
            r["mesh"] if first else "", r["faces"] if first else "", topo if first else "",
            r["method"], seconds(r["seconds"]), fmt(r["log_area_distortion"]),
            fmt(r["qc_mean"]), "" if r["flipped"] is None else r["flipped"],
            note(r).replace("|", "\\|")))
    return "\n".join(out) + "\n"


def main(paths):
    rows = []
    for path in paths:
        with open(path) as f:
            rows += [json.loads(line) for line in f if line.strip()]
    sys.stdout.write(table(rows))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
