#!/usr/bin/python3
"""Table and plot of a scaling series written by benchmark/scaling.sh.

Reads the JSON lines of `compare --json` (one object per mesh level and method), prints a
Markdown table  faces | method | seconds | stages | peak MB | Newton its | status  (stages:
the seconds of each stage the method reports; a mesh column first when the series has
several meshes) and, with --plot, draws time and peak memory against the number of faces on
log-log axes (matplotlib; the format follows the file extension: .svg, .png, .pdf).

With BFF's rows (method bff, and icm_param_whole, from benchmark/whole_process.py: whole
processes, reading and writing included) the table is followed by ICM against BFF per size:
ICM's parameterize seconds (icm_param's own), compare's in-process icm_free_boundary, both
whole processes, and the ratios ICM / BFF, with their medians when there are several sizes.

usage: plot_scaling.py SERIES.jsonl [--table OUT.md] [--plot OUT.svg] [--title TEXT]
"""

import argparse
import json
import math
import sys


def load(path):
    rows = []
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line:
                continue
            try:
                rows.append(json.loads(line))
            except json.JSONDecodeError as e:
                print(f"plot_scaling: {path}:{n}: not JSON ({e}), line skipped", file=sys.stderr)
    return rows


def fmt(x, spec):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return ""
    return format(x, spec)


def fmt_seconds(x):
    if x is None:
        return ""
    return f"{x:.3g}" if x < 10 else f"{x:.1f}"


STAGES = ["index", "metric", "cones", "optimum", "cut", "layout"]
# icm_param's own times (the whole process's rows, icm_param_whole).
WHOLE_STAGES = ["read", "parameterize", "write"]


def stages(r):
    """The stages' seconds the method reports, in pipeline order ("index 2.9, optimum 4.6")."""
    names = WHOLE_STAGES if r.get("method") == WHOLE else STAGES
    return ", ".join("{} {}".format(name, fmt_seconds(r["seconds_" + name]))
                     for name in names if r.get("seconds_" + name) is not None)


def meshes_of(rows):
    """The meshes of the series, in the order they come."""
    out = []
    for r in rows:
        if r.get("mesh") not in out:
            out.append(r.get("mesh"))
    return out


def table(rows):
    several = len(meshes_of(rows)) > 1
    out = [("| mesh " if several else "") + "| faces | method | seconds | stages (s) | peak MB | Newton its | status |",
           ("|---" if several else "") + "|---:|---|---:|---|---:|---:|---|"]
    order = meshes_of(rows)
    for r in sorted(rows, key=lambda r: (order.index(r.get("mesh")) if several else 0,
                                         r.get("faces") or 0, r.get("method") or "")):
        out.append(("| {} ".format(r.get("mesh", "")) if several else "") + "| {} | {} | {} | {} | {} | {} | {} |".format(
            r.get("faces", ""), r.get("method", ""), fmt_seconds(r.get("seconds")), stages(r),
            fmt(r.get("peak_rss_mb"), ".1f"),
            "" if r.get("newton_iterations") is None else r["newton_iterations"],
            str(r.get("status", "")).replace("|", "\\|")))
    md = "\n".join(out) + "\n"
    ratios = ratio_table(rows)
    return md + ("\n" + ratios if ratios else "")


# The rows of the side-by-side with BFF (benchmark/scaling.sh with BFF=...).
BFF, WHOLE, IN_PROCESS = "bff", "icm_param_whole", "icm_free_boundary"


def ratio(a, b):
    return a / b if a is not None and b and math.isfinite(a) and math.isfinite(b) else None


