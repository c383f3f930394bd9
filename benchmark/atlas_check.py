#!/usr/bin/python3
"""Check icm_param's texture atlases (--atlas 2048 --padding 4) on a set of meshes.

For every mesh (*.off and *.obj of a directory, default /work/shared/data/meshes, or the
paths given) this runs

    icm_param MESH -o OUT/NAME.glb       --atlas 2048 --padding 4 --json   (skyline, the default)
    icm_param MESH -o OUT/NAME.ply       --atlas 2048 --padding 4 --json
    icm_param MESH -o OUT/NAME.shelf.glb --atlas 2048 --padding 4 --json --atlas-packer shelf

then reads the outputs back itself (the GLB container and its accessors; the PLY, ASCII or
binary little-endian, with per-corner `texcoord` lists) and checks

  * every UV lies in [0,1] (and how many texels the charts keep from the square's border);
  * the PLY's per-corner UVs are the GLB's (glTF stores (u, 1 - v)), face by face in the same
    order if they are, otherwise as multisets of per-face corner triples rounded to 1e-6;
    both have the JSON's face count;
  * charts = connected components of GLB triangles sharing a vertex (glTF splits vertices at
    seams); their count against the JSON's; the minimum gap between two charts in texels:
    pairs whose bounding boxes are closer than NEAR texels get the exact distance between their
    border segments (edges of one triangle only, found through a uniform grid) and a containment
    test, the others count their box distance (a lower bound, shown ">= x (bound)"). PASS if the minimum is at least
    padding - 1e-3 texel (UVs are float32);
  * utilization: the JSON's atlas_utilization for both packers, and the GLB's UV area.

It prints one Markdown table row per mesh and a machine line. Standard library only:

    /usr/bin/python3 benchmark/atlas_check.py [MESH_OR_DIR ...] [--icm build/examples/icm_param]
        [--out /tmp/atlas_check] [--size 2048] [--padding 4]
"""

import argparse
import datetime
import glob
import json
import math
import os
import platform
import struct
import subprocess
import sys
import time
from collections import Counter, defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
NEAR = 8.0  # texels: chart pairs whose boxes are closer get the exact border distance (--near)
TEXEL_SLACK = 1e-3  # float32 UVs


# ---------------------------------------------------------------- running icm_param

def run_icm(icm, mesh, out, size, padding, extra=()):
    cmd = [icm, mesh, "-o", out, "--atlas", str(size), "--padding", str(padding), "--json", "-q"]
    cmd += list(extra)
    t = time.time()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.time() - t
    j = {}
    for line in p.stdout.splitlines():
        line = line.strip()
        if line.startswith("{"):
            try:
                j = json.loads(line)
            except ValueError:
                pass
    err = j.get("error") or (p.stderr.strip().splitlines() or [""])[-1]
    return {"rc": p.returncode, "json": j, "wall": wall, "error": err if p.returncode else ""}


# ---------------------------------------------------------------- GLB reader

