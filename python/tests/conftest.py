"""Shared fixtures: the bundled meshes and icm_param, from the environment ctest sets
(python/CMakeLists.txt), else from the source tree and build/."""

import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = pathlib.Path(os.environ.get("ICM_DATA", ROOT / "examples" / "data"))
ICM_PARAM = os.environ.get("ICM_PARAM", str(ROOT / "build" / "examples" / "icm_param"))
MESHES = sorted(DATA.glob("*.off"))


@pytest.fixture
def sphere():
    """sphere966.off: a closed genus-0 mesh."""
    import icm

    V, F, repairs = icm.read_mesh(str(DATA / "sphere966.off"))
    return V, F
