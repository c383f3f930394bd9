"""The Python module icm: against icm_param on the bundled meshes, the UVs' shapes and areas,
the files, the refusals of bad arrays, the atlas."""

import math

import numpy as np
import pytest

import icm
from conftest import DATA, MESHES, assert_same_as_icm_param, run_icm_param


def _triangle_areas_3d(V, F):
    a, b, c = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)


def _triangle_areas_uv(uv, fuv):
    a, b, c = uv[fuv[:, 0]], uv[fuv[:, 1]], uv[fuv[:, 2]]
    return 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


@pytest.mark.parametrize("mesh", MESHES, ids=[m.name for m in MESHES])
def test_same_as_icm_param(mesh, tmp_path):
    """icm.parameterize on the mesh icm.read_mesh read gives icm_param's figures."""
    run, expected, obj = run_icm_param(mesh, tmp_path)
    if run.returncode != 0:
        pytest.skip("icm_param refuses " + mesh.name + ": " + run.stderr.strip())
    V, F, _ = icm.read_mesh(str(mesh))
    assert_same_as_icm_param(icm.parameterize(V, F), expected, obj)


def test_shapes_and_chart_areas(sphere):
    """On a closed mesh: one uv row per corner index, F x 3 fuv, and each chart's UV area is its
    3D area (charts at their 3D scale)."""
    V, F = sphere
    result = icm.parameterize(V, F)
    uv, fuv = result.uv, result.fuv
    assert uv.dtype == np.float64 and uv.ndim == 2 and uv.shape[1] == 2
    assert fuv.shape == F.shape and np.issubdtype(fuv.dtype, np.integer)
    assert fuv.min() == 0 and fuv.max() == uv.shape[0] - 1
    assert result.report["boundary_loops"] == 0 and result.report["cones"] >= 2
    assert result.seams.shape[1] == 2 and result.seams.shape[0] > 0
    # Charts: faces joined by shared UV indices.
    parent = list(range(len(F)))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    first_face_of_uv = {}
    for f, row in enumerate(fuv):
        for t in row:
            g = first_face_of_uv.setdefault(int(t), f)
            parent[find(f)] = find(g)
    charts = {}
    for f in range(len(F)):
        charts.setdefault(find(f), []).append(f)
    assert len(charts) == result.charts
    area_3d = _triangle_areas_3d(V, F)
    area_uv = _triangle_areas_uv(uv, fuv)
    assert (area_uv > 0).all()
    for faces in charts.values():
        assert area_uv[faces].sum() == pytest.approx(area_3d[faces].sum(), rel=1e-6)
    # measure_distortion reads the same figures as the report.
    measures = icm.measure_distortion(V, F, uv, fuv)
    assert measures["flipped_faces"] == 0
    assert measures["log_area_distortion"] == pytest.approx(result.report["log_area_distortion"], rel=1e-12)


def test_energy_u_square(sphere):
    V, F = sphere
    result = icm.parameterize(V, F, energy="u-square", cones=8)
    assert result.report["energy"] == "u-square"
    assert result.report["cones"] == 8
    assert result.report["flipped_faces"] == 0


def test_user_cones():
    V, F, _ = icm.read_mesh(str(DATA / "sphere966.off"))
    result = icm.parameterize(V, F, cones=0, cone=[(0, 180.0), (100, 180.0), (300, 180.0), (500, 180.0)])
    assert result.report["cones"] == 4
    # Two half turns: the curvatures do not sum to 4 pi.
    with pytest.raises(icm.Error, match="Gauss-Bonnet") as failure:
        icm.parameterize(V, F, cones=0, cone=[(0, 180.0), (500, 180.0)])
    assert failure.value.code is not None and failure.value.code != 0


