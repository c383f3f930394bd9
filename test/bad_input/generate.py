#!/usr/bin/env python3
"""Writes the bad-input corpus of icm_param (test/bad_input/) and its manifest expected.tsv.

Each case is a small file that a hostile or careless user could hand to icm_param, with the
exit status it must give (0: read, repaired if needed, and parameterized; nonzero: refused)
and a substring of the message it must print on stderr. run_corpus.sh runs them in ctest.
Run this script again after changing a case; the files are committed, so the test does not
need Python.
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
cases = []  # (file, extra arguments, expected exit, substring of stderr)


def write(name, content, expect, message, args=""):
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(os.path.join(HERE, name), mode) as f:
        f.write(content)
    cases.append((name, args, expect, message))


# A 4 x 4 grid of vertices with a bump: a disk of 18 triangles, consistently oriented.
def grid(scale=1.0, n=4):
    pts = []
    for j in range(n):
        for i in range(n):
            x, y = i / (n - 1), j / (n - 1)
            pts.append((x * scale, y * scale, 0.3 * math.sin(3 * x) * math.cos(2 * y) * scale))
    tris = []
    for j in range(n - 1):
        for i in range(n - 1):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i
            tris += [(a, b, c), (a, c, d)]
    return pts, tris


def off(pts, faces, keyword="OFF", vertex_extra=lambda i: "", face_extra=""):
    lines = [keyword, f"{len(pts)} {len(faces)} 0"]
    lines += [" ".join(repr(x) for x in p) + vertex_extra(i) for i, p in enumerate(pts)]
    lines += [f"{len(f)} " + " ".join(map(str, f)) + face_extra for f in faces]
    return "\n".join(lines) + "\n"


def obj(pts, faces, one_based=True):
    lines = ["# a small disk"] + ["v " + " ".join(repr(x) for x in p) for p in pts]
    lines += ["f " + " ".join(str(i + 1) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def ply_header(fmt, nv, nf, xyz="float", index="int", count="uchar", extra=""):
    return (f"ply\nformat {fmt} 1.0\ncomment test\nelement vertex {nv}\nproperty {xyz} x\n"
            f"property {xyz} y\nproperty {xyz} z\n{extra}element face {nf}\n"
            f"property list {count} {index} vertex_indices\nend_header\n")


def ply_binary(pts, faces, endian="<", fmt="binary_little_endian", xyz="f", xyz_name="float",
               count_override=None, header_counts=None):
    nv, nf = header_counts or (len(pts), len(faces))
    out = ply_header(fmt, nv, nf, xyz_name).encode()
    for p in pts:
        out += struct.pack(endian + xyz * 3, *p)
    for k, f in enumerate(faces):
        n = len(f) if count_override is None or k != len(faces) - 1 else count_override
        out += struct.pack(endian + "B", n) + struct.pack(endian + "i" * len(f), *f)
    return out


def stl_ascii(pts, faces):
    lines = ["solid test"]
    for f in faces:
        lines += ["  facet normal 0 0 1", "    outer loop"]
        lines += ["      vertex " + " ".join(repr(x) for x in pts[i]) for i in f]
        lines += ["    endloop", "  endfacet"]
    lines.append("endsolid test")
    return "\n".join(lines) + "\n"


def stl_binary(pts, faces, count=None, header=b"binary stl"):
    out = header.ljust(80, b" ") + struct.pack("<I", len(faces) if count is None else count)
    for f in faces:
        out += struct.pack("<3f", 0, 0, 1)
        for i in f:
            out += struct.pack("<3f", *pts[i])
        out += b"\0\0"
    return out


P, T = grid()
quad_pts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (2, 0, 0), (2, 1, 0)]
quads = [(0, 1, 2, 3), (1, 4, 5, 2)]

# --- OFF: header counts, indices, numbers, truncation ---------------------------------------
write("off_empty.off", "", 1, "the file is empty")
write("off_only_keyword.off", "OFF\n", 1, "no vertex and face counts")
write("off_count_too_large.off", "OFF\n2000000000 1 0\n0 0 0\n3 0 0 0\n", 1, "more than this reader takes")
write("off_vertex_count_lies.off", "OFF\n100000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 1,
      "bytes follow")
write("off_face_count_lies.off", "OFF\n3 200000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 1, "bytes follow")
write("off_negative_count.off", "OFF\n-3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 1, "not a non-negative integer")
write("off_count_not_a_number.off", "OFF\nthree 1 0\n", 1, "not a non-negative integer")
write("off_index_out_of_range.off", off(P, T[:-1] + [(0, 5, 16)]), 1, "vertex index 16 is out of range")
write("off_negative_index.off", off(P, [(0, -1, 5)] + T[1:]), 1, "vertex index -1 is out of range")
write("off_huge_index.off", off(P, [(0, 1, 99999999999999999999)] + T[1:]), 1, "not a vertex index")
write("off_more_faces_than_announced.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n", 1,
      "line 7: the file goes on after the 1 faces its header announces")
write("off_byte_order_mark.off", "\ufeff" + off(P, T), 0, "-")
write("obj_byte_order_mark.obj", "\ufeff" + obj(P, T), 0, "-")
write("off_face_size_huge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n1000000000 0 1 2\n", 1,
      "announces 1000000000 corners")
write("off_face_size_two.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 1, "a face needs at least 3")
write("off_face_lists_too_few.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n", 1, "lists 2")
write("off_face_trailing_garbage.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 2 3 4 5 6\n", 1,
      "at most a colour")
write("off_nan.off", off([(0, 0, 0), (1, 0, 0), (1, float("nan"), 0), (0, 1, 0)], [(0, 1, 2), (0, 2, 3)]),
      1, "non-finite coordinate")
write("off_inf.off", "OFF\n3 1 0\n0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n", 1, "non-finite coordinate")
write("off_number_overflow.off", "OFF\n3 1 0\n0 0 0\n1e999 0 0\n0 1 0\n3 0 1 2\n", 1, "not a number")
write("off_not_a_number.off", "OFF\n3 1 0\n0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n", 1, "'zero' is not a number")
write("off_vertex_too_few_numbers.off", "OFF\n3 1 0\n0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 1, "has 2 numbers")
write("off_truncated_vertices.off", off(P, T)[:120], 1, "truncated")
write("off_truncated_faces.off", off(P, T)[:-40], 1, "truncated")
write("off_repeated_corner.off", off(P, [(0, 0, 5)] + T[1:]), 1, "twice")
write("off_binary_garbage.off", bytes(range(256)) * 4, 1, "does not start with an OFF keyword")
# --- OFF variants ----------------------------------------------------------------------------
write("off_stoff.off", off(P, T, "STOFF", lambda i: f" {i * 0.1} {i * 0.2}"), 0, "")
write("off_coff_rgba.off", off(P, T, "COFF", lambda i: " 255 0 0 255"), 0, "")
write("off_coff_rgb_float.off", off(P, T, "COFF", lambda i: " 1.0 0.5 0.0"), 0, "")
write("off_noff.off", off(P, T, "NOFF", lambda i: " 0 0 1"), 0, "")
write("off_stcnoff.off", off(P, T, "STCNOFF", lambda i: " 0 0 1 1 1 1 1 0.5 0.5"), 0, "")
write("off_4off.off", off([(x * 2, y * 2, z * 2) for x, y, z in P], T, "4OFF", lambda i: " 2"), 0, "")
write("off_face_colours.off", off(P, T, face_extra=" 255 0 0"), 0, "")
write("off_counts_on_keyword_line.off", off(P, T).replace("OFF\n", "OFF ", 1), 0, "")
write("off_comments_and_blanks.off", "# a comment\n\n" + off(P, T).replace("\n", "  # c\n\n", 3), 0, "")
write("off_stoff_without_texture.off", off(P, T, "STOFF"), 1, "has 3 numbers")
write("off_coff_too_many_numbers.off", off(P, T, "COFF", lambda i: " 1 2 3 4 5 6"), 1, "numbers")
write("off_noff_missing_normal.off", off(P, T, "NOFF", lambda i: " 0 1"), 1, "numbers")
write("off_binary.off", "OFF BINARY\n", 1, "binary OFF is not supported")
write("off_ndim.off", "nOFF\n3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 1, "nOFF")
write("off_4off_w_zero.off", off(P, T, "4OFF", lambda i: " 0"), 1, "w = 0")
write("off_unknown_keyword.off", off(P, T, "XYOFF"), 1, "unknown OFF keyword")
# --- repairs and topology ----------------------------------------------------------------------
write("off_isolated_vertex.off", off(P + [(5, 5, 5)], T), 0, "dropped 1 isolated vertex")
write("off_isolated_vertex_first.off", off([(9, 9, 9)] + P, [tuple(i + 1 for i in t) for t in T]), 0,
      "dropped 1 isolated vertex")
# Two disks sharing vertex 0 only: one vertex with two fans of faces.
bowtie = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (-1, 0, 0), (-1, -1, 0), (0, -1, 0)]
write("off_nonmanifold_vertex.off", off(bowtie, [(0, 1, 2), (0, 2, 3), (0, 4, 5), (0, 5, 6)]), 0,
      "split 1 non-manifold vertex")
# Two closed tetrahedra sharing vertex 0: two closed fans at one vertex.
tet = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (-1, 0, 0), (0, -1, 0), (0, 0, -1)]
write("off_two_tetrahedra_one_vertex.off",
      off(tet, [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3), (0, 4, 5), (0, 5, 6), (0, 6, 4), (4, 6, 5)]), 0,
      "split 1 non-manifold vertex")
write("off_nonmanifold_edge.off",
      off([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)], [(0, 1, 2), (1, 0, 3), (0, 1, 4)]), 1,
      "non-manifold edge")
# The first face against the 17 others: it is the one reversed, not the others.
write("off_inconsistent_orientation.off", off(P, [(T[0][0], T[0][2], T[0][1])] + T[1:]), 0,
      "reoriented 1 face to agree with the faces around it: 0")
# A Moebius strip: no consistent orientation exists.
mob_pts, mob_tris, m = [], [], 8
for k in range(m):
    a = 2 * math.pi * k / m
    for s in (-0.3, 0.3):
        r = 1 + s * math.cos(a / 2)
        mob_pts.append((r * math.cos(a), r * math.sin(a), s * math.sin(a / 2)))
for k in range(m):
    i0, i1 = 2 * k, 2 * k + 1
    j0, j1 = (2 * k + 2, 2 * k + 3) if k < m - 1 else (1, 0)
    mob_tris += [(i0, j0, j1), (i0, j1, i1)]
write("off_moebius.off", off(mob_pts, mob_tris), 1, "the surface is not orientable")
write("off_quads.off", off(quad_pts, quads), 1, "non-triangle faces")
cases.append(("off_quads.off", "--triangulate", 0, "triangulated 2 polygons"))
write("off_degenerate_face.off", "OFF\n4 3 0\n0 0 0\n1 0 0\n2 0 0\n1 1 0\n3 0 1 3\n3 1 2 3\n3 0 2 1\n", 1,
      "degenerate")
write("off_all_corners_equal.off", "OFF\n4 2 0\n0 0 0\n0 0 0\n0 0 0\n1 1 0\n3 0 1 2\n3 0 2 3\n", 1, "degenerate")
write("off_no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", 1, "no faces")
write("off_face_listed_twice.off", off(P, T + [T[0]]), 1, "a face listed twice")
# A plane heptagon, simple and as the star {7/2} whose sides cross: CGAL's triangulate_face
# crashed on the star.
hept = [(math.cos(2 * math.pi * k / 7), math.sin(2 * math.pi * k / 7), 0.0) for k in range(7)]
write("off_heptagon.off", off(hept, [tuple(range(7))]), 1, "non-triangle faces")
cases.append(("off_heptagon.off", "--triangulate", 0, "triangulated 1 polygon"))
write("off_heptagon_self_crossing.off", off(hept, [tuple(2 * k % 7 for k in range(7))]), 1, "non-triangle faces")
cases.append(("off_heptagon_self_crossing.off", "--triangulate", 1,
              "its side from vertex 0 to vertex 2 meets its side from vertex 6 to vertex 1 on its best-fit plane"))
# --- topologies that must work: closed, genus 1, two components --------------------------------
def uv_sphere(n=6, m=8):
    pts = [(0, 0, 1)] + [(math.sin(math.pi * i / n) * math.cos(2 * math.pi * j / m),
                          math.sin(math.pi * i / n) * math.sin(2 * math.pi * j / m),
                          math.cos(math.pi * i / n)) for i in range(1, n) for j in range(m)] + [(0, 0, -1)]
    tris = [(0, 1 + j, 1 + (j + 1) % m) for j in range(m)]
    for i in range(n - 2):
        for j in range(m):
            a, b = 1 + i * m + j, 1 + i * m + (j + 1) % m
            tris += [(a, a + m, b + m), (b, a, b + m)] if False else [(a, a + m, b), (b, a + m, b + m)]
    last = len(pts) - 1
    tris += [(1 + (n - 2) * m + j, last, 1 + (n - 2) * m + (j + 1) % m) for j in range(m)]
    return pts, tris


def torus(n=10, m=6):
    pts = [((2 + math.cos(2 * math.pi * j / m)) * math.cos(2 * math.pi * i / n),
            (2 + math.cos(2 * math.pi * j / m)) * math.sin(2 * math.pi * i / n),
            math.sin(2 * math.pi * j / m)) for i in range(n) for j in range(m)]
    tris = []
    for i in range(n):
        for j in range(m):
            a, b = i * m + j, i * m + (j + 1) % m
            c, d = ((i + 1) % n) * m + j, ((i + 1) % n) * m + (j + 1) % m
            tris += [(a, c, d), (a, d, b)]
    return pts, tris


write("topology_sphere.off", off(*uv_sphere()), 0, "")
write("topology_torus.off", off(*torus()), 0, "")
write("topology_two_disks.off", off(P + [(x + 3, y, z) for x, y, z in P], T + [tuple(i + len(P) for i in t) for t in T]),
      0, "")
cases.append(("topology_sphere.off", "--cones 0", 1, "needs at least two cones"))


# A 6 x 6 grid with a hole where an interior vertex's star was, but for one face: that face
# has all three corners on the hole's loop, so on the hole's circle it would lie in the hole.
def grid_with_an_ear(n=6):
    pts, tris = grid(n=n)
    centre = (n // 2) * n + n // 2
    star = [t for t in tris if centre in t]
    keep = star[0]
    return pts, [t for t in tris if centre not in t or t == keep]


write("topology_hole_ear.off", off(*grid_with_an_ear()), 1, "all three corners on one hole's border",
      "--boundary circle-domain")

# --- scale: any finite scale works as 1 does --------------------------------------------------------
write("scale_1e-300.off", off(grid(1e-300)[0], T), 0, "")
write("scale_1e+300.off", off(grid(1e300)[0], T), 0, "")
write("scale_1e-300.obj", obj(grid(1e-300)[0], T), 0, "")
write("scale_1e+300_binary.ply", ply_binary(grid(1e300)[0], T, xyz="d", xyz_name="double"), 0, "")
write("scale_offset_1e+12.off", off([(x + 1e12, y + 1e12, z) for x, y, z in P], T), 0, "")
# A unit disk beside one 1e200 or 1e308 times larger: the reader takes both, but one UV map
# whose charts keep their 3D scale cannot hold both (the small chart would round to a point
# where it is packed), so ICM::parameterize refuses the small one and says why.
for big in (1e200, 1e308):
    write(f"scale_two_disks_1e+{round(math.log10(big))}.off",
          off(P + [(x * big / 2 + big / 2, y * big / 2, z * big / 2) for x, y, z in P],
              T + [tuple(i + len(P) for i in t) for t in T]), 1, "too small to share one UV map with the rest")
# A disk so large that its layout, scaled back to it, overflows: the writer names the extent.
write("scale_layout_overflow.off", off(grid(1.7e308)[0], T), 1, "scaled back to the mesh's extent")
# Coordinates whose differences overflow a double: refused by the extent, not a face.
write("scale_extent_overflow.off", off([(-1e308, 0, 0)] + P[1:-1] + [(1e308, 1, 0)], T), 1,
      "the mesh's extent along x, from -1e+308 to 1e+308, is beyond the range of a double")

# --- OBJ ---------------------------------------------------------------------------------------
write("obj_valid_texture_normals.obj",
      "\n".join(["mtllib none.mtl", "o disk"] + ["v %r %r %r" % p for p in P] + ["vt 0 0", "vn 0 0 1", "g g", "s 1"] +
                ["f " + " ".join(f"{i + 1}/1/1" for i in t) for t in T]) + "\n", 0, "")
write("obj_negative_indices.obj",
      "\n".join(["v %r %r %r" % p for p in P[:4]] + ["f -4 -3 -2", "f -4 -2 -1"]) + "\n", 0, "")
write("obj_forward_reference.obj", "f 1 2 3\nf 1 3 4\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n", 0, "")
write("obj_index_zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 1, "index 0")
write("obj_index_out_of_range.obj", obj(P, T).replace("f 1 2 6", "f 1 2 17", 1), 1, "vertex index 17 is out of range")
write("obj_negative_too_far.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", 1, "reaches before the first vertex")
write("obj_huge_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", 1, "not a vertex reference")
write("obj_bad_reference.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 two 3\n", 1, "not a vertex reference")
write("obj_nan.obj", obj([(0, 0, 0), (1, 0, 0), (0, float("nan"), 0)], [(0, 1, 2)]), 1, "non-finite")
write("obj_vertex_two_numbers.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", 1, "has 2 numbers")
write("obj_face_two_corners.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", 1, "at least 3")
write("obj_garbage_line.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n12 34 56\nf 1 2 3\n", 1, "does not start an OBJ statement")
write("obj_only_comments.obj", "# nothing here\n\n", 1, "no faces")
write("obj_no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", 1, "no faces")
write("obj_quads.obj", obj(quad_pts, quads), 1, "non-triangle faces")
cases.append(("obj_quads.obj", "--triangulate", 0, "triangulated 2 polygons"))
write("obj_isolated_vertices.obj", obj(P + [(7, 7, 7), (8, 8, 8)], T), 0, "dropped 2 isolated vertices")
write("obj_nonmanifold_edge.obj",
      obj([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1)], [(0, 1, 2), (1, 0, 3), (0, 1, 4)]), 1,
      "non-manifold edge")
write("obj_repeated_corner.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n", 1, "twice")
write("obj_long_polygon.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf " + " ".join(["1 2 3"] * 2000) + "\n", 1, "twice")

# --- PLY ---------------------------------------------------------------------------------------
ply_ascii = ply_header("ascii", len(P), len(T)) + "".join("%r %r %r\n" % p for p in P) + \
    "".join("3 %d %d %d\n" % t for t in T)
write("ply_ascii.ply", ply_ascii, 0, "")
write("ply_binary_little_endian.ply", ply_binary(P, T), 0, "")
write("ply_binary_big_endian.ply", ply_binary(P, T, ">", "binary_big_endian"), 0, "")
write("ply_extra_elements.ply",
      (f"ply\nformat ascii 1.0\nelement vertex {len(P)}\nproperty float x\nproperty float y\nproperty float z\n"
       f"property uchar red\nelement material 1\nproperty list uchar float coefficients\n"
       f"element face {len(T)}\nproperty list uchar int vertex_indices\nproperty int flags\nend_header\n") +
      "".join("%r %r %r 7\n" % p for p in P) + "3 0.1 0.2 0.3\n" + "".join("3 %d %d %d 0\n" % t for t in T), 0, "")
write("ply_vertex_count_lies.ply", ply_binary(P, T, header_counts=(100000000, len(T))), 1, "bytes follow")
write("ply_face_count_too_large.ply", ply_binary(P, T, header_counts=(len(P), 2000000000)), 1,
      "more than this reader takes")
write("ply_face_count_lies.ply", ply_binary(P, T, header_counts=(len(P), 100000000)), 1, "bytes follow")
write("ply_list_count_lies.ply", ply_binary(P, T, count_override=255), 1, "runs past the end")
write("ply_index_out_of_range.ply", ply_binary(P, T[:-1] + [(0, 1, 1000)]), 1, "vertex index 1000 is out of range")
write("ply_negative_index.ply", ply_binary(P, T[:-1] + [(0, 1, -7)]), 1, "not a non-negative integer")
write("ply_nan_binary.ply", ply_binary([(0, 0, 0), (1, float("nan"), 0), (0, 1, 0)], [(0, 1, 2)]), 1, "non-finite")
write("ply_ascii_nan.ply", ply_ascii.replace("0.0 0.0 0.0", "0.0 nan 0.0", 1), 1, "non-finite")
write("ply_truncated_binary.ply", ply_binary(P, T)[:-30], 1, "runs past the end of the file")
write("ply_truncated_ascii.ply", ply_ascii[:-40], 1, "truncated")
write("ply_no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", 1, "end_header")
write("ply_no_format.ply", "ply\nelement vertex 0\nend_header\n", 1, "no 'format' line")
write("ply_unknown_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n1\n", 1,
      "unknown PLY type")
write("ply_missing_xyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
      "end_header\n0 0\n", 1, "no x, y and z")
write("ply_float_index.ply", ply_ascii.replace("property list uchar int", "property list uchar float").replace(
    "3 0 1 5\n", "3 0 1.5 5\n"), 1, "not a non-negative integer")
write("ply_float_list_count.ply", ply_ascii.replace("property list uchar int", "property list float int"), 1,
      "floating-point")
write("ply_bad_magic.ply", "plyx\nformat ascii 1.0\nend_header\n", 1, "does not start with 'ply'")
write("ply_huge_face_size.ply", ply_header("ascii", 3, 1, index="int", count="uint") +
      "0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n", 1, "a list of 4000000000 items runs past the end")

# --- STL ---------------------------------------------------------------------------------------
write("stl_ascii.stl", stl_ascii(P, T), 0, "")
write("stl_binary.stl", stl_binary(P, T), 0, "")
write("stl_binary_header_says_solid.stl", stl_binary(P, T, header=b"solid but binary"), 0, "")
write("stl_binary_count_lies.stl", stl_binary(P, T, count=1000000000), 1, "announces 1000000000 triangles")
write("stl_binary_truncated.stl", stl_binary(P, T)[:-25], 1, "truncated")
write("stl_binary_solid_count_lies.stl", stl_binary(P, T, count=7, header=b"solid x"), 1, "neither an ASCII STL")
write("stl_binary_nan.stl", stl_binary([(0, 0, 0), (1, float("nan"), 0), (0, 1, 0)], [(0, 1, 2)]), 1, "non-finite")
write("stl_ascii_nan.stl", stl_ascii([(0, 0, 0), (1, float("inf"), 0), (0, 1, 0)], [(0, 1, 2)]), 1, "non-finite")
write("stl_ascii_four_vertices.stl", stl_ascii(quad_pts, quads), 1, "STL facets are triangles")
write("stl_ascii_truncated.stl", stl_ascii(P, T)[:300], 1, "a vertex line has 1 numbers")
write("stl_ascii_no_endsolid.stl", stl_ascii(P, T).replace("endsolid test\n", ""), 1, "no 'endsolid'")
write("stl_ascii_bad_keyword.stl", stl_ascii(P, T).replace("outer loop", "inner loop", 1), 1, "expected 'outer loop'")
write("stl_too_short.stl", "hello\n", 1, "too short")
write("stl_degenerate_triangle.stl", stl_ascii([(0, 0, 0), (1, 0, 0), (1, 0, 0)], [(0, 1, 2)]), 1, "twice")

# --- names -------------------------------------------------------------------------------------
write("wrong_extension_off_as.obj", off(P, T), 1, "looks like OFF")
write("wrong_extension_ply_as.off", ply_ascii, 1, "looks like PLY")
write("wrong_extension_stl_as.ply", stl_binary(P, T), 1, "does not start with 'ply'")
write("unknown_extension.xyz", off(P, T), 1, "unknown extension")
write("no_extension", off(P, T), 1, "unknown extension")
# --- arguments that refer to the mesh -----------------------------------------------------------
cases.append(("off_isolated_vertex.off", "--cone 16:90", 1, "vertex 16 is in no face"))
cases.append(("off_nonmanifold_vertex.off", "--cone 0:90", 1, "non-manifold and was split"))
cases.append(("off_isolated_vertex_first.off", "--cone 100:90", 1, "the mesh has 17 vertices"))

with open(os.path.join(HERE, "expected.tsv"), "w") as f:
    f.write("# file\targuments (- for none)\texpected exit (0 or 1)\tsubstring of stderr (- for any)\n")
    for name, args, expect, message in cases:
        f.write(f"{name}\t{args or '-'}\t{expect}\t{message or '-'}\n")
print(len(set(c[0] for c in cases)), "files,", len(cases), "cases")
