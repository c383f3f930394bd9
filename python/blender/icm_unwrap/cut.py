"""ICM's cut moved off the diagonals of the n-gons, so that every face keeps one UV per corner.

ICM cuts a closed or higher-genus piece along edges of the triangles it is given, and some of
those are diagonals of quads or n-gons that Blender cannot part: a loop has one UV. When ICM's
seams use a diagonal, each such diagonal is replaced by the shorter way around its face's
border (one without border edges), and ICM runs again on that cut (its `seams`: the ends and
branch points of the cut become the cones, whose angles the optimum chooses).
"""

import numpy as np


def edge_key(a, b):
    """An undirected edge as a sorted pair of rows of V."""
    return (a, b) if a < b else (b, a)


def face_cycles(arrays):
    """The rows of V around each original face, in its loop order."""
    return [[arrays.row_of[loop] for loop in face.loops] for face in arrays.faces]


def original_edges(cycles):
    """The edges of the original faces."""
    edges = set()
    for cycle in cycles:
        for i, row in enumerate(cycle):
            edges.add(edge_key(row, cycle[(i + 1) % len(cycle)]))
    return edges


def triangle_sides(F):
    """{edge: the number of triangles on it}."""
    count = {}
    for tri in F:
        for i in range(3):
            key = edge_key(int(tri[i]), int(tri[(i + 1) % 3]))
            count[key] = count.get(key, 0) + 1
    return count


def diagonal_faces(arrays, cycles, originals):
    """{diagonal: the cycle of the face it cuts}."""
    faces = {}
    index = {face: i for i, face in enumerate(arrays.faces)}
    for t, tri in enumerate(arrays.corner_loops):
        cycle = cycles[index[tri[0].face]]
        for i in range(3):
            key = edge_key(int(arrays.F[t, i]), int(arrays.F[t, (i + 1) % 3]))
            if key not in originals:
                faces[key] = cycle
    return faces


def way_around(cycle, a, b, sides):
    """The edges of the shorter way from a to b along the cycle that uses no border edge, or None."""
    i, j = cycle.index(a), cycle.index(b)
    n = len(cycle)
    ways = []
    for start, end in ((i, j), (j, i)):
        rows = [cycle[(start + k) % n] for k in range((end - start) % n + 1)]
        edges = [edge_key(rows[k], rows[k + 1]) for k in range(len(rows) - 1)]
        if all(sides.get(e, 0) == 2 for e in edges):
            ways.append(edges)
    return min(ways, key=len) if ways else None


def off_diagonals(arrays, seams):
    """ICM's seams (s, 2) with every diagonal taken around its face, or None if none is a diagonal.

    Also None when a diagonal has no way around (its face on the border on both sides).
    """
    cycles = face_cycles(arrays)
    originals = original_edges(cycles)
    keys = [edge_key(int(a), int(b)) for a, b in np.asarray(seams).reshape(-1, 2)]
    if all(key in originals for key in keys):
        return None
    sides = triangle_sides(arrays.F)
    diagonals = diagonal_faces(arrays, cycles, originals)
    cut = set()
    for key in keys:
        if key in originals:
            cut.add(key)
            continue
        way = way_around(diagonals[key], key[0], key[1], sides) if key in diagonals else None
        if way is None:
            return None
        cut.update(way)
    return np.array(sorted(cut), dtype=np.int64).reshape(-1, 2)


def angle_sums(rows, F, uv, fuv):
    """The UV angle around every row of V, summed over its triangles (radians)."""
    sums = np.zeros(rows)
    for c in range(3):
        p, q, r = uv[fuv[:, c]], uv[fuv[:, (c + 1) % 3]], uv[fuv[:, (c + 2) % 3]]
        u, v = q - p, r - p
        angle = np.arctan2(np.abs(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]), np.sum(u * v, axis=1))
        np.add.at(sums, F[:, c], angle)
    return sums


def border_rows(F):
    """The rows of V on a border edge."""
    return {row for edge, count in triangle_sides(F).items() if count == 1 for row in edge}


def cones_of(arrays, result):
    """The cones of ICM's run as (row, degrees): the interior rows whose UV angle is not 2 pi."""
    border = border_rows(arrays.F)
    sums = angle_sums(len(arrays.V), arrays.F, np.asarray(result.uv), np.asarray(result.fuv))
    return [
        (row, float(np.degrees(sums[row])))
        for row in range(len(arrays.V))
        if row not in border and abs(sums[row] - 2.0 * np.pi) > 1e-6
    ]


def cones_for_moved_cut(arrays, result, seams):
    """The `cone` argument of the run on the moved cut: the first run's cones with their angles,
    and every other end or branch point of the moved cut flat (360 degrees).

    ICM makes the ends and branch points of given seams cones whose angles its optimum chooses;
    those the move made would otherwise get small cones that the first run did not have.
    """
    cones = cones_of(arrays, result)
    taken = {row for row, _ in cones}
    degree = {}
    for a, b in np.asarray(seams).reshape(-1, 2):
        for row in (int(a), int(b)):
            degree[row] = degree.get(row, 0) + 1
    border = border_rows(arrays.F)
    flat = [(row, 360.0) for row, d in sorted(degree.items()) if d != 2 and row not in taken and row not in border]
    return cones + flat
