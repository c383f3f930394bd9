#!/usr/bin/python3
"""Checks that two builds of icm_param give the same maps: a refactoring must not change them.

    scripts/check_same_maps.py REFERENCE_ICM_PARAM CANDIDATE_ICM_PARAM [--meshes DIR]
                               [--only SUBSTRING] [--jobs N] [--timeout SECONDS] [--cache DIR]

Runs both binaries on every mesh of DIR (default ../shared/data/meshes) with every option the
README lists (each metric, each energy, each border condition, --cones 0, --keep-overlaps) and
compares, case by case:
  - the exit status and the error line (a refused case must be refused for the same reason);
  - the OBJ: the same vertices and faces, every UV within 1e-12 of the UV extent; where they
    differ, whether the UV edge lengths agree (to 1e-9 of the extent): the charts only moved;
  - the JSON figures: strings equal, numbers within 1e-9 relative (timings are skipped, and
    figures the reference does not write; the figures of rounding, such as the layout's
    length error, are the same below 1e-8).
Prints one line per case that differs and a summary; exits 1 if any case differs.
With --cache, the reference's results are kept in DIR and read back on the next run (the
reference binary is then not run again: clear DIR when it changes); CANDIDATE "-" only fills it.
"""

import argparse
import concurrent.futures
import hashlib
import json
import math
import os
import subprocess
import sys
import tempfile

UV_TOLERANCE = 1e-12       # relative to the largest |UV| of the map
SHAPE_TOLERANCE = 1e-9     # of the UV extent, for UV edge lengths when the UVs differ
FIGURE_TOLERANCE = 1e-9    # relative, for the JSON numbers derived from the UVs
SKIPPED_KEYS = ("input", "output")
# Figures that measure rounding (a layout's edge lengths against the metric's, a seam's two
# sides, the curvature left by Newton): the same map may carry other rounding, so these are
# the same when both are below ROUNDING_LEVEL or within FIGURE_TOLERANCE of each other.
ROUNDING_KEYS = ("max_layout_length_error", "seam_length_error", "max_curvature_error")
ROUNDING_LEVEL = 1e-8

DISK_ONLY = ("--boundary circle", "--boundary square")


def cases():
    """Every option of the README, each on its own beside the defaults."""
    yield ""
    for metric in ("vertex-scaling", "inversive-distance", "circle-packing"):
        yield "--metric " + metric
    for energy in ("u-square", "area", "angle", "log-area"):
        yield "--energy " + energy
    for boundary in ("circle", "square", "circle-domain"):
        yield "--boundary " + boundary
    yield "--cones 0"
    yield "--keep-overlaps"


def run(exe, mesh, options, out_dir, timeout):
    out = os.path.join(out_dir, "uv.obj")
    command = [exe, mesh, "-o", out, "--json"] + options.split()
    try:
        p = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"status": "timeout"}
    result = {"status": p.returncode, "error": "", "json": None, "obj": None}
    errors = [l for l in p.stderr.splitlines() if l.startswith("icm_param:")]
    result["error"] = errors[-1] if errors else ""
    if p.returncode == 0:
        result["json"] = json.loads(p.stdout.strip().splitlines()[-1])
        result["obj"] = read_obj(out)
    return result


def read_obj(path):
    v, vt, f = [], [], []
    with open(path) as file:
        for line in file:
            if line.startswith("v "):
                v.append(line.split()[1:])
            elif line.startswith("vt "):
                vt.append([float(x) for x in line.split()[1:3]])
            elif line.startswith("f "):
                f.append(line.split()[1:])
    return v, vt, f


def edge_length_difference(vt0, vt1, faces, extent):
    """The largest difference of a face's UV edge length between two maps with the same faces,
    relative to the UV extent: zero when they differ by a rigid motion of each chart (the
    propagation's root, or the packing's order, chosen by a comparison that rounding can tip)."""
    worst = 0.0
    for f in faces:
        corners = [int(c.split("/")[1]) - 1 for c in f]
        for i in range(len(corners)):
            a, b = corners[i], corners[(i + 1) % len(corners)]
            worst = max(worst, abs(math.dist(vt0[a], vt0[b]) - math.dist(vt1[a], vt1[b])))
    return worst / extent


def number_differs(a, b):
    if a is None or b is None:
        return a is not b
    if isinstance(a, bool) or isinstance(b, bool) or not isinstance(a, (int, float)):
        return a != b
    if math.isnan(a) or math.isnan(b):
        return not (math.isnan(a) and math.isnan(b))
    return abs(a - b) > FIGURE_TOLERANCE * max(abs(a), abs(b), 1e-300) and abs(a - b) > 1e-14


