"""The runs of benchmark/tables.py: compare, icm_param and scaling.sh run one process at a
time, their JSON rows kept in the cache directory (RUN.jsonl, whose first line records the
machine, the date, the commit and the commands), and read back (--from).
"""

import datetime
import json
import os
import shlex
import subprocess
import sys
import tempfile

import plot_scaling  # the rows of a scaling series
from tables_plan import (BIG_SURFACES, BORDER_SHAPES, CLOSED_GENUS_0, CONE_MESHES, CONE_METHODS, DISKS, HERE,
                         NOT_DISKS, OPENED_METHODS, OTHER_DISKS, ROOT, SUMMARY_MESHES, SUMMARY_METHODS,
                         SURFACE_ENERGY_MESHES, SURFACE_ENERGY_METHODS, face_count, find_mesh, relative)

# ---------------------------------------------------------------- what made the figures

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
    nice = nice_prefix(a)
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



def nice_prefix(a):
    """`nice -n N` before a command, or nothing with --nice 0."""
    return ["nice", "-n", str(a.nice)] if a.nice else []


def found_meshes(names, dirs):
    """The paths of the meshes `names` in `dirs`; those not found are named and skipped."""
    found = [find_mesh(n, dirs) for n in names]
    missing = [n for n, p in zip(names, found) if p is None]
    if missing:
        print(f"tables: not found, skipped: {' '.join(missing)}", file=sys.stderr)
    return [p for p in found if p]


def compare_run(name, a, dirs):
    """(rows, commands) of a run of compare: every run but border and scaling."""
    def meshes(default):
        return found_meshes(a.meshes or default, dirs)

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
    else:
        raise SystemExit(f"tables: unknown run {name}")
    return rows, cmds


def border_run(a, dirs):
    """(rows, commands) of run border: icm_param --boundary on the disks of BORDER_SHAPES."""
    rows, cmds = [], []
    nice = nice_prefix(a)
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
    return rows, cmds


def scaling_run(a):
    """(rows, commands) of run scaling: scaling.sh with KMAX=--scaling-kmax into the cache."""
    outdir = os.path.join(a.cache, "scaling")
    env = dict(os.environ, KMAX=str(a.scaling_kmax), NAME="short")
    cmd = nice_prefix(a) + ["bash", os.path.join(HERE, "scaling.sh"), a.compare, outdir]
    print("tables: KMAX=%d %s" % (a.scaling_kmax, " ".join(cmd)), file=sys.stderr)
    subprocess.run(cmd, env=env, stdout=subprocess.DEVNULL, check=False)
    rows = plot_scaling.load(os.path.join(outdir, "short.jsonl"))
    return rows, [[f"KMAX={a.scaling_kmax}"] + cmd]


def run(name, a, dirs):
    """Makes run `name` and keeps its rows in the cache, after a first line that records how
    they were made; returns (that record, the rows)."""
    start_load, started = os.getloadavg()[0], now()
    if name == "border":
        rows, cmds = border_run(a, dirs)
    elif name == "scaling":
        rows, cmds = scaling_run(a)
    else:
        rows, cmds = compare_run(name, a, dirs)
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

