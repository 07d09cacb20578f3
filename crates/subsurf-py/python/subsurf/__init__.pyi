"""Type stubs of the subsurf package."""

import os
from typing import Any, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

from ._errors import GpuError as GpuError
from ._errors import MeshError as MeshError
from ._errors import ParseError as ParseError
from ._errors import SubsurfError as SubsurfError
from ._errors import UnsupportedError as UnsupportedError

__version__: str
_Path = Union[str, "os.PathLike[str]"]
_Tess = Tuple[npt.NDArray[np.float32], npt.NDArray[np.float32], npt.NDArray[np.uint32]]

class Mesh:
    def __init__(
        self,
        points: npt.ArrayLike,
        faces: Any,
        *,
        creases: Optional[npt.ArrayLike] = None,
        crease_sharpness: Optional[npt.ArrayLike] = None,
        corners: Optional[npt.ArrayLike] = None,
        corner_sharpness: Optional[npt.ArrayLike] = None,
        holes: Optional[npt.ArrayLike] = None,
        uvs: Optional[npt.ArrayLike] = None,
        uv_indices: Optional[npt.ArrayLike] = None,
        scheme: str = "catmark",
        boundary: str = "edge-only",
        crease_method: str = "uniform",
        triangles: str = "catmark",
        uv_interpolation: str = "linear",
    ) -> None: ...
    @property
    def points(self) -> npt.NDArray[np.float32]: ...
    @property
    def face_counts(self) -> npt.NDArray[np.uint32]: ...
    @property
    def face_indices(self) -> npt.NDArray[np.uint32]: ...
    @property
    def uvs(self) -> Optional[npt.NDArray[np.float32]]: ...
    @property
    def uv_indices(self) -> Optional[npt.NDArray[np.uint32]]: ...
    @property
    def creases(self) -> Tuple[npt.NDArray[np.uint32], npt.NDArray[np.float32]]: ...
    @property
    def corners(self) -> Tuple[npt.NDArray[np.uint32], npt.NDArray[np.float32]]: ...
    @property
    def holes(self) -> npt.NDArray[np.uint32]: ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def num_faces(self) -> int: ...
    @property
    def options(self) -> dict: ...
    def faces(self) -> list: ...
    def triangles(self) -> npt.NDArray[np.uint32]: ...
    def write(self, path: _Path, normals: Optional[npt.ArrayLike] = None) -> None: ...
    @classmethod
    def from_trimesh(cls, t: Any, **kwargs: Any) -> "Mesh": ...
    def to_trimesh(self, **kwargs: Any) -> Any: ...

def read(path: _Path) -> Mesh: ...
def refine(mesh: Mesh, level: int, *, limit: bool = False, backend: str = "cpu") -> Mesh: ...

class Refiner:
    level: int
    def __init__(self, mesh: Mesh, level: int) -> None: ...
    @property
    def num_vertices(self) -> int: ...
    def refine(self, values: npt.ArrayLike) -> npt.NDArray[np.float32]: ...
    def limit(self, values: npt.ArrayLike) -> npt.NDArray[np.float32]: ...
    def refine_uvs(
        self, uvs: npt.ArrayLike, uv_indices: Optional[npt.ArrayLike] = None
    ) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]: ...
    def mesh(self, points: npt.ArrayLike) -> Mesh: ...
    def stencils(
        self,
    ) -> Tuple[npt.NDArray[np.uint32], npt.NDArray[np.uint32], npt.NDArray[np.float32]]: ...
    def stencil_matrix(self) -> Any: ...

class LimitSurface:
    def __init__(self, mesh: Mesh, isolation: int = 4, editable: bool = False) -> None: ...
    @property
    def num_ptex_faces(self) -> int: ...
    @property
    def domain(self) -> str: ...
    def evaluate(
        self, faces: npt.ArrayLike, u: npt.ArrayLike, v: npt.ArrayLike
    ) -> Tuple[npt.NDArray[np.floating], npt.NDArray[np.floating], npt.NDArray[np.floating]]: ...
    def tessellate(self, n: int = 8) -> _Tess: ...
    def update(self, points: npt.ArrayLike) -> None: ...
    def set_sharpness(
        self,
        creases: Optional[npt.ArrayLike] = None,
        sharpness: Optional[npt.ArrayLike] = None,
        *,
        corners: Optional[npt.ArrayLike] = None,
        corner_sharpness: Optional[npt.ArrayLike] = None,
    ) -> str: ...

class Prep:
    def __init__(self, mesh: Mesh) -> None: ...
    @property
    def num_faces(self) -> int: ...
    def bezier(self) -> npt.NDArray[np.float64]: ...
    def tessellate(
        self, n: int = 8
    ) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.uint32]]: ...

def tessellate(
    mesh: Mesh,
    method: str = "limit",
    n: int = 8,
    backend: str = "cpu",
    isolation: int = 4,
    *,
    tolerance: Optional[float] = None,
    max_edge_length: Optional[float] = None,
    edge_rates: Optional[npt.ArrayLike] = None,
) -> _Tess: ...
def render(
    mesh: Mesh,
    size: Tuple[int, int] = (800, 600),
    method: str = "limit",
    n: Optional[int] = None,
    view: str = "iso",
    up: str = "y",
    colors: str = "none",
    cage: bool = False,
    background: Union[str, Sequence[int]] = "white",
    path: Optional[str] = None,
) -> npt.NDArray[np.uint8]: ...
