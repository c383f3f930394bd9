#!/usr/bin/python3
"""Regenerate the measured tables of doc/benchmarks.md.

    /usr/bin/python3 benchmark/tables.py [--sections a,b] [--meshes MESH...] [--from FILE...]

Runs the already built `compare` (and `icm_param` for the border shapes compare does not
have, and `scaling.sh` for a short scaling series), one process at a time, keeps the JSON
lines of every run in the cache directory, and rewrites each generated section of the
document: the text between

    <!-- BEGIN GENERATED: name -->
    <!-- END GENERATED: name -->

Each section starts with one line naming the machine, the date, the commit of the measured
code and the command that regenerates it. Nothing outside the markers is touched.

Runs (each one cache file, RUN.jsonl, whose first line records how it was made):
  all      compare, default methods, on the disks and on the surfaces that are not disks
           (meshes above --big-faces faces with --runs 1): sections disks, energies,
           nondisk and the circle domains of border
  icm      compare --methods icm,icm_free_boundary_opened on the disks and the largest
           surfaces: with the icm rows of `all`, section surfaces
  senergies  compare --methods icm,icm_u_square,... on small surfaces that are not disks:
           section surface-energies
  opened   compare --open on the closed genus-0 meshes: section opened
  border   icm_param --boundary circle|square --json on some disks: section border
  scaling  scaling.sh with KMAX=--scaling-kmax into the cache: section scaling-short
  summary  compare --methods icm,lscm,arap on a few disks and closed meshes:
           section summary, which goes into README.md (--readme), not doc/benchmarks.md
Section scaling renders a series written earlier by scaling.sh (--scaling-series), which
is too slow to rerun here.

--from FILE... reads cache files instead of running (a file without the first line is
taken to be the run its name says: all.jsonl, icm.jsonl, ...); runs it lacks are made. --meshes replaces the mesh
list of every compare run; each section shows the rows that apply to it.
"""

import argparse
import datetime
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import nondisk_table  # noqa: E402  (the table of surfaces that are not disks)
import plot_scaling  # noqa: E402  (the table of a scaling series)

# The meshes of the tables (file names in the mesh directories).
DISKS = ["nefertiti.off", "three_peaks.off", "mushroom.off", "lion-head.off", "camelhead.off",
         "mannequin-devil.off", "horse.obj"]
OTHER_DISKS = ["mesh_with_border.off", "cylinder_locally_refined.off"]
NOT_DISKS = ["sphere966.off", "cow.off", "bull.off", "rotor.off", "elk.off", "knot1.off",
             "eight.off", "femur.off", "elephant.off", "pig.off", "head.off",
             "mech-holes-shark.off", "camel.off", "bear.off"]
# The largest surfaces get only ICM's rows (run icm): CGAL's methods on their cuts, ARAP above
# all, would take most of the time of the whole run.
BIG_SURFACES = ["armadillo.off", "bunny00.off", "refined_elephant.off"]
CLOSED_GENUS_0 = ["sphere966.off", "cow.off", "bull.off", "camel.off", "bear.off"]
# What the default mesh lists leave out, for the header of a section: (run, text).
LEFT_OUT = {
    "nondisk": ("all", "armadillo, bunny00 and refined_elephant left out to keep the whole "
                "run within 15 minutes (their ICM rows are in Every surface)"),
    "opened": ("opened", "armadillo and bunny00 left out to keep the whole run within 15 "
               "minutes (ARAP runs into the time limit on them)"),
}
# icm_param --boundary square; the circles are compare's icm_circle_domain rows (on a disk
# the circle domain is the circle border).
BORDER_SHAPES = [("three_peaks.off", "square"), ("lion-head.off", "square"),
                 ("horse.obj", "square")]
OPENED_METHODS = "icm_free_boundary,lscm,arap,dcm,mvc"
# Every energy through ICM::parameterize on surfaces that are not disks.
SURFACE_ENERGY_MESHES = ["sphere966.off", "pig.off", "cow.off", "eight.off", "elk.off",
                         "rotor.off", "femur.off", "elephant.off", "head.off",
                         "mech-holes-shark.off", "knot1.off"]