def read_glb(path):
    """Returns (positions, uvs, triangles) with uvs as stored (glTF's (u, 1 - v))."""
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67 or version != 2:
        raise ValueError("not a glTF 2 binary")
    if length != len(data):
        raise ValueError("GLB length %d, file %d bytes" % (length, len(data)))
    off, gltf, binary = 12, None, b""
    while off < length:
        clen, ctype = struct.unpack_from("<II", data, off)
        chunk = data[off + 8: off + 8 + clen]
        if ctype == 0x4E4F534A:
            gltf = json.loads(chunk.decode("utf-8"))
        elif ctype == 0x004E4942:
            binary = chunk
        off += 8 + clen
    if gltf is None:
        raise ValueError("no JSON chunk")
    for b in gltf.get("buffers", []):
        if "uri" in b:
            raise ValueError("external buffer in a GLB")

    fmt = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
    ncomp = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}

    def accessor(i):
        a = gltf["accessors"][i]
        view = gltf["bufferViews"][a["bufferView"]]
        f = fmt[a["componentType"]]
        n = ncomp[a["type"]]
        size = struct.calcsize("<" + f)
        stride = view.get("byteStride") or size * n
        base = view.get("byteOffset", 0) + a.get("byteOffset", 0)
        count = a["count"]
        end = base + stride * (count - 1) + size * n if count else base
        if end > view.get("byteOffset", 0) + view["byteLength"] or end > len(binary):
            raise ValueError("accessor %d overruns its buffer view" % i)
        if stride == size * n:
            flat = struct.unpack_from("<%d%s" % (count * n, f), binary, base)
            return [flat[k * n:(k + 1) * n] for k in range(count)] if n > 1 else list(flat)
        out = []
        for k in range(count):
            v = struct.unpack_from("<%d%s" % (n, f), binary, base + k * stride)
            out.append(v if n > 1 else v[0])
        return out

    positions, uvs, tris = [], [], []
    for mesh in gltf.get("meshes", []):
        for prim in mesh["primitives"]:
            if prim.get("mode", 4) != 4:
                raise ValueError("primitive mode %s, not triangles" % prim.get("mode"))
            attrs = prim["attributes"]
            if "TEXCOORD_0" not in attrs:
                raise ValueError("no TEXCOORD_0")
            uva = gltf["accessors"][attrs["TEXCOORD_0"]]
            if uva["componentType"] != 5126 or uva["type"] != "VEC2":
                raise ValueError("TEXCOORD_0 is not float VEC2")
            ind = gltf["accessors"][prim["indices"]]
            if ind["componentType"] not in (5121, 5123, 5125):
                raise ValueError("index componentType %d" % ind["componentType"])
            base = len(uvs)
            p = accessor(attrs["POSITION"])
            t = accessor(attrs["TEXCOORD_0"])
            if len(p) != len(t):
                raise ValueError("POSITION and TEXCOORD_0 counts differ")
            idx = accessor(prim["indices"])
            if len(idx) % 3:
                raise ValueError("index count not a multiple of 3")
            if idx and max(idx) >= len(t):
                raise ValueError("index out of range")
            positions += p
            uvs += t
            tris += [(base + idx[k], base + idx[k + 1], base + idx[k + 2]) for k in range(0, len(idx), 3)]
    return positions, uvs, tris


# ---------------------------------------------------------------- PLY reader

PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
             "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
             "float": "f", "float32": "f", "double": "d", "float64": "d"}


def read_ply(path):
    """Returns (header_lines, {element: [ {property: value or list} ]})."""
    data = open(path, "rb").read()
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise ValueError("not a PLY")
    nl = data.find(b"\n", end)
    header = data[:nl].decode("ascii").splitlines()
    body = data[nl + 1:]
    fmt, elements = None, []
    for line in header:
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append((w[1], int(w[2]), []))
        elif w[0] == "property":
            if w[1] == "list":
                elements[-1][2].append((w[4], "list", w[2], w[3]))
            else:
                elements[-1][2].append((w[2], "scalar", w[1], None))
    out = {}
    if fmt == "ascii":
        tokens = body.split()
        pos = 0
        for name, count, props in elements:
            rows = []
            for _ in range(count):
                row = {}
                for pname, kind, t1, t2 in props:
                    if kind == "scalar":
                        row[pname] = float(tokens[pos]); pos += 1
                    else:
                        n = int(tokens[pos]); pos += 1
                        row[pname] = [float(x) for x in tokens[pos:pos + n]]; pos += n
                rows.append(row)
            out[name] = rows
        if pos != len(tokens):
            raise ValueError("%d trailing tokens" % (len(tokens) - pos))
    elif fmt == "binary_little_endian":
        pos = 0
        for name, count, props in elements:
            rows = []
            for _ in range(count):
                row = {}
                for pname, kind, t1, t2 in props:
                    if kind == "scalar":
                        f = "<" + PLY_TYPES[t1]
                        row[pname] = struct.unpack_from(f, body, pos)[0]; pos += struct.calcsize(f)
                    else:
                        f = "<" + PLY_TYPES[t1]
                        n = struct.unpack_from(f, body, pos)[0]; pos += struct.calcsize(f)
                        f = "<%d%s" % (n, PLY_TYPES[t2])
                        row[pname] = list(struct.unpack_from(f, body, pos)); pos += struct.calcsize(f)
                rows.append(row)
            out[name] = rows
        if pos != len(body):
            raise ValueError("%d trailing bytes" % (len(body) - pos))
    else:
        raise ValueError("PLY format %s not read here" % fmt)
    return header, out


