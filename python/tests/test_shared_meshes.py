"""icm.parameterize against icm_param on every mesh of the shared data folder (closed
surfaces of genus 0 to 3, disks, surfaces with several holes, up to ~90k faces), as
test_same_as_icm_param does on the bundled meshes."""

import pytest

import icm
from conftest import SHARED_DATA, SHARED_MESHES, assert_same_as_icm_param, run_icm_param

# Without the folder, one test that says why it did not run rather than none.
_MESHES = SHARED_MESHES or [
    pytest.param(None, marks=pytest.mark.skip(reason=f"no shared meshes in {SHARED_DATA} (set ICM_SHARED_DATA)"))
]


@pytest.mark.shared_meshes
@pytest.mark.parametrize("mesh", _MESHES, ids=[m.name for m in SHARED_MESHES] or ["absent"])
def test_shared_mesh_same_as_icm_param(mesh, tmp_path):
    """The same figures as icm_param's --json line, or the same refusal."""
    run, expected, obj = run_icm_param(mesh, tmp_path)
    if run.returncode != 0:
        # icm_param refuses it: so must the module, reading or parameterizing.
        with pytest.raises(icm.Error):
            V, F, _ = icm.read_mesh(str(mesh))
            icm.parameterize(V, F)
        return
    V, F, _ = icm.read_mesh(str(mesh))
    result = icm.parameterize(V, F)
    assert_same_as_icm_param(result, expected, obj, keys=("boundary_loops", "cones_above_full_turn", "metric"))