SURFACE_ENERGY_METHODS = "icm,icm_u_square,icm_area,icm_angle,icm_log_area"

# Area distortion against the cone count, with the entropy's cone angles (icm_cones_N, and
# icm for the default) and with u-square's (icm_u_square_cones_N, icm_u_square).
CONE_MESHES = CLOSED_GENUS_0 + ["armadillo.off", "bunny00.off", "eight.off", "femur.off"]
CONE_COUNTS = [4, 8, 16, 32]
CONE_ENERGIES = [("entropy", "icm_cones_", "icm"), ("u-square", "icm_u_square_cones_", "icm_u_square")]
CONE_METHODS = ",".join([f"{prefix}{n}" for _, prefix, _ in CONE_ENERGIES for n in CONE_COUNTS] +
                        [default for _, _, default in CONE_ENERGIES])
# BFF 1.6 with --nCones=8 on the same meshes, area-weighted mean log² area by the same
# independent evaluator (../shared/tools/uv_metrics.py): the figures of issue 29, which
# measured them. BFF is not built by this repository, so they are quoted, not rerun.
BFF_8_CONES = {"sphere966.off": 0.065, "cow.off": 15.6, "bull.off": 20.2, "camel.off": 13.9,
               "bear.off": 1.24, "armadillo.off": 6.95, "bunny00.off": 2.40}

# The README's few rows: ICM's default call against CGAL's LSCM and ARAP (on ICM's cut where
# ICM cuts), on disks and closed meshes.
SUMMARY_MESHES = ["nefertiti.off", "three_peaks.off", "camelhead.off", "sphere966.off", "cow.off",
                  "bunny00.off"]
SUMMARY_METHODS = ["icm", "lscm", "arap"]
# Sections that go into the README rather than the document of --doc.
README_SECTIONS = ["summary"]

SECTIONS = {  # section: the runs it reads
    "disks": ["all"], "energies": ["all"], "nondisk": ["all"], "surfaces": ["all", "icm"],
    "surface-energies": ["senergies"], "opened": ["opened"], "border": ["all", "border"],
    "scaling": [], "scaling-short": ["scaling"], "cones": ["cones"], "summary": ["summary"],
}
REGISTRY_METRICS = ["icm_free_boundary", "icm_vertex_scaling", "icm_inversive_distance",
                    "icm_circle_packing"]
CGAL = ["lscm", "arap", "dcm", "dac", "mvc"]
ENERGIES = ["icm_u_square", "icm_area", "icm_angle", "icm_log_area"]


# ---------------------------------------------------------------- where and what

def mesh_dirs(extra):
    dirs = list(extra)
    if os.environ.get("ICM_MESH_DIR"):
        dirs.append(os.environ["ICM_MESH_DIR"])
    dirs += [os.path.join(ROOT, "..", "shared", "data", "meshes"), "/work/shared/data/meshes",
             os.path.join(ROOT, "examples", "data")]
    return dirs


def find_mesh(name, dirs):
    if os.sep in name or os.path.isfile(name):
        return name
    for d in dirs:
        path = os.path.join(d, name)
        if os.path.isfile(path):
            return os.path.normpath(path)
    return None


def face_count(path):
    """Faces of an OFF (its header) or OBJ (its f lines) file; 0 when unknown."""
    try:
        with open(path, errors="replace") as f:
            if path.endswith(".obj"):
                return sum(1 for line in f if line.startswith("f "))
            words = []
            for line in f:
                line = line.split("#")[0].strip()
                if line:
                    words += line.split()
                if len(words) >= 3 and not words[0].isalpha():
                    return int(words[1])
                if len(words) >= 4:
                    return int(words[2])
    except (OSError, ValueError):
        pass
    return 0


def machine():
    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} logical cores"