# ---------------------------------------------------------------- geometry

def seg_point_d2(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    l2 = dx * dx + dy * dy
    t = 0.0 if l2 == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / l2))
    ex, ey = ax + t * dx - px, ay + t * dy - py
    return ex * ex + ey * ey


def orient(ax, ay, bx, by, cx, cy):
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)


def seg_seg_dist(a, b, c, d):
    d1 = orient(c[0], c[1], d[0], d[1], a[0], a[1])
    d2 = orient(c[0], c[1], d[0], d[1], b[0], b[1])
    d3 = orient(a[0], a[1], b[0], b[1], c[0], c[1])
    d4 = orient(a[0], a[1], b[0], b[1], d[0], d[1])
    if ((d1 > 0 and d2 < 0) or (d1 < 0 and d2 > 0)) and ((d3 > 0 and d4 < 0) or (d3 < 0 and d4 > 0)):
        return 0.0
    return math.sqrt(min(seg_point_d2(a[0], a[1], c[0], c[1], d[0], d[1]),
                         seg_point_d2(b[0], b[1], c[0], c[1], d[0], d[1]),
                         seg_point_d2(c[0], c[1], a[0], a[1], b[0], b[1]),
                         seg_point_d2(d[0], d[1], a[0], a[1], b[0], b[1])))


def point_in_triangles(p, tris, uvs):
    x, y = p
    for t in tris:
        a, b, c = uvs[t[0]], uvs[t[1]], uvs[t[2]]
        if x < min(a[0], b[0], c[0]) or x > max(a[0], b[0], c[0]) or \
           y < min(a[1], b[1], c[1]) or y > max(a[1], b[1], c[1]):
            continue
        o1 = orient(a[0], a[1], b[0], b[1], x, y)
        o2 = orient(b[0], b[1], c[0], c[1], x, y)
        o3 = orient(c[0], c[1], a[0], a[1], x, y)
        if (o1 >= 0 and o2 >= 0 and o3 >= 0) or (o1 <= 0 and o2 <= 0 and o3 <= 0):
            return True
    return False


def charts_of(nverts, tris):
    parent = list(range(nverts))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for a, b, c in tris:
        ra, rb, rc = find(a), find(b), find(c)
        parent[rb] = ra
        parent[find(rc)] = ra
    roots = {}
    chart_of_tri = []
    for t in tris:
        r = find(t[0])
        chart_of_tri.append(roots.setdefault(r, len(roots)))
    return len(roots), chart_of_tri