def test_write_and_read_back(sphere, tmp_path):
    """write_mesh writes an OBJ with one vt per uv row, read_mesh reads the mesh back."""
    V, F = sphere
    result = icm.parameterize(V, F)
    path = tmp_path / "sphere.obj"
    icm.write_mesh(str(path), V, F, result.uv, result.fuv)
    vts = sum(1 for line in open(path) if line.startswith("vt "))
    assert vts == result.uv.shape[0]
    V2, F2, repairs = icm.read_mesh(str(path))
    assert repairs == []
    assert V2.shape == V.shape and F2.shape == F.shape
    assert np.allclose(V2, V, rtol=1e-12, atol=0)
    assert (F2 == F).all()
    icm.write_mesh(str(tmp_path / "sphere.ply"), V, F, result.uv, result.fuv, binary_ply=True)
    if icm.HAS_GLTF:
        icm.write_mesh(str(tmp_path / "sphere.glb"), V, F, result.uv, result.fuv)
        assert (tmp_path / "sphere.glb").stat().st_size > 0
    with pytest.raises(icm.Error, match="off"):
        icm.write_mesh(str(tmp_path / "sphere.off"), V, F, result.uv, result.fuv)


def test_read_refusals(tmp_path):
    with pytest.raises(icm.Error, match="nothing_here.off"):
        icm.read_mesh(str(tmp_path / "nothing_here.off"))
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n")
    with pytest.raises(icm.Error):
        icm.read_mesh(str(bad))


def _triangle():
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    F = np.array([[0, 1, 2]])
    return V, F


@pytest.mark.parametrize(
    "V, F, reason",
    [
        (np.zeros((3, 2)), np.array([[0, 1, 2]]), r"V must have shape \(n, 3\)"),
        (np.zeros(9), np.array([[0, 1, 2]]), r"V must have shape \(n, 3\)"),
        (np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64), "V is empty"),
        (np.array([["a", "b", "c"]] * 3), np.array([[0, 1, 2]]), "V must hold real numbers"),
        ("not an array", np.array([[0, 1, 2]]), "V must"),
        (np.array([[0.0, 0, 0], [1, 0, 0], [np.nan, 1, 0]]), np.array([[0, 1, 2]]), "non-finite.*row 2"),
        (np.array([[0.0, 0, 0], [1, 0, 0], [np.inf, 1, 0]]), np.array([[0, 1, 2]]), "non-finite"),
        (_triangle()[0], np.array([[0, 1, 3]]), "index 3 out of range"),
        (_triangle()[0], np.array([[0, -1, 2]]), "index -1 out of range"),
        (_triangle()[0], np.array([[0.0, 1, 2]]), "F must hold integers"),
        (_triangle()[0], np.array([[0, 1]]), r"F must have shape \(m, 3\)"),
        (_triangle()[0], np.zeros((0, 3), dtype=np.int32), "F is empty"),
        (np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]), np.array([[0, 1, 2]]), "degenerate|zero area"),
        (np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]), np.array([[0, 1, 2]] * 2), "twice|listed|duplicate"),
    ],
)
def test_bad_arrays(V, F, reason):
    """Every bad array is refused with icm.Error naming the reason, by every function."""
    with pytest.raises(icm.Error, match=reason):
        icm.parameterize(V, F)
    if "degenerate" in reason or "twice" in reason:
        return  # the mesh checks are parameterize()'s; the others read arrays only
    uv = np.zeros((3, 2))
    fuv = np.array([[0, 1, 2]])
    with pytest.raises(icm.Error, match=reason):
        icm.measure_distortion(V, F, uv, fuv)