def git(args, cwd):
    try:
        return subprocess.run(["git"] + args, cwd=cwd, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def commit_of(binary):
    """HEAD of the git tree the binary was built in; marked when files of include/ or
    benchmark/ changed there without a commit before the binary was built (they may be in
    it), or when HEAD is newer than the binary."""
    top = git(["rev-parse", "--show-toplevel"], os.path.dirname(os.path.abspath(binary))) or ROOT
    head = git(["rev-parse", "--short", "HEAD"], top) or "unknown"
    built = os.path.getmtime(binary)
    changed = [line[3:].strip() for line in
               git(["status", "--porcelain", "--", "include", "benchmark"], top).splitlines()]
    paths = [os.path.join(top, p) for p in changed]
    if any(os.path.exists(p) and os.path.getmtime(p) < built for p in paths):
        head += " with uncommitted changes"
    commit_time = git(["log", "-1", "--format=%ct"], top)
    if commit_time and int(commit_time) > built:
        head += " (the binary is older than this commit)"
    return head


def now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")


# ---------------------------------------------------------------- running

def run_command(cmd, log):
    print("tables: " + " ".join(shlex.quote(c) for c in cmd), file=sys.stderr)
    out = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=log, text=True)
    return out.returncode, out.stdout


def compare_rows(a, meshes, extra, big=True):
    """compare --json on the meshes; those above --big-faces faces in a second call with
    --runs 1. Returns rows and the commands."""
    nice = ["nice", "-n", str(a.nice)] if a.nice else []
    base = nice + [a.compare, "--json", "--quiet", "--time-limit", str(a.time_limit)] + extra
    small = [m for m in meshes if not big or face_count(m) <= a.big_faces]
    large = [m for m in meshes if m not in small]
    rows, cmds = [], []
    for group, opts in ((small, []), (large, ["--runs", "1"])):
        if not group:
            continue
        cmd = base + opts + group
        cmds.append(cmd)
        _, out = run_command(cmd, sys.stderr)
        rows += [json.loads(line) for line in out.splitlines() if line.strip().startswith("{")]
    return rows, cmds


