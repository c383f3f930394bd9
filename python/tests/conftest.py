"""Shared fixtures and helpers: the bundled meshes, the shared meshes and icm_param, from the
environment ctest sets (python/CMakeLists.txt), else from the source tree and build/."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = pathlib.Path(os.environ.get("ICM_DATA", ROOT / "examples" / "data"))
ICM_PARAM = os.environ.get("ICM_PARAM", str(ROOT / "build" / "examples" / "icm_param"))
MESHES = sorted(DATA.glob("*.off"))
# The shared test meshes (up to ~100k faces), beside the repository unless ICM_SHARED_DATA says.
SHARED_DATA = pathlib.Path(os.environ.get("ICM_SHARED_DATA", ROOT.parent / "shared" / "data" / "meshes"))
SHARED_MESHES = sorted(m for m in SHARED_DATA.glob("*") if m.suffix in (".off", ".obj", ".ply", ".stl"))

# The figures icm.parameterize must give as icm_param's --json line gives them: the counts
# exactly, the measures to the last digits (both run the same code on the same mesh).
SAME_COUNTS = ("vertices", "faces", "charts", "components", "cones", "seam_edges", "flipped_faces", "genus")
SAME_MEASURES = ("log_area_distortion", "log_area_distortion_area_weighted", "qc_mean", "seam_length")


def pytest_configure(config):
    config.addinivalue_line(
        "markers",
        "shared_meshes: icm.parameterize against icm_param on every mesh of the shared data folder "
        "(ICM_SHARED_DATA); the largest take seconds each, deselect with -m 'not shared_meshes'",
    )


@pytest.fixture
def sphere():
    """sphere966.off: a closed genus-0 mesh."""
    import icm

    V, F, repairs = icm.read_mesh(str(DATA / "sphere966.off"))
    return V, F


def run_icm_param(mesh, tmp_path, *options):
    """icm_param on `mesh` with `options` into tmp_path/out.obj: (the finished process, the
    parsed --json line, the OBJ's path)."""
    obj = tmp_path / "out.obj"
    run = subprocess.run(
        [ICM_PARAM, str(mesh), "-o", str(obj), "--json", "--quiet", *options],
        capture_output=True,
        text=True,
        timeout=900,
    )
    lines = run.stdout.splitlines()
    return run, json.loads(lines[0]) if lines else {}, obj


def obj_uvs(obj):
    """The vt rows of an OBJ, in order: icm_param writes one per row of the module's uv."""
    import numpy as np

    return np.array([[float(x) for x in line.split()[1:3]] for line in open(obj) if line.startswith("vt ")])


def assert_same_as_icm_param(result, expected, obj, keys=()):
    """`result` (icm.parameterize's) has the figures of icm_param's --json line `expected`, one
    uv row per vt of its OBJ and its seams; `keys` are further keys to compare exactly."""
    got = result.report
    for key in SAME_COUNTS + tuple(keys):
        assert got[key] == expected[key], key
    assert result.charts == expected["charts"]
    for key in SAME_MEASURES:
        assert got[key] == pytest.approx(expected[key], rel=1e-9, abs=1e-300), key
    assert obj_uvs(obj).shape == result.uv.shape
    assert result.seams.shape == (expected["seam_edges"], 2)
