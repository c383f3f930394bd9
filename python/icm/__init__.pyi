"""Type stubs of the module icm (python/icm_module.cpp)."""

from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

ENERGIES: List[str]
METRICS: List[str]
BOUNDARIES: List[str]
HAS_GLTF: bool

class Error(ValueError):
    """A refused input or a failed run; ``code`` is ICM's error code where there is one."""

    code: Optional[int]

class Parameterization:
    """The result of parameterize()."""

    @property
    def uv(self) -> npt.NDArray[np.float64]: ...
    @property
    def fuv(self) -> npt.NDArray[np.int64]: ...
    @property
    def charts(self) -> int: ...
    @property
    def seams(self) -> npt.NDArray[np.int64]: ...
    @property
    def report(self) -> Dict[str, Any]: ...

def parameterize(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    *,
    cones: Union[str, int] = "auto",
    cone: Sequence[Tuple[int, float]] = ...,
    energy: str = "entropy",
    atlas: Optional[int] = None,
    padding: int = 4,
    seams: Optional[npt.ArrayLike] = None,
    metric: str = "intrinsic-delaunay",
    boundary: str = "free",
    keep_overlaps: bool = False,
) -> Parameterization: ...
def read_mesh(
    path: str, *, triangulate: bool = False
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], List[str]]: ...
def write_mesh(
    path: str,
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    uv: npt.ArrayLike,
    fuv: npt.ArrayLike,
    *,
    binary_ply: bool = False,
) -> None: ...
def measure_distortion(
    V: npt.ArrayLike, F: npt.ArrayLike, uv: npt.ArrayLike, fuv: npt.ArrayLike
) -> Dict[str, float]: ...