def differences(ref, new):
    """The ways `new` differs from `ref`, in words."""
    if ref["status"] != new["status"]:
        return ["exit status %s -> %s (%s)" % (ref["status"], new["status"], new.get("error", ""))]
    if ref["status"] == "timeout":
        return []
    found = []
    if ref["error"] != new["error"]:
        found.append("error %r -> %r" % (ref["error"], new["error"]))
    if ref["status"] != 0:
        return found
    for key in sorted(set(ref["json"]) | set(new["json"])):
        if key.startswith("seconds_") or key in SKIPPED_KEYS:
            continue
        if key not in ref["json"]:
            continue  # a figure the candidate adds is no change of the map
        a, b = ref["json"].get(key, "<missing>"), new["json"].get(key, "<missing>")
        if key in ROUNDING_KEYS and isinstance(a, float) and isinstance(b, float) and \
                max(abs(a), abs(b)) < ROUNDING_LEVEL:
            continue
        if number_differs(a, b):
            found.append("%s %r -> %r" % (key, a, b))
    (v0, vt0, f0), (v1, vt1, f1) = ref["obj"], new["obj"]
    if v0 != v1:
        found.append("vertices differ")
    if f0 != f1:
        found.append("faces differ")
    elif len(vt0) != len(vt1):
        found.append("%d UVs -> %d" % (len(vt0), len(vt1)))
    else:
        extent = max((max(abs(u), abs(w)) for u, w in vt0), default=1.0)
        worst = max((max(abs(a[0] - b[0]), abs(a[1] - b[1])) for a, b in zip(vt0, vt1)), default=0.0)
        if worst > UV_TOLERANCE * extent:
            shape = edge_length_difference(vt0, vt1, f0, extent)
            found.append("UVs differ by %.3g of the extent (UV edge lengths by %.3g of it: %s)" %
                         (worst / extent, shape, "the same up to a rigid motion of each chart"
                          if shape <= SHAPE_TOLERANCE else "another map"))
    return found


def cached_run(exe, mesh, options, timeout, cache):
    if not cache:
        with tempfile.TemporaryDirectory() as out:
            return run(exe, mesh, options, out, timeout)
    key = hashlib.sha1(("%s|%s|%s" % (os.path.abspath(exe), os.path.abspath(mesh), options)).encode()).hexdigest()
    path = os.path.join(cache, key + ".json")
    if os.path.exists(path):
        with open(path) as file:
            return json.load(file)
    with tempfile.TemporaryDirectory() as out:
        result = run(exe, mesh, options, out, timeout)
    with open(path + ".tmp", "w") as file:
        json.dump(result, file)
    os.replace(path + ".tmp", path)
    return result


def check(reference, candidate, mesh, options, timeout, cache):
    ref = cached_run(reference, mesh, options, timeout, cache)
    if candidate == "-":  # only fill the cache
        return mesh, options, ref["status"], []
    new = cached_run(candidate, mesh, options, timeout, None)
    return mesh, options, ref["status"], differences(ref, new)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("reference")
    parser.add_argument("candidate")
    parser.add_argument("--meshes", default=os.path.join(here, "..", "..", "shared", "data", "meshes"))
    parser.add_argument("--only", default="", help="only meshes whose file name contains this")
    parser.add_argument("--jobs", type=int, default=1, help="cases run at once (each runs two binaries in turn)")
    parser.add_argument("--timeout", type=float, default=900, help="seconds per run; a case both time out is equal")
    parser.add_argument("--cache", default="", help="keep the reference's results in this folder")
    args = parser.parse_args()

    meshes = sorted(os.path.join(args.meshes, m) for m in os.listdir(args.meshes)
                    if m.endswith((".off", ".obj", ".ply", ".stl")) and args.only in m)
    work = [(m, o) for m in meshes for o in cases()]
    failures = 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        if args.cache:
            os.makedirs(args.cache, exist_ok=True)
        futures = [pool.submit(check, args.reference, args.candidate, m, o, args.timeout, args.cache) for m, o in work]
        for future in concurrent.futures.as_completed(futures):
            mesh, options, status, found = future.result()
            name = "%s %s" % (os.path.basename(mesh), options or "(defaults)")
            if found:
                failures += 1
                print("DIFFERS %s: %s" % (name, "; ".join(found)), flush=True)
            else:
                print("same    %s (exit %s)" % (name, status), flush=True)
    print("%d of %d cases differ" % (failures, len(work)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