def atlas_geometry(uvs, tris, size, padding):
    """Chart count, min gap in texels (and whether it is exact), border margin, UV area."""
    nch, chart_of_tri = charts_of(len(uvs), tris)
    area = 0.0
    for a, b, c in tris:
        pa, pb, pc = uvs[a], uvs[b], uvs[c]
        area += 0.5 * abs(orient(pa[0], pa[1], pb[0], pb[1], pc[0], pc[1]))
    used = sorted({v for t in tris for v in t})
    margin = min(min(uvs[v][0], 1 - uvs[v][0], uvs[v][1], 1 - uvs[v][1]) for v in used) * size
    if nch < 2:
        return {"charts": nch, "gap": math.inf, "gap_exact": True, "margin": margin, "area": area,
                "near_pairs": 0}

    # boxes
    box = [[math.inf, math.inf, -math.inf, -math.inf] for _ in range(nch)]
    tris_of = [[] for _ in range(nch)]
    for t, c in zip(tris, chart_of_tri):
        tris_of[c].append(t)
        b = box[c]
        for v in t:
            x, y = uvs[v]
            if x < b[0]: b[0] = x
            if y < b[1]: b[1] = y
            if x > b[2]: b[2] = x
            if y > b[3]: b[3] = y
    pair_gap = {}
    near = set()
    for i in range(nch):
        bi = box[i]
        for j in range(i + 1, nch):
            bj = box[j]
            dx = max(0.0, bj[0] - bi[2], bi[0] - bj[2])
            dy = max(0.0, bj[1] - bi[3], bi[1] - bj[3])
            g = math.hypot(dx, dy) * size
            pair_gap[(i, j)] = g
            if g < NEAR:
                near.add((i, j))
    exact = {}
    if near:
        # border segments of the charts that are in a near pair
        involved = {i for p in near for i in p}
        count = Counter()
        for t, c in zip(tris, chart_of_tri):
            if c in involved:
                for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])):
                    count[(min(e), max(e), c)] += 1
        segs = [(a, b, c) for (a, b, c), n in count.items() if n == 1]
        h = NEAR / size
        grid = defaultdict(list)
        for k, (a, b, c) in enumerate(segs):
            (ax, ay), (bx, by) = uvs[a], uvs[b]
            for gx in range(int(math.floor(min(ax, bx) / h)), int(math.floor(max(ax, bx) / h)) + 1):
                for gy in range(int(math.floor(min(ay, by) / h)), int(math.floor(max(ay, by) / h)) + 1):
                    grid[(gx, gy)].append(k)
        for k, (a, b, c) in enumerate(segs):
            pa, pb = uvs[a], uvs[b]
            seen = set()
            for gx in range(int(math.floor(min(pa[0], pb[0]) / h)) - 1, int(math.floor(max(pa[0], pb[0]) / h)) + 2):
                for gy in range(int(math.floor(min(pa[1], pb[1]) / h)) - 1, int(math.floor(max(pa[1], pb[1]) / h)) + 2):
                    for m in grid.get((gx, gy), ()):
                        if m <= k or m in seen:
                            continue
                        seen.add(m)
                        a2, b2, c2 = segs[m]
                        if c2 == c:
                            continue
                        key = (min(c, c2), max(c, c2))
                        if key not in near:
                            continue
                        d = seg_seg_dist(pa, pb, uvs[a2], uvs[b2]) * size
                        if d < exact.get(key, math.inf):
                            exact[key] = d
        # one chart inside another without their borders meeting
        for (i, j) in near:
            if pair_gap[(i, j)] == 0 and exact.get((i, j), math.inf) > 0:
                if point_in_triangles(uvs[tris_of[i][0][0]], tris_of[j], uvs) or \
                   point_in_triangles(uvs[tris_of[j][0][0]], tris_of[i], uvs):
                    exact[(i, j)] = 0.0
    gap, gap_exact = math.inf, True
    for key, g in pair_gap.items():
        if key in near:
            d = exact.get(key, NEAR)  # nothing within the grid's reach: at least NEAR
            is_exact = key in exact
        else:
            d, is_exact = g, False
        if d < gap:
            gap, gap_exact = d, is_exact
    return {"charts": nch, "gap": gap, "gap_exact": gap_exact, "margin": margin, "area": area,
            "near_pairs": len(near)}


# ---------------------------------------------------------------- one mesh