def median(xs):
    xs = sorted(x for x in xs if x is not None)
    if not xs:
        return None
    n = len(xs)
    return xs[n // 2] if n % 2 else 0.5 * (xs[n // 2 - 1] + xs[n // 2])


def ratio_table(rows):
    """ICM against BFF per (mesh, faces): the seconds of each side, the ratios ICM / BFF of
    the whole processes (time and peak memory) and of icm_param's parameterize against BFF's
    whole process; a median line when there are several sizes. "" without BFF rows."""
    ok = {(r.get("mesh"), r.get("faces"), r.get("method")): r for r in rows if r.get("status") == "ok"}
    sizes = []
    for r in rows:
        if r.get("method") == BFF and (r.get("mesh"), r.get("faces")) not in sizes:
            sizes.append((r.get("mesh"), r.get("faces")))
    if not sizes:
        return ""
    several = len({m for m, _ in sizes}) > 1
    out = [("| mesh " if several else "") + "| faces | ICM parameterize (s) | ICM in-process (s) | "
           "ICM whole (s) | BFF whole (s) | ICM whole / BFF | ICM parameterize / BFF | "
           "ICM / BFF peak MB |",
           ("|---" if several else "") + "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    columns = [[] for _ in range(3)]
    for mesh, faces in sizes:
        bff, whole, inproc = (ok.get((mesh, faces, m), {}) for m in (BFF, WHOLE, IN_PROCESS))
        bff_s = bff.get("seconds")
        values = [ratio(whole.get("seconds"), bff_s), ratio(whole.get("seconds_parameterize"), bff_s),
                  ratio(whole.get("peak_rss_mb"), bff.get("peak_rss_mb"))]
        for column, v in zip(columns, values):
            column.append(v)
        status = "" if bff else next((" (" + str(r.get("status")) + ")" for r in rows
                                      if (r.get("mesh"), r.get("faces"), r.get("method")) == (mesh, faces, BFF)), "")
        out.append(("| {} ".format(mesh) if several else "") + "| {} | {} | {} | {} | {} | {} | {} | {} |".format(
            faces, fmt_seconds(whole.get("seconds_parameterize")), fmt_seconds(inproc.get("seconds")),
            fmt_seconds(whole.get("seconds")), fmt_seconds(bff_s) + status.replace("|", "\\|"),
            *(fmt(v, ".2f") for v in values)))
    if len(sizes) > 1:
        out.append(("| " if several else "") + "| median of {} | | | | | {} |".format(
            sum(v is not None for v in columns[0]), " | ".join(fmt(median(c), ".2f") for c in columns)))
    return "\n".join(out) + "\n"


def plot(rows, path, title):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    except ImportError:
        print("plot_scaling: matplotlib is missing (apt-get install python3-matplotlib); "
              "no plot written", file=sys.stderr)
        return False

    methods = []
    for r in rows:
        if r.get("method") not in methods:
            methods.append(r.get("method"))

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.5))
    whole = any(r.get("method") in (BFF, WHOLE) for r in rows)
    panels = [("seconds", f"wall time (s); {BFF}, {WHOLE}:\nwhole process, others: parameterize()"
               if whole else "wall time of parameterize() (s)"),
              ("peak_rss_mb", "peak resident memory (MB)")]
    style = {"marker": "o"} if len(meshes_of(rows)) == 1 else {"marker": "o", "ls": "none"}
    for ax, (key, label) in zip(axes, panels):
        all_x = []
        for m in methods:
            pts = sorted((r["faces"], r[key]) for r in rows
                         if r.get("method") == m and r.get("status") == "ok"
                         and r.get(key) is not None and r.get("faces"))
            if not pts:  # still listed, so that a method that never finished is not hidden
                ax.plot([], [], marker="x", ls="none", label=f"{m}: no level finished")
                continue
            xs, ys = zip(*pts)
            all_x.extend(xs)
            # Levels that did not finish (timeout, crash, failure) are named in the legend.
            bad = sorted((r["faces"], str(r.get("status"))) for r in rows
                         if r.get("method") == m and r.get("status") != "ok"
                         and not str(r.get("status", "")).startswith("skipped"))
            name = m + "".join(f"; {st.split(':')[0]} at {f} faces" for f, st in bad)
            ax.loglog(xs, ys, label=name, **style)
        if all_x:
            # Guide: linear growth through the geometric middle of the data.
            x0, x1 = min(all_x), max(all_x)
            ys_all = [r[key] for r in rows if r.get("status") == "ok" and r.get(key)]
            if ys_all and x1 > x0:
                ymid = math.exp(sum(math.log(y) for y in ys_all) / len(ys_all))
                xmid = math.sqrt(x0 * x1)
                ax.loglog([x0, x1], [ymid * x0 / xmid, ymid * x1 / xmid], ls="--",
                          color="lightgray", label="∝ faces")
        for axis in (ax.xaxis, ax.yaxis):  # plain numbers at 1, 2, 5 x 10^k
            axis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
            axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
            axis.set_minor_formatter(NullFormatter())
        ax.set_xlabel("faces")
        ax.set_ylabel(label)
        ax.grid(True, which="both", ls=":", lw=0.5)
        ax.legend(fontsize=8)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("series", help="JSON lines from compare --json")
    ap.add_argument("--table", help="also write the Markdown table to this file")
    ap.add_argument("--plot", help="write the log-log plot to this file (.svg, .png, .pdf)")
    ap.add_argument("--title", default="", help="title of the plot")
    a = ap.parse_args()

    rows = load(a.series)
    if not rows:
        print(f"plot_scaling: {a.series}: no results", file=sys.stderr)
        return 1
    md = table(rows)
    sys.stdout.write(md)
    if a.table:
        with open(a.table, "w", encoding="utf-8") as f:
            f.write(md)
    if a.plot and plot(rows, a.plot, a.title):
        print(f"plot_scaling: wrote {a.plot}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
