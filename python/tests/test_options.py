"""icm.parameterize's seams, metric, boundary and keep_overlaps against icm_param's --seams,
--metric, --boundary and --keep-overlaps, and each of their refusals, by its reason."""

import numpy as np
import pytest

import icm
from conftest import DATA, assert_same_as_icm_param, obj_uvs, run_icm_param

SPHERE = DATA / "sphere966.off"  # closed, genus 0
SELECTION = DATA / "sphere966.selection.txt"  # its cut: edges on the third line
DISK = DATA / "nefertiti.off"  # one border loop, genus 0
HOLES = DATA / "pig.off"  # genus 0, 7 border loops
BORDER_KEYS = ("boundary", "boundary_loops", "degenerate_faces", "border_iterations", "metric")


def _selection_edges(path):
    """The edges of a CGAL selection file: the vertex indices of its third and later lines, in pairs."""
    values = [int(v) for line in open(path).read().splitlines()[2:] for v in line.split()]
    return np.array(values, dtype=np.int64).reshape(-1, 2)


def _read(path):
    V, F, _ = icm.read_mesh(str(path))
    return V, F


def _edge_set(pairs):
    return {tuple(sorted(map(int, pair))) for pair in pairs}


def _areas(V, F, uv, fuv):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    area_3d = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    p, q, r = uv[fuv[:, 0]], uv[fuv[:, 1]], uv[fuv[:, 2]]
    area_uv = 0.5 * ((q[:, 0] - p[:, 0]) * (r[:, 1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (r[:, 0] - p[:, 0]))
    return area_3d, area_uv


# --- seams ----------------------------------------------------------------------------------


def test_seams_same_as_icm_param(tmp_path):
    """The selection file's edges as an array give icm_param --seams FILE's figures and map: the
    cut along exactly those edges, cones at their ends and branch points, no other cone."""
    run, expected, obj = run_icm_param(SPHERE, tmp_path, "--seams", str(SELECTION))
    assert run.returncode == 0, run.stderr
    V, F = _read(SPHERE)
    edges = _selection_edges(SELECTION)
    result = icm.parameterize(V, F, seams=edges)
    assert_same_as_icm_param(result, expected, obj, keys=("cones_above_full_turn",))
    assert np.allclose(result.uv, obj_uvs(obj), rtol=0, atol=1e-6 * np.abs(result.uv).max())
    # The cut is the user's (one chart: the overlap removal cut nothing more), and the cones are
    # its ends and branch points: its vertices on other than two of its edges.
    assert result.charts == 1 and _edge_set(result.seams) == _edge_set(edges)
    _, degrees = np.unique(np.array(sorted(_edge_set(edges))).ravel(), return_counts=True)
    assert result.report["cones"] == np.count_nonzero(degrees != 2)


def _two_spheres(tmp_path):
    """sphere966 and a copy beside it, as arrays and as an OFF file for icm_param."""
    V, F = _read(SPHERE)
    V2, F2 = np.vstack([V, V + [5.0, 0, 0]]), np.vstack([F, F + len(V)])
    path = tmp_path / "two_spheres.off"
    with open(path, "w") as off:
        off.write(f"OFF\n{len(V2)} {len(F2)} 0\n")
        off.writelines("%.17g %.17g %.17g\n" % tuple(p) for p in V2)
        off.writelines("3 %d %d %d\n" % tuple(f) for f in F2)
    return V2, F2, path


def test_seams_and_a_cone_count_same_as_icm_param(tmp_path):
    """Seams on one sphere of two: the other gets automatic cones only when cones is a count,
    as with icm_param --seams FILE --cones N; else it has none, and fails as icm_param does."""
    V, F, path = _two_spheres(tmp_path)
    edges = _selection_edges(SELECTION)
    run, expected, obj = run_icm_param(path, tmp_path, "--seams", str(SELECTION), "--cones", "4")
    assert run.returncode == 0, run.stderr
    result = icm.parameterize(V, F, seams=edges, cones=4)
    assert_same_as_icm_param(result, expected, obj)
    cut_alone = icm.parameterize(V[: len(V) // 2], F[: len(F) // 2], seams=edges)
    assert result.report["cones"] == cut_alone.report["cones"] + 4
    run, expected, _ = run_icm_param(path, tmp_path, "--seams", str(SELECTION))
    assert run.returncode == 1
    with pytest.raises(icm.Error, match="automatic cones are off") as failure:
        icm.parameterize(V, F, seams=edges)
    assert str(failure.value) == expected["error"]


def test_seams_in_any_order_and_repeated():
    """A pair reversed or given twice names the same edge once, as in a selection file."""
    V, F = _read(SPHERE)
    edges = _selection_edges(SELECTION)
    once = icm.parameterize(V, F, seams=edges)
    twice = icm.parameterize(V, F, seams=np.vstack([edges[:, ::-1], edges[:5]]).astype(np.int32))
    assert twice.report["seam_edges"] == once.report["seam_edges"] == len(_edge_set(edges))
    assert twice.report["log_area_distortion"] == pytest.approx(once.report["log_area_distortion"], rel=1e-12)


def test_seams_on_the_rows_of_V(sphere):
    """With a row of V in no face (dropped by the repair), seams still name rows of V."""
    V, F = sphere
    edges = _selection_edges(SELECTION)
    reference = icm.parameterize(V, F, seams=edges)
    shifted = icm.parameterize(np.vstack([[[9.0, 9.0, 9.0]], V]), F + 1, seams=edges + 1)
    assert shifted.report["isolated_vertices_dropped"] == 1
    assert _edge_set(shifted.seams) == _edge_set(edges + 1)
    assert shifted.report["log_area_distortion"] == pytest.approx(reference.report["log_area_distortion"], rel=1e-9)
    with pytest.raises(icm.Error, match=r"seams row 0 \(0, 1\): vertex 0 is in no face"):
        icm.parameterize(np.vstack([[[9.0, 9.0, 9.0]], V]), F + 1, seams=[[0, 1]])


def _a_non_edge(F):
    """Two rows of V that no face joins."""
    joined = _edge_set(np.vstack([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]))
    return next((0, v) for v in range(1, F.max() + 1) if (0, v) not in joined)


@pytest.mark.parametrize(
    "seams, reason",
    [
        (np.array([[0, 1, 2]]), r"seams must have shape \(s, 2\), not \(1, 3\)"),
        (np.array([0, 1]), r"seams must have shape \(s, 2\), not \(2,\)"),
        (np.array([[0.0, 1.0]]), "seams must hold integers"),
        ("edges", "seams must be an array of integers|seams must hold integers"),
        (np.zeros((0, 2), dtype=np.int64), "seams is empty"),
        (np.array([[164, 166], [0, 926]]), r"seams row 1 has index 926 out of range: V has 926 rows"),
        (np.array([[164, 166], [-1, 3]]), r"seams row 1 has index -1 out of range"),
        (np.array([[164, 166], [3, 3]]), r"seams row 1 \(3, 3\): a vertex paired with itself is not an edge"),
        ("non-edge", r"seams row 0 \(0, \d+\): vertices 0 and \d+ are not joined by an edge of the mesh"),
    ],
)
def test_seams_refused(sphere, seams, reason):
    V, F = sphere
    if isinstance(seams, str) and seams == "non-edge":
        seams = np.array([_a_non_edge(F)])
    with pytest.raises(icm.Error, match=reason):
        icm.parameterize(V, F, seams=seams)


def test_seams_on_the_border_refused():
    V, F = _read(DISK)
    # A border edge: one face only has it.
    edges, counts = np.unique(np.sort(np.vstack([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1), axis=0,
                              return_counts=True)
    border = edges[counts == 1][0]
    with pytest.raises(icm.Error, match=r"seams row 0 \(\d+, \d+\): a border edge"):
        icm.parameterize(V, F, seams=[border])


def test_seams_that_do_not_cut_a_disk_fail(sphere):
    """One seam edge on a closed sphere leaves no disk: the library's refusal, with its code."""
    V, F = sphere
    with pytest.raises(icm.Error) as failure:
        icm.parameterize(V, F, seams=_selection_edges(SELECTION)[:1])
    assert failure.value.code not in (None, 0)


# --- metric ---------------------------------------------------------------------------------


@pytest.mark.parametrize("metric", icm.METRICS)
def test_metric_same_as_icm_param(metric, tmp_path):
    """Every metric gives icm_param --metric's figures, with the metric in the report as in its
    JSON (the circle packing's when the metric fell back to it, and why)."""
    run, expected, obj = run_icm_param(SPHERE, tmp_path, "--metric", metric)
    assert run.returncode == 0, run.stderr
    V, F = _read(SPHERE)
    result = icm.parameterize(V, F, metric=metric)
    assert_same_as_icm_param(result, expected, obj, keys=("metric", "metric_fallback"))
    assert metric in result.report["metric"] or result.report["metric_fallback"]


@pytest.mark.parametrize("metric, energy", [("circle-packing", "u-square"), ("vertex-scaling", "log-area")])
def test_metric_with_an_energy_same_as_icm_param(metric, energy, tmp_path):
    """A metric other than the default goes with every energy, as in icm_param."""
    run, expected, obj = run_icm_param(DISK, tmp_path, "--metric", metric, "--energy", energy)
    assert run.returncode == 0, run.stderr
    V, F = _read(DISK)
    result = icm.parameterize(V, F, metric=metric, energy=energy)
    assert_same_as_icm_param(result, expected, obj, keys=("metric", "energy", "energy_iterations"))
    assert result.report["final_energy"] == pytest.approx(expected["final_energy"], rel=1e-9)


# --- boundary -------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "boundary, mesh, metric",
    [
        ("circle", DISK, "intrinsic-delaunay"),
        ("square", DATA / "mesh_with_border.off", "intrinsic-delaunay"),
        ("circle-domain", HOLES, "intrinsic-delaunay"),
        ("circle", DISK, "circle-packing"),
        ("square", DISK, "inversive-distance"),
    ],
)
def test_boundary_same_as_icm_param(boundary, mesh, metric, tmp_path):
    """Every prescribed border gives icm_param --boundary's map (its OBJ's UVs) and figures;
    the chart at its 3D area, as icm_param writes it."""
    run, expected, obj = run_icm_param(mesh, tmp_path, "--boundary", boundary, "--metric", metric)
    assert run.returncode == 0, run.stderr
    V, F = _read(mesh)
    result = icm.parameterize(V, F, boundary=boundary, metric=metric)
    assert_same_as_icm_param(result, expected, obj, keys=BORDER_KEYS)
    got = result.report
    assert got["boundary"] == boundary and got["charts"] == 1 and len(result.seams) == 0
    assert got["circle_deviation"] == pytest.approx(expected["circle_deviation"], rel=1e-6, abs=1e-12)
    assert np.allclose(result.uv, obj_uvs(obj), rtol=0, atol=1e-6 * np.abs(result.uv).max())
    area_3d, area_uv = _areas(V, F, result.uv, result.fuv)
    assert area_uv.sum() == pytest.approx(area_3d.sum(), rel=1e-6)
    if boundary == "square":
        assert "degenerate_faces" in got and got["border_iterations"] == 0
    else:
        assert got["border_iterations"] > 0 and got["circle_deviation"] < 1e-6


def test_boundary_takes_cones_0(tmp_path):
    """cones=0 asks for no cone, so it goes with a prescribed border (as --cones 0 does)."""
    V, F = _read(DISK)
    result = icm.parameterize(V, F, boundary="circle", cones=0)
    assert result.report["cones"] == 0 and result.report["boundary"] == "circle"


@pytest.mark.parametrize(
    "kwargs, reason",
    [
        (dict(energy="area"), r"energy='area' cannot go with boundary='circle': a prescribed border leaves one"),
        (dict(cone=[(10, 90.0)]), r"cone cannot go with boundary='circle': .* without cones or seams"),
        (dict(seams=[[0, 1]]), r"seams cannot go with boundary='circle': .* without cones or seams"),
        (dict(cones=3), r"cones cannot go with boundary='circle': .* without cones or seams"),
        (dict(atlas=256), r"atlas cannot go with boundary='circle': .* packs no charts"),
    ],
)
def test_boundary_conflicts_refused(kwargs, reason):
    """What icm_param refuses with --boundary (exit 2), before the mesh is read."""
    V, F = _read(DISK)
    with pytest.raises(icm.Error, match=reason) as failure:
        icm.parameterize(V, F, boundary="circle", **kwargs)
    assert failure.value.code is None


@pytest.mark.parametrize(
    "mesh, boundary, reason",
    [
        (SPHERE, "circle", r"boundary='circle' needs a disk .*, and it is closed, genus 0"),
        (HOLES, "square", r"boundary='square' needs a disk .*, and it has genus 0 and 7 boundary loops"),
        (DATA / "rotor.off", "circle-domain", r"boundary='circle-domain' needs one component of genus 0 .*genus 1"),
        ("two disks", "circle", r"boundary='circle' needs a disk .*, and it has 2 connected components"),
    ],
)
def test_boundary_on_the_wrong_surface_refused(mesh, boundary, reason, tmp_path):
    """The surfaces icm_param refuses with --boundary (exit 1), for its reason."""
    if mesh == "two disks":
        V, F = _read(DISK)
        V, F = np.vstack([V, V + [10.0, 0, 0]]), np.vstack([F, F + len(V)])
    else:
        V, F = _read(mesh)
    with pytest.raises(icm.Error, match=reason) as failure:
        icm.parameterize(V, F, boundary=boundary)
    assert failure.value.code is not None
    if mesh != "two disks":
        run, _, _ = run_icm_param(mesh, tmp_path, "--boundary", boundary)
        assert run.returncode == 1
        assert run.stderr.split(" needs ", 1)[1].strip() in str(failure.value)


# --- names and keep_overlaps ------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs, reason",
    [
        (dict(metric="euclidean"), "metric 'euclidean' is not one of intrinsic-delaunay, vertex-scaling, "),
        (dict(boundary="disk"), "boundary 'disk' is not one of free, circle, square, circle-domain"),
    ],
)
def test_unknown_names_refused(kwargs, reason):
    V, F = _read(DISK)
    with pytest.raises(icm.Error, match=reason):
        icm.parameterize(V, F, **kwargs)


def test_names_are_icm_params():
    assert icm.METRICS == ["intrinsic-delaunay", "vertex-scaling", "inversive-distance", "circle-packing"]
    assert icm.BOUNDARIES == ["free", "circle", "square", "circle-domain"]


def test_keep_overlaps_same_as_icm_param(tmp_path):
    """pig's map with exactly 8 cones folds over itself: cut into 3 charts by default, kept
    whole with keep_overlaps=True, as icm_param --keep-overlaps keeps it. (With the automatic
    count it gives 4 of its 8 cones up instead and stays one chart.)"""
    V, F = _read(HOLES)
    assert icm.parameterize(V, F).report["cones_given_up"] > 0
    cut = icm.parameterize(V, F, cones=8)
    assert cut.charts > 1 and cut.report["raw_overlapping_border_edges"] > 0
    run, expected, obj = run_icm_param(HOLES, tmp_path, "--cones", "8", "--keep-overlaps")
    assert run.returncode == 0, run.stderr
    kept = icm.parameterize(V, F, cones=8, keep_overlaps=True)
    assert_same_as_icm_param(kept, expected, obj, keys=("overlapping_border_edges",))
    assert kept.charts == 1 and kept.report["overlapping_border_edges"] > 0