def check_mesh(args, mesh):
    name = os.path.splitext(os.path.basename(mesh))[0]
    glb = os.path.join(args.out, name + ".glb")
    ply = os.path.join(args.out, name + ".ply")
    shelf = os.path.join(args.out, name + ".shelf.glb")
    r = {"mesh": name, "problems": []}
    r["glb"] = run_icm(args.icm, mesh, glb, args.size, args.padding)
    r["ply"] = run_icm(args.icm, mesh, ply, args.size, args.padding)
    r["shelf"] = run_icm(args.icm, mesh, shelf, args.size, args.padding, ["--atlas-packer", "shelf"])
    for k in ("glb", "ply", "shelf"):
        if r[k]["rc"] != 0:
            r["problems"].append("%s: exit %d: %s" % (k, r[k]["rc"], r[k]["error"]))
    j = r["glb"]["json"]
    faces = j.get("faces")

    def geometry(path, label):
        try:
            pos, uvs, tris = read_glb(path)
        except Exception as e:  # noqa: BLE001 - reported in the row
            r["problems"].append("%s unreadable: %s" % (label, e))
            return None
        used = {v for t in tris for v in t}
        bad = sum(1 for v in used if not (0 <= uvs[v][0] <= 1 and 0 <= uvs[v][1] <= 1))
        g = atlas_geometry(uvs, tris, args.size, args.padding)
        g.update({"tris": tris, "uvs": uvs, "pos": pos, "out_of_square": bad})
        if faces is not None and len(tris) != faces:
            r["problems"].append("%s has %d triangles, JSON faces %d" % (label, len(tris), faces))
        return g

    if r["glb"]["rc"] == 0:
        r["g"] = geometry(glb, "GLB")
    if r["shelf"]["rc"] == 0:
        r["gs"] = geometry(shelf, "shelf GLB")
    g = r.get("g")
    if g and r["ply"]["rc"] == 0:
        try:
            header, el = read_ply(ply)
            verts, pfaces = el.get("vertex", []), el.get("face", [])
            r["ply_header"] = header
            ok = True
            if len(pfaces) != faces:
                r["problems"].append("PLY has %d faces, JSON %d" % (len(pfaces), faces))
                ok = False
            puv = [f["texcoord"] for f in pfaces]
            bad = sum(1 for t in puv for x in t if not 0 <= x <= 1)
            r["ply_out_of_square"] = bad
            # GLB per-corner (u, 1 - v) back to (u, v)
            guv = [[c for v in t for c in (g["uvs"][v][0], 1.0 - g["uvs"][v][1])] for t in g["tris"]]
            same_order = len(puv) == len(guv) and all(len(p) == 6 for p in puv)
            maxdiff = 0.0
            if same_order:
                for p, q in zip(puv, guv):
                    for a, b in zip(p, q):
                        d = abs(a - b)
                        if d > maxdiff:
                            maxdiff = d
                same_order = maxdiff <= 1e-6
            if same_order:
                # the positions of the corners too (PLY prints 6 significant digits)
                xs = [c for p in g["pos"] for c in p]
                tol = 1e-5 * (max(xs) - min(xs) + 1e-30) if xs else 0
                for f, t in zip(pfaces, g["tris"]):
                    for vi, gv in zip(f["vertex_indices"], t):
                        pv = verts[int(vi)]
                        gp = g["pos"][gv]
                        if max(abs(pv["x"] - gp[0]), abs(pv["y"] - gp[1]), abs(pv["z"] - gp[2])) > tol:
                            ok = False
                if not ok:
                    r["problems"].append("PLY and GLB corner positions differ")
                r["ply_eq"] = ("yes" if ok else "NO") + " (in order, max %.1e)" % maxdiff
            else:
                def key(t):
                    return tuple(round(x, 6) for x in t)
                same = Counter(key(t) for t in puv) == Counter(key(t) for t in guv)
                r["ply_eq"] = ("yes" if same and ok else "NO") + " (as multisets; in-order max %.1e)" % maxdiff
                if not same:
                    jp = r["ply"]["json"]
                    runs = [k for k in ("atlas_rotated_charts", "atlas_utilization", "charts", "cones")
                            if j.get(k) != jp.get(k)]
                    r["problems"].append("PLY and GLB per-corner UVs differ" + (
                        " (the two icm_param runs packed differently: " +
                        ", ".join("%s %s vs %s" % (k, j.get(k), jp.get(k)) for k in runs) + ")" if runs else ""))
        except Exception as e:  # noqa: BLE001
            r["problems"].append("PLY unreadable: %s" % e)
    return r


def fmt_gap(g, padding):
    if g is None:
        return "-"
    s = "inf" if g["gap"] == math.inf else ("%.2f" if g["gap_exact"] else ">= %.2f (bound)") % g["gap"]
    return s + (" PASS" if g["gap"] >= padding - TEXEL_SLACK else " **FAIL**")


