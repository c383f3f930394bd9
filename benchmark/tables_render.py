"""The sections of benchmark/tables.py: each a Markdown table of the rows of the runs it
reads (tables_plan.SECTIONS), and the line above it that says how they were measured.
The section cones, which also draws a figure, is in tables_cones.py.
"""

import json
import math

import nondisk_table  # the table of surfaces that are not disks
import plot_scaling  # the table of a scaling series
from tables_plan import (CGAL, ENERGIES, LEFT_OUT, OPENED_METHODS, REGISTRY_METRICS, SUMMARY_METHODS,
                         SURFACE_ENERGY_METHODS)

# ---------------------------------------------------------------- formatting

def num(x, digits):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return ""
    if x != 0 and (abs(x) < 10 ** -digits or abs(x) >= 1e5):
        return f"{x:.2e}"
    return f"{x:.{digits}f}"


def sec(x):
    return plot_scaling.fmt_seconds(x)


def integer(x):
    return "" if x is None else str(x)


def cell(text):
    return str(text).replace("|", "\\|")


def label(r):
    m = r["method"]
    if r.get("metric") and (m.startswith("icm_") or m == "icm"):
        return f"{m} ({r['metric']})"
    return m


TABLE_I = ("| mesh | method | conformality | angle distortion | L2 shear | L2 stretch "
           "| log area distortion | time (s) | flipped | QC mean | QC max | peak MB "
           "| Newton its | status |\n"
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")


def table_i_row(r, first, status):
    name = f'{r["mesh"]} ({r["faces"]} faces)' if first else ""
    return "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |".format(
        name, label(r), num(r.get("conformality"), 5), num(r.get("angle_distortion"), 5),
        num(r.get("l2_shear"), 4), num(r.get("l2_stretch"), 4),
        num(r.get("log_area_distortion"), 5), sec(r.get("seconds")), integer(r.get("flipped")),
        num(r.get("qc_mean"), 4), num(r.get("qc_max"), 3), num(r.get("peak_rss_mb"), 1),
        integer(r.get("newton_iterations")), cell(status))


def crossings(r):
    n = r.get("border_crossings")
    return f"; {n} border crossings" if n else ""


def by_mesh(rows, methods):
    """Rows of the methods, grouped by mesh in the order the meshes came, methods in order."""
    meshes = []
    for r in rows:
        if r["method"] in methods and r["mesh"] not in meshes:
            meshes.append(r["mesh"])
    for mesh in meshes:
        group = [r for r in rows if r["mesh"] == mesh and r["method"] in methods]
        group.sort(key=lambda r: methods.index(r["method"]))
        yield mesh, group


def disk_rows(rows):
    return [r for r in rows if "genus" not in r]


def section_disks(data):
    _, rows = data["all"]
    out = [TABLE_I]
    for _, group in by_mesh(disk_rows(rows), REGISTRY_METRICS + CGAL):
        for i, r in enumerate(group):
            out.append(table_i_row(r, i == 0, r["status"] + crossings(r)))
    return "\n".join(out)


def section_energies(data):
    _, rows = data["all"]
    methods = ["icm_free_boundary"] + ENERGIES + ["lscm", "arap"]
    head = TABLE_I.split("\n")
    out = [head[0] + " time / entropy's |", head[1] + "---:|"]
    for _, group in by_mesh(disk_rows(rows), methods):
        entropy = next((r for r in group if r["method"] == "icm_free_boundary"), None)
        for i, r in enumerate(group):
            status = r["status"]
            if r.get("seconds_optimum") is not None:
                status += f'; optimum {sec(r["seconds_optimum"])} s'
            status += crossings(r)
            if r.get("energy_iterations") is not None:
                status += "; {} energy steps, E {:.4g} -> {:.4g}".format(
                    r["energy_iterations"], r["initial_energy"], r["final_energy"])
            ratio = ""
            if entropy and entropy.get("seconds") and r.get("seconds") and \
                    r["method"] in ENERGIES:
                ratio = f'{r["seconds"] / entropy["seconds"]:.1f}'
            out.append(table_i_row(r, i == 0, status) + f" {ratio} |")
    return "\n".join(out)


def section_nondisk(data):
    _, rows = data["all"]
    return nondisk_table.table(rows).rstrip("\n")


def cones_and_given_up(row):
    given_up = row.get("cones_given_up") or 0
    return integer(row.get("cones")) + (f" ({integer(given_up)})" if given_up else "")


def section_surfaces(data):
    both = data["all"][1] + data["icm"][1]
    icm = {r["mesh"]: r for r in both if r["method"] == "icm"}  # run icm's row if in both
    opened = {r["mesh"]: r for r in both if r["method"] == "icm_free_boundary_opened"}
    rows = [icm[m] for m in sorted(icm)]
    out = ["| mesh | faces | genus / loops | cones (given up) | seam edges | charts | metric | QC mean "
           "| log area distortion | flipped | border crossings | time (s) | cones (s) "
           "| optimum (s) | cut (s) | layout (s) | peak MB | opened, free boundary (s) | status |",
           "|---|---:|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in rows:
        topo = f'{r["genus"]} / {r["loops"]}' if "genus" in r else "disk"
        out.append("| " + " | ".join([
            r["mesh"], str(r["faces"]), topo, cones_and_given_up(r),
            integer(r.get("seam_edges")), integer(r.get("charts")), r.get("metric") or "",
            num(r.get("qc_mean"), 3), num(r.get("log_area_distortion"), 3),
            integer(r.get("flipped")), integer(r.get("border_crossings")),
            sec(r.get("seconds")), sec(r.get("seconds_cones")), sec(r.get("seconds_optimum")),
            sec(r.get("seconds_cut")), sec(r.get("seconds_layout")),
            num(r.get("peak_rss_mb"), 1), sec(opened.get(r["mesh"], {}).get("seconds")),
            cell(r["status"])]) + " |")
    return "\n".join(out)


def section_surface_energies(data):
    _, rows = data["senergies"]
    methods = SURFACE_ENERGY_METHODS.split(",")
    out = ["| mesh | faces | genus / loops | method | cones | charts | log area distortion "
           "| QC mean | flipped | border crossings | energy steps | time (s) | time / entropy's "
           "| status |",
           "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for _, group in by_mesh([r for r in rows if "genus" in r], methods):
        entropy = next((r for r in group if r["method"] == "icm"), None)
        for i, r in enumerate(group):
            ratio = ""
            if entropy and entropy.get("seconds") and r.get("seconds") and r is not entropy:
                ratio = f'{r["seconds"] / entropy["seconds"]:.1f}'
            out.append("| " + " | ".join([
                r["mesh"] if i == 0 else "", str(r["faces"]) if i == 0 else "",
                f'{r["genus"]} / {r["loops"]}' if i == 0 else "", label(r),
                integer(r.get("cones")), integer(r.get("charts")),
                num(r.get("log_area_distortion"), 3), num(r.get("qc_mean"), 3),
                integer(r.get("flipped")), integer(r.get("border_crossings")),
                integer(r.get("energy_iterations")), sec(r.get("seconds")), ratio,
                cell(r["status"])]) + " |")
    return "\n".join(out)


def section_opened(data):
    _, rows = data["opened"]
    methods = OPENED_METHODS.split(",")
    head = TABLE_I.split("\n")
    out = [head[0] + " UV/3D area ratio min | max |", head[1] + "---:|---:|"]
    for _, group in by_mesh(rows, methods):
        for i, r in enumerate(group):
            out.append(table_i_row(r, i == 0, r["status"]) + " {} | {} |".format(
                num(r.get("area_ratio_min"), 3), num(r.get("area_ratio_max"), 3)))
    return "\n".join(out)


def section_border(data):
    out = ["| mesh | loops | boundary | outer iterations | circle deviation | flipped "
           "| degenerate | border crossings | QC mean | log area distortion | time (s) | made by |",
           "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"]
    for r in data["all"][1]:
        if r["method"] == "icm_circle_domain":
            out.append("| " + " | ".join([
                r["mesh"], str(r.get("loops", 1)), "circle-domain", integer(r.get("border_iterations")),
                num(r.get("circle_deviation"), 3), integer(r.get("flipped")),
                integer(r.get("degenerate")), integer(r.get("border_crossings")),
                num(r.get("qc_mean"), 3), num(r.get("log_area_distortion"), 3),
                sec(r.get("seconds")),
                "compare" + ("" if r["status"] == "ok" else ": " + cell(r["status"]))]) + " |")
    for r in data["border"][1]:
        circle = r.get("boundary") == "circle"
        out.append("| " + " | ".join([
            r["mesh"], str(r.get("boundary_loops")), r.get("boundary", ""),
            integer(r.get("border_iterations")) if circle else "",
            num(r.get("circle_deviation"), 3) if circle else "", integer(r.get("flipped_faces")),
            integer(r.get("degenerate_faces")), integer(r.get("overlapping_border_edges")),
            num(r.get("qc_mean"), 3), num(r.get("log_area_distortion"), 3),
            sec(r.get("seconds_parameterize")), "icm_param"]) + " |")
    return "\n".join(out)


def section_scaling_short(data):
    return plot_scaling.table(data["scaling"][1]).rstrip("\n")


def section_scaling(series):
    rows = plot_scaling.load(series)
    return plot_scaling.table(rows).rstrip("\n")


def section_reading(figures):
    """The reader's figures (BM_read_triangle_mesh of benchmark/kernels.cpp, Google
    Benchmark's JSON): per file, its faces, the triangles read and the median wall and CPU
    times of the repetitions, against the first file's."""
    with open(figures, encoding="utf-8") as f:
        report = json.load(f)
    medians = [b for b in report["benchmarks"] if b.get("aggregate_name") == "median"]
    context = report["context"]
    out = [f'{context["num_cpus"]} CPUs at {context["mhz_per_cpu"]} MHz, {context["date"][:10]}, '
           f'median of {medians[0]["repetitions"] if medians else 0} reads each.', "",
           "| file | faces in the file | triangles | wall s | CPU s | wall ÷ the first |",
           "|---|---|---|---|---|---|"]
    first = medians[0]["real_time"] if medians else None
    for b in medians:
        scale = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b["time_unit"]]
        out.append("| " + " | ".join([
            b.get("label", b["name"]), integer(round(b["file_faces"])), integer(round(b["faces"])),
            sec(b["real_time"] * scale), sec(b["cpu_time"] * scale),
            num(b["real_time"] / first, 2)]) + " |")
    return "\n".join(out)


def section_summary(data):
    """A few rows for the README: log area distortion (eq. 8), flipped faces and border
    crossings, seconds, for ICM and CGAL's LSCM and ARAP."""
    _, rows = data["summary"]
    out = ["| mesh | ICM | CGAL LSCM | CGAL ARAP |", "|---|---|---|---|"]

    def figures(r):
        if r is None:
            return ""
        if not r["status"].startswith("ok"):
            return cell(r["status"])
        folds = integer(r.get("flipped")) + (f' + {r["border_crossings"]} crossings'
                                             if r.get("border_crossings") else "")
        return f'{num(r.get("log_area_distortion"), 3)}, {folds} flipped, {sec(r.get("seconds"))} s'

    for mesh, group in by_mesh(rows, SUMMARY_METHODS):
        by_method = {r["method"]: r for r in group}
        icm = by_method.get("icm", {})
        kind = "closed" if icm.get("loops") == 0 else "disk"
        out.append(f'| {mesh} ({group[0]["faces"]} faces, {kind}, {integer(icm.get("cones"))} cones) | '
                   f'{figures(by_method.get("icm"))} | {figures(by_method.get("lscm"))} | '
                   f'{figures(by_method.get("arap"))} |')
    return "\n".join(out)


def header(section, metas, hint, rendered_from):
    """One line: machine, date, commit, the command that regenerates the section, and the
    commands that ran."""
    machines = []
    for m in metas:
        if m["machine"] not in machines:
            machines.append(m["machine"])
    runs = []
    for m in metas:
        load = f' (load average {m["load"]:.1f})' if m.get("load") is not None else ""
        runs.append(f'{m["date"]}{load}, commit {m["commit"]}')
    text = f"Measured on {' / '.join(machines)}: " + "; ".join(runs)
    text += f"; regenerate with `{hint}`"
    run_name, left_out = LEFT_OUT.get(section, (None, ""))
    if any(m["run"] == run_name and m.get("default_meshes") for m in metas):
        text += f"; {left_out}"
    commands = [c for m in metas for c in m.get("commands", [])]
    if commands:
        text += "; ran " + "; ".join(f"`{c}`" for c in commands)
    if rendered_from:
        text += "; rendered from " + ", ".join(f"`{f}`" for f in rendered_from)
    return "_" + text + "._"


def replace_section(doc, name, body):
    begin = f"<!-- BEGIN GENERATED: {name} -->"
    end = f"<!-- END GENERATED: {name} -->"
    i = doc.find(begin)
    j = doc.find(end)
    if i < 0 or j < i:
        raise SystemExit(f"tables: no markers {begin} ... {end} in the document")
    return doc[:i + len(begin)] + "\n" + body.rstrip("\n") + "\n" + doc[j:]
