"""The arrays `icm.parameterize` takes, made of the selected faces of a bmesh.

Every n-gon is cut into triangles by Blender's own polyfill (`BMesh.calc_loop_triangles`), and
each triangle corner keeps the loop of the original face it came from, so that the UVs go back
per loop. The edges marked as seams are the user's cut: the mesh is opened along them before it
is handed to ICM (a vertex gets one row of V per fan of faces between its seams), so that each
piece the seams cut off becomes a component of its own and both sides of a seam get UVs of
their own. Nothing here changes the bmesh.
"""

import numpy as np


class SelectionError(ValueError):
    """A selection ICM cannot unwrap; the message is the reason, for the user."""


class Arrays:
    """V (n, 3), F (m, 3), the loop of every corner of F (`corner_loops[t][c]`), the faces,
    and the row of V of every loop of the faces (`row_of`)."""

    def __init__(self, V, F, corner_loops, faces, row_of):
        self.V = V
        self.F = F
        self.corner_loops = corner_loops
        self.faces = faces
        self.row_of = row_of


def selected_faces(bm, selected_only):
    """The faces to unwrap: the selected ones (edit mode) or all (object mode)."""
    faces = [f for f in bm.faces if f.select or not selected_only]
    if not faces:
        raise SelectionError("no face selected")
    return faces


def check_manifold(faces):
    """Refuses an edge with more than two of the faces (a non-manifold selection)."""
    chosen = set(faces)
    for face in faces:
        for edge in face.edges:
            count = sum(1 for f in edge.link_faces if f in chosen)
            if count > 2:
                raise SelectionError(
                    f"non-manifold selection: edge {edge.index} has {count} faces (at most 2)"
                )


def cut_edges_open(faces):
    """{loop: row of V}: the loops around a vertex share a row unless a seam or a border parts them.

    Union-find over the loops: across every edge with exactly two of the faces and no seam,
    the loops of the two faces at each end of the edge are joined.
    """
    chosen = set(faces)
    loops = [loop for face in faces for loop in face.loops]
    parent = {loop: loop for loop in loops}

    def find(loop):
        while parent[loop] != loop:
            parent[loop] = parent[parent[loop]]
            loop = parent[loop]
        return loop

    for face in faces:
        for loop in face.loops:
            edge = loop.edge
            if edge.seam:
                continue
            others = [f for f in edge.link_faces if f in chosen and f != face]
            if len(others) != 1:
                continue
            for here in (loop, loop.link_loop_next):
                there = next(l for l in others[0].loops if l.vert == here.vert)
                a, b = find(here), find(there)
                if a != b:
                    parent[a] = b
    rows = {}
    row_of = {}
    for loop in loops:
        root = find(loop)
        row_of[loop] = rows.setdefault(root, len(rows))
    return row_of


def triangles(bm, faces):
    """The triangles (three loops each) of the faces, in face order."""
    chosen = set(faces)
    return [tri for tri in bm.calc_loop_triangles() if tri[0].face in chosen]


def check_degenerate(V, F, faces_of_triangles):
    """Refuses a triangle of (nearly) zero area, naming its face."""
    if len(V) == 0:
        raise SelectionError("no vertex selected")
    extent = float(np.max(np.ptp(V, axis=0)))
    if not np.isfinite(extent) or extent <= 0.0:
        raise SelectionError("degenerate selection: all vertices at one point")
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    doubled = np.linalg.norm(np.cross(b - a, c - a), axis=1)
    bad = np.flatnonzero(~(doubled > 1e-12 * extent * extent))
    if len(bad):
        face = faces_of_triangles[int(bad[0])]
        raise SelectionError(
            f"degenerate selection: face {face.index} has zero area ({len(bad)} triangles)"
        )


def build(bm, selected_only):
    """The Arrays of the faces to unwrap, or SelectionError with the reason."""
    bm.faces.index_update()
    bm.edges.index_update()
    faces = selected_faces(bm, selected_only)
    check_manifold(faces)
    row_of = cut_edges_open(faces)
    tris = triangles(bm, faces)
    V = np.zeros((len(set(row_of.values())), 3))
    for loop, row in row_of.items():
        V[row] = loop.vert.co
    F = np.array([[row_of[l] for l in tri] for tri in tris], dtype=np.int64).reshape(-1, 3)
    check_degenerate(V, F, [tri[0].face for tri in tris])
    return Arrays(V, F, tris, faces, row_of)

