"""ICM: conformal parameterization of triangle meshes by the inverse curvature map.

The functions are those of the compiled module ``_icm`` (python/icm_module.cpp); see
doc/python.md and the docstring of each. ``python3 -m icm.batch`` (the module icm.batch, not
imported here) parameterizes many meshes, each in a process of its own, on a Dask cluster:
doc/batch.md.
"""

from ._icm import (
    BOUNDARIES,
    ENERGIES,
    HAS_GLTF,
    METRICS,
    Error,
    Parameterization,
    measure_distortion,
    parameterize,
    read_mesh,
    write_mesh,
)

__all__ = [
    "BOUNDARIES",
    "ENERGIES",
    "HAS_GLTF",
    "METRICS",
    "Error",
    "Parameterization",
    "measure_distortion",
    "parameterize",
    "read_mesh",
    "write_mesh",
]