def run(name, a, dirs):
    start_load, started = os.getloadavg()[0], now()
    def meshes(default):
        names = a.meshes or default
        found = [find_mesh(n, dirs) for n in names]
        missing = [n for n, p in zip(names, found) if p is None]
        if missing:
            print(f"tables: not found, skipped: {' '.join(missing)}", file=sys.stderr)
        return [p for p in found if p]

    if name == "all":
        rows, cmds = compare_rows(a, meshes(DISKS + NOT_DISKS), [])
    elif name == "icm":
        rows, cmds = compare_rows(a, meshes(DISKS + OTHER_DISKS + BIG_SURFACES),
                                  ["--methods", "icm,icm_free_boundary_opened"])
        rows = [r for r in rows if not r["status"].startswith("skipped")]
    elif name == "senergies":
        rows, cmds = compare_rows(a, meshes(SURFACE_ENERGY_MESHES),
                                  ["--methods", SURFACE_ENERGY_METHODS])
    elif name == "cones":
        rows, cmds = compare_rows(a, meshes(CONE_MESHES), ["--methods", CONE_METHODS])
    elif name == "summary":
        rows, cmds = compare_rows(a, meshes(SUMMARY_MESHES), ["--methods", ",".join(SUMMARY_METHODS)])
    elif name == "opened":
        paths = meshes(CLOSED_GENUS_0)
        rows, cmds = compare_rows(a, paths, ["--open", "--methods", OPENED_METHODS])
        faces = {os.path.splitext(os.path.basename(p))[0]: face_count(p) for p in paths}
        rows = [r for r in rows if r.get("faces", 0) < faces.get(r["mesh"], 0)]  # opened ones
    elif name == "border":
        rows, cmds = [], []
        nice = ["nice", "-n", str(a.nice)] if a.nice else []
        with tempfile.TemporaryDirectory() as tmp:
            for mesh, boundary in BORDER_SHAPES:
                path = find_mesh(mesh, dirs)
                if path is None or (a.meshes and mesh not in a.meshes):
                    continue
                cmd = nice + [a.icm_param, path, "-o", os.path.join(tmp, "out.obj"),
                              "--boundary", boundary, "--json", "--quiet"]
                cmds.append(cmd)
                _, out = run_command(cmd, sys.stderr)
                for line in out.splitlines():
                    if line.startswith("{"):
                        r = json.loads(line)
                        r["mesh"] = os.path.splitext(os.path.basename(path))[0]
                        rows.append(r)
    elif name == "scaling":
        outdir = os.path.join(a.cache, "scaling")
        env = dict(os.environ, KMAX=str(a.scaling_kmax), NAME="short")
        cmd = (["nice", "-n", str(a.nice)] if a.nice else []) + \
            ["bash", os.path.join(HERE, "scaling.sh"), a.compare, outdir]
        cmds = [cmd]
        print("tables: KMAX=%d %s" % (a.scaling_kmax, " ".join(cmd)), file=sys.stderr)
        subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, check=False)
        rows = plot_scaling.load(os.path.join(outdir, "short.jsonl"))
        cmds = [[f"KMAX={a.scaling_kmax}"] + cmd]
    else:
        raise SystemExit(f"tables: unknown run {name}")
    binary = a.icm_param if name == "border" else a.compare
    meta = {"run": name, "machine": machine(), "date": started, "load": start_load,
            "commit": a.commit or commit_of(binary),
            "commands": [short(cmd) for cmd in cmds],
            "time_limit": a.time_limit, "big_faces": a.big_faces,
            "default_meshes": not a.meshes}
    os.makedirs(a.cache, exist_ok=True)
    path = os.path.join(a.cache, name + ".jsonl")
    with open(path, "w") as f:
        f.write(json.dumps({"tables_meta": meta}) + "\n")
        for r in rows:
            f.write(json.dumps(r) + "\n")
    print(f"tables: {len(rows)} rows -> {path}", file=sys.stderr)
    return meta, rows


def short(cmd):
    """A command as the header shows it: programs and meshes by their file names."""
    words = []
    for w in cmd:
        if os.path.isfile(w) or os.path.isabs(w):
            w = os.path.basename(w.rstrip("/")) if not w.endswith(".sh") else relative(w)
        words.append(shlex.quote(w))
    return " ".join(words)


def load(path):
    meta, rows = None, []
    with open(path) as f:
        for line in f:
            if line.strip():
                r = json.loads(line)
                if "tables_meta" in r:
                    meta = r["tables_meta"]
                else:
                    rows.append(r)
    if meta is None:
        meta = {"run": os.path.splitext(os.path.basename(path))[0], "machine": "not recorded",
                "date": "not recorded", "commit": "not recorded", "commands": []}
    meta["file"] = path
    return meta, rows


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


RENDER = {"disks": section_disks, "energies": section_energies, "nondisk": section_nondisk,
          "surfaces": section_surfaces, "surface-energies": section_surface_energies,
          "cones": section_cones,
          "opened": section_opened, "border": section_border,
          "scaling-short": section_scaling_short, "summary": section_summary}


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