def row(args, r):
    j = r["glb"]["json"]
    g, gs = r.get("g"), r.get("gs")
    js = r["shelf"]["json"]
    faces = j.get("faces", "-")
    charts = "-"
    if g:
        ok = g["charts"] == j.get("atlas_charts") == j.get("charts")
        charts = "%d%s" % (g["charts"], "" if ok else " (JSON charts %s, atlas_charts %s)" % (
            j.get("charts"), j.get("atlas_charts")))
        if not ok:
            r["problems"].append("chart count differs from the JSON")

    def util(jj, gg):
        if "atlas_utilization" not in jj:
            return "-"
        s = "%.1f%%" % (100 * jj["atlas_utilization"])
        if gg and abs(gg["area"] - jj["atlas_utilization"]) > 1e-5:
            s += " (GLB area %.1f%%)" % (100 * gg["area"])
        return s

    if g:
        inside = g["out_of_square"] == 0 and r.get("ply_out_of_square", 0) == 0 and \
            (not gs or gs["out_of_square"] == 0)
        uv01 = ("yes" if inside else "**NO**") + " (margin %.2f / %.2f)" % (
            g["margin"], gs["margin"] if gs else float("nan"))
        if not inside:
            r["problems"].append("UVs outside [0,1]")
    else:
        uv01 = "-"
    if g and min(g["margin"], gs["margin"] if gs else math.inf) < args.padding - TEXEL_SLACK:
        r["problems"].append("a chart closer than the padding to the square's border")
    secs = " / ".join("%.2f" % r[k]["json"]["seconds_total"] if "seconds_total" in r[k]["json"] else "-"
                      for k in ("glb", "ply", "shelf"))
    cells = [r["mesh"], str(faces), charts, util(j, g), util(js, gs),
             fmt_gap(g, args.padding) + " / " + fmt_gap(gs, args.padding), uv01,
             r.get("ply_eq", "-"), secs]
    if r["problems"]:
        cells[0] += " — " + "; ".join(r["problems"]).replace("|", "\\|")
    return "| " + " | ".join(cells) + " |"


def main():
    global NEAR
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("meshes", nargs="*", default=["/work/shared/data/meshes"])
    ap.add_argument("--icm", default=os.path.join(REPO, "build", "examples", "icm_param"))
    ap.add_argument("--out", default="/tmp/atlas_check")
    ap.add_argument("--size", type=int, default=2048)
    ap.add_argument("--padding", type=int, default=4)
    ap.add_argument("--near", type=float, default=NEAR,
                    help="chart pairs whose boxes are closer than this many texels get the exact distance (default %(default)s)")
    args = ap.parse_args()
    NEAR = max(args.near, args.padding)
    meshes = []
    for m in args.meshes:
        if os.path.isdir(m):
            meshes += sorted(glob.glob(os.path.join(m, "*.off")) + glob.glob(os.path.join(m, "*.obj")))
        else:
            meshes.append(m)
    meshes.sort(key=lambda p: os.path.basename(p))
    os.makedirs(args.out, exist_ok=True)

    try:
        rev = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                             stderr=subprocess.DEVNULL, text=True).stdout.strip()
    except OSError:
        rev = "?"
    print("Machine: %s, %d cores, %s, ICM %s; `icm_param MESH -o OUT --atlas %d --padding %d`"
          % (platform.machine(), len(os.sched_getaffinity(0)), datetime.datetime.now().astimezone().strftime("%Y-%m-%d %H:%M %Z"),
             rev, args.size, args.padding))
    print()
    print("| mesh | faces | charts | utilization (skyline) | utilization (shelf) | min gap texels (skyline / shelf) "
          "| UVs in [0,1] (border margin texels, skyline / shelf) | PLY = GLB | seconds (glb / ply / shelf) |")
    print("|---|---:|---:|---:|---:|---|---|---|---|")
    sys.stdout.flush()
    failures = 0
    for m in meshes:
        try:
            r = check_mesh(args, m)
            line = row(args, r)
            failures += bool(r["problems"])
        except Exception as e:  # noqa: BLE001 - one bad mesh does not stop the table
            line = "| %s — check crashed: %s | | | | | | | | |" % (os.path.basename(m), e)
            failures += 1
        print(line)
        sys.stdout.flush()
    print()
    print("%d of %d meshes with a problem" % (failures, len(meshes)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
