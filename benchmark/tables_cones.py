"""The section cones of benchmark/tables.py: per mesh, energy and cone count, the figures a
choice of cones trades, against BFF's at 8 cones, and their plot (doc/figures/cones.svg).
"""

import os
import sys

from tables_plan import CONE_COUNTS, CONE_ENERGIES, CONE_METHODS, ROOT, relative
from tables_render import by_mesh, cell, integer, num, sec

# BFF 1.6 with --nCones=8 on the same meshes, area-weighted mean log² area by the same
# independent evaluator (../shared/tools/uv_metrics.py): the figures of issue 29, which
# measured them. BFF is not built by this repository, so they are quoted, not rerun.
BFF_8_CONES = {"sphere966.off": 0.065, "cow.off": 15.6, "bull.off": 20.2, "camel.off": 13.9,
               "bear.off": 1.24, "armadillo.off": 6.95, "bunny00.off": 2.40}
CONES_PLOT = os.path.join(ROOT, "doc", "figures", "cones.svg")


def plot_cones(rows, path):
    """The area-weighted log² area and the charts against the cone count, one colour per
    mesh, solid for the entropy's cone angles and dashed for u-square's (matplotlib; skipped
    with a note when it is missing). Returns the Markdown that shows it, or ''."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("tables: matplotlib is missing (apt-get install python3-matplotlib); "
              f"{relative(path)} not redrawn", file=sys.stderr)
        return ""
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    colours = {}
    for energy, prefix, _ in CONE_ENERGIES:
        methods = [f"{prefix}{n}" for n in CONE_COUNTS]
        style = "-" if energy == "entropy" else "--"
        for mesh, group in by_mesh(rows, methods):
            ok = [r for r in group if r["status"].startswith("ok")]
            counts = [CONE_COUNTS[methods.index(r["method"])] for r in ok]
            name = os.path.splitext(mesh)[0]
            colour = colours.setdefault(name, f"C{len(colours) % 10}")
            shown = name if energy == "entropy" else None
            left.plot(counts, [r["log_area_distortion_area_weighted"] for r in ok], style, marker="o",
                      color=colour, label=shown)
            right.plot(counts, [r["charts"] for r in ok], style, marker="o", color=colour, label=shown)
    for axes, text in ((left, "log² area, area-weighted mean"), (right, "charts")):
        axes.set_xscale("log", base=2)
        axes.set_xticks(CONE_COUNTS)
        axes.set_xticklabels([str(n) for n in CONE_COUNTS])
        axes.set_xlabel("cones (solid: entropy's angles, dashed: u-square's)")
        axes.set_ylabel(text)
        axes.grid(True, which="both", alpha=0.3)
    left.set_yscale("log")
    right.legend(fontsize="small", loc="upper left")
    fig.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fig.savefig(path, metadata={"Date": None})  # no date: the file changes only with the data
    plt.close(fig)
    return f"![area distortion and charts against the cone count]({os.path.relpath(path, os.path.join(ROOT, 'doc'))})"


def section_cones(data):
    """The Pareto table: per mesh, energy and cone count, the figures a choice trades."""
    _, rows = data["cones"]
    methods = CONE_METHODS.split(",")
    out = ["| mesh | faces | genus / loops | cone angles | cones | log² area (area-weighted) "
           "| eq. 8 | QC mean | seam length | charts | flipped | border crossings | time (s) |",
           "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    eight = {}
    for mesh, group in by_mesh(rows, methods):
        by_method = {r["method"]: r for r in group}
        any_row = group[0]
        topo = f'{any_row["genus"]} / {any_row["loops"]}' if "genus" in any_row else "disk"
        first = True
        for energy, prefix, default in CONE_ENERGIES:
            for m in [f"{prefix}{n}" for n in CONE_COUNTS] + [default]:
                r = by_method.get(m)
                if r is None:
                    continue
                head = [mesh, str(any_row["faces"]), topo] if first else ["", "", ""]
                first = False
                cones = integer(r.get("cones")) + (" (default)" if m == default else "")
                if not r["status"].startswith("ok"):
                    out.append("| " + " | ".join(head + [energy, cones] + [""] * 7 + [cell(r["status"])]) + " |")
                    continue
                out.append("| " + " | ".join(head + [
                    energy, cones, num(r.get("log_area_distortion_area_weighted"), 4),
                    num(r.get("log_area_distortion"), 4), num(r.get("qc_mean"), 3),
                    num(r.get("seam_length"), 3), integer(r.get("charts")), integer(r.get("flipped")),
                    integer(r.get("border_crossings")), sec(r.get("seconds"))]) + " |")
                if m == f"{prefix}8":
                    eight.setdefault(mesh, {})[energy] = r
    out += ["", "At exactly 8 cones against BFF 1.6 (`--nCones=8`; its figures quoted from issue 29, "
            "same evaluator), area-weighted mean log² area, charts in brackets:", "",
            "| mesh | BFF, 8 cones | ICM, entropy's angles | ICM, u-square's angles |", "|---|---:|---:|---:|"]
    for mesh, bff in BFF_8_CONES.items():
        cells = []
        for energy, _, _ in CONE_ENERGIES:
            r = eight.get(os.path.splitext(mesh)[0], {}).get(energy)
            cells.append(f'{num(r.get("log_area_distortion_area_weighted"), 4)} ({integer(r.get("charts"))})'
                         if r else "")
        out.append("| " + " | ".join([os.path.splitext(mesh)[0], num(bff, 3)] + cells) + " |")
    figure = plot_cones(rows, CONES_PLOT)
    return "\n".join(out) + ("\n\n" + figure if figure else "")