def relative(path):
    path = os.path.abspath(path)
    return os.path.relpath(path, ROOT) if path.startswith(ROOT + os.sep) else path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0], epilog=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sections", default=",".join(SECTIONS),
                    help="comma-separated sections to regenerate (default: all: %(default)s)")
    ap.add_argument("--meshes", nargs="+", help="mesh files or names in the mesh directories, "
                    "replacing every run's list")
    ap.add_argument("--mesh-dir", action="append", default=[], help="look for meshes here first")
    ap.add_argument("--from", dest="sources", nargs="+", metavar="FILE",
                    help="read these cache files (RUN.jsonl) instead of running; the runs "
                    "they lack are made")
    ap.add_argument("--compare", default=os.path.join(ROOT, "build", "benchmark", "compare"),
                    help="the compare binary (default: build/benchmark/compare)")
    ap.add_argument("--icm-param", default=os.path.join(ROOT, "build", "examples", "icm_param"),
                    help="the icm_param binary (default: build/examples/icm_param)")
    ap.add_argument("--cache", default=os.path.join(ROOT, "build", "tables"),
                    help="where the runs' JSON lines go (default: build/tables)")
    ap.add_argument("--doc", default=os.path.join(ROOT, "doc", "benchmarks.md"),
                    help="the document to rewrite (default: doc/benchmarks.md)")
    ap.add_argument("--readme", default=os.path.join(ROOT, "README.md"),
                    help="the document of the README sections (default: README.md)")
    ap.add_argument("--time-limit", type=float, default=60, help="seconds per run (default 60)")
    ap.add_argument("--big-faces", type=int, default=15000,
                    help="meshes with more faces get --runs 1 (default 15000)")
    ap.add_argument("--nice", type=int, default=10, help="niceness of the runs (0: none)")
    ap.add_argument("--scaling-series", default=os.path.join(ROOT, "doc", "figures",
                                                             "scaling.jsonl"))
    ap.add_argument("--scaling-kmax", type=int, default=1,
                    help="Loop subdivision levels 0..K of the short series (default 1)")
    ap.add_argument("--commit", help="the commit to name in the headers (default: HEAD of the "
                    "binary's git tree, for a binary copied out of its tree)")
    ap.add_argument("--print", action="store_true", help="print the sections, leave the doc")
    a = ap.parse_args()

    sections = [s for s in a.sections.split(",") if s]
    unknown = [s for s in sections if s not in SECTIONS]
    if unknown:
        ap.error(f"unknown sections {unknown}; known: {', '.join(SECTIONS)}")
    needed = []
    for s in sections:
        needed += [r for r in SECTIONS[s] if r not in needed]

    data = {}
    for path in a.sources or []:
        meta, rows = load(path)
        data[meta["run"]] = (meta, rows)
    missing = [r for r in needed if r not in data]
    if missing:
        for tool in [a.compare] + ([a.icm_param] if "border" in missing else []):
            if not os.access(tool, os.X_OK):
                raise SystemExit(f"tables: {tool} is not an executable; build it (doc/benchmarks.md)")
        dirs = mesh_dirs(a.mesh_dir)
        for r in missing:
            data[r] = run(r, a, dirs)

    docs = {}  # path: its text, rewritten section by section
    for s in sections:
        path = a.readme if s in README_SECTIONS else a.doc
        if path not in docs:
            with open(path, encoding="utf-8") as f:
                docs[path] = f.read()
        hint = f"/usr/bin/python3 benchmark/tables.py --sections {s}"
        if a.meshes:
            hint += " --meshes " + " ".join(a.meshes)
        if s == "scaling":
            series = a.scaling_series
            made = git(["log", "-1", "--format=%h %cs", "--", relative(series)], ROOT)
            line = ("_Read from `{}`: written by `bash benchmark/scaling.sh` (METHODS as in the "
                    "table) with the code of commit {} (the file's last commit), not remeasured "
                    "here (it takes long); rerender with `{}`._").format(
                        relative(series), made or "none: not committed", hint)
            body = line + "\n\n" + section_scaling(series)
        else:
            metas = [data[r][0] for r in SECTIONS[s]]
            rendered = [relative(m["file"]) for m in metas if m.get("file")]
            body = header(s, metas, hint, rendered) + "\n\n" + RENDER[s](data)
        if a.print:
            print(f"<!-- {s} -->\n{body}\n")
        else:
            docs[path] = replace_section(docs[path], s, body)
    if not a.print:
        for path, text in docs.items():
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
        print(f"tables: rewrote {', '.join(sections)} in {', '.join(relative(p) for p in docs)}",
              file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