def test_bad_options_and_uvs(tmp_path):
    V, F = _triangle()
    for kwargs, reason in [
        (dict(energy="nope"), "energy 'nope' is not one of"),
        (dict(cones="many"), "cones takes 'auto'"),
        (dict(cones=-1), "cones takes 'auto'"),
        (dict(cone=[(7, 90.0)]), r"cone \(7.*V has 3 rows"),
        (dict(cone=[(0, -5.0)]), "angle must be"),
        (dict(atlas=0), "atlas.size"),
        (dict(atlas=64, padding=40), "atlas.padding"),
    ]:
        with pytest.raises(icm.Error, match=reason):
            icm.parameterize(V, F, **kwargs)
    error = None
    try:
        icm.parameterize(V, F, atlas=0)
    except icm.Error as e:
        error = e
    assert isinstance(error, ValueError) and error.code is not None
    uv = np.array([[0.0, 0], [1, 0], [0, np.nan]])
    with pytest.raises(icm.Error, match="uv has a non-finite"):
        icm.measure_distortion(V, F, uv, np.array([[0, 1, 2]]))
    with pytest.raises(icm.Error, match="fuv row 0 has index 5"):
        icm.write_mesh(str(tmp_path / "t.obj"), V, F, np.zeros((3, 2)), np.array([[0, 1, 5]]))
    with pytest.raises(icm.Error, match="fuv has 2 rows and F 1"):
        icm.write_mesh(str(tmp_path / "t.obj"), V, F, np.zeros((3, 2)), np.array([[0, 1, 2]] * 2))
    assert not (tmp_path / "t.obj").exists()


def test_failure_has_code():
    """A run that fails reports ICM's error code."""
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])  # a closed tetrahedron
    with pytest.raises(icm.Error) as failure:
        icm.parameterize(V, F, cones=0)
    assert failure.value.code is not None and failure.value.code != 0
    assert "cone" in str(failure.value)


def test_atlas_in_unit_square(sphere):
    V, F = sphere
    result = icm.parameterize(V, F, atlas=256, padding=2)
    assert result.uv.min() >= 0.0 and result.uv.max() <= 1.0
    assert result.report["atlas_size"] == 256 and result.report["atlas_padding"] == 2
    assert 0 < result.report["atlas_utilization"] <= 1


def test_int32_and_float32_inputs(sphere):
    V, F = sphere
    result = icm.parameterize(V.astype(np.float32).astype(np.float64), F.astype(np.int32))
    assert result.fuv.shape == F.shape
    assert math.isfinite(result.report["log_area_distortion"])


@pytest.mark.parametrize("energy", icm.ENERGIES)
def test_energies_same_as_icm_param(energy, tmp_path):
    """Every energy the module offers gives icm_param --energy's figures (nefertiti, a disk)."""
    mesh = DATA / "nefertiti.off"
    run, expected, _ = run_icm_param(mesh, tmp_path, "--energy", energy)
    assert run.returncode == 0, run.stderr
    V, F, _ = icm.read_mesh(str(mesh))
    got = icm.parameterize(V, F, energy=energy).report
    assert got["energy"] == expected["energy"] == energy
    assert got["charts"] == expected["charts"] and got["flipped_faces"] == expected["flipped_faces"]
    assert got["log_area_distortion"] == pytest.approx(expected["log_area_distortion"], rel=1e-9)
    if energy != "entropy":
        assert got["energy_iterations"] == expected["energy_iterations"]
        assert got["final_energy"] == pytest.approx(expected["final_energy"], rel=1e-9)


def test_repairs_keep_the_rows_of_V_and_F(sphere):
    """A vertex in no face is dropped and a face against its neighbours reoriented, as a file's
    would be; uv, fuv and seams still index V and F as given."""
    V, F = sphere
    V2 = np.vstack([[[5.0, 5.0, 5.0]], V])  # row 0 in no face
    F2 = F + 1
    F2[7] = F2[7, ::-1]  # one face reversed
    result = icm.parameterize(V2, F2)
    assert result.report["isolated_vertices_dropped"] == 1 and result.report["faces_reoriented"] == 1
    assert len(result.report["repairs"]) == 2
    assert result.fuv.shape == F2.shape
    assert result.seams.min() >= 1 and result.seams.max() < len(V2)
    area_uv = _triangle_areas_uv(result.uv, result.fuv)
    # fuv follows F2's corners: the reversed face is the one face with a negative UV area.
    assert (area_uv < 0).nonzero()[0].tolist() == [7]
    reference = icm.parameterize(V, F)
    assert result.report["log_area_distortion"] == pytest.approx(reference.report["log_area_distortion"], rel=1e-9)
    with pytest.raises(icm.Error, match="vertex 0 is in no face"):
        icm.parameterize(V2, F2, cone=[(0, 90.0)])
