"""subsurf: Catmull-Clark and bilinear subdivision that reproduces OpenSubdiv 3.5, limit
surfaces and the p-rep, with numpy arrays in and out.

Every computation releases the GIL; objects are immutable (``LimitSurface.update`` swaps its
state atomically) and safe to share between threads. Floating-point work is done in float32
(the library's precision) except where positions are float64: a ``Mesh`` keeps float64
positions as given, ``refine`` and ``Refiner.refine`` then work in float64 (Catmull-Clark and
bilinear meshes, on the CPU), and ``Prep`` is always built in float64.
"""

from __future__ import annotations

import functools as _functools
import inspect as _inspect
import typing as _typing

import numpy as _np

from . import _subsurf
from ._errors import GpuError, MeshError, ParseError, SubsurfError, UnsupportedError

if _typing.TYPE_CHECKING:  # the annotations' names, for type checkers only
    import os
    from typing import Any, Optional, Sequence, Tuple, Union


__all__ = [
    "Mesh", "read", "refine", "Refiner", "LimitSurface", "Prep", "tessellate", "render",
    "MeshError", "ParseError", "GpuError", "SubsurfError", "UnsupportedError",
]
__version__ = "0.1.0"

_U32_MAX = 2**32 - 1

# Keywords renamed for one vocabulary (docs/vocabulary.md): named in the error an old
# spelling raises, never accepted silently.
_RENAMED = {
    "n": "tess (samples per side) or level (method 'refine')",
    "points": "positions",
    "triangles": "triangle_subdivision",
    "colors": "color_by",
    "sharpness": "crease_sharpness",
    "path": "output",
}


def _keywords(f: Any) -> Any:
    """``f`` refusing an unknown keyword with a ``TypeError`` that names it, the new name of a
    renamed one and the accepted keywords (``inspect.signature`` still shows ``f``'s)."""
    params = _inspect.signature(f).parameters.values()
    accepted = tuple(p.name for p in params if p.name != "self"
                     and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY))
    name = f.__qualname__.replace(".__init__", "")

    @_functools.wraps(f)
    def checked(*args: Any, **kwargs: Any) -> Any:
        for k in kwargs:
            if k not in accepted:
                renamed = f" (renamed: use {_RENAMED[k]})" if k in _RENAMED else ""
                raise TypeError(f"{name}() got an unknown keyword argument {k!r}{renamed}; "
                                f"accepted: {', '.join(accepted)}")
        return f(*args, **kwargs)

    return checked


def _floats(a: Any, cols: int, what: str, keep_f64: bool = False) -> _np.ndarray:
    """(n, cols) float32 (float64 kept with ``keep_f64``), C-contiguous; no copy when it
    already is."""
    try:
        arr = _np.asarray(a)
    except Exception as e:  # ragged lists and the like
        raise ValueError(f"{what}: not an array ({e})") from None
    if arr.dtype.kind not in "fiu" or arr.dtype == _np.float16:
        if arr.size or arr.dtype.kind not in "O":
            if arr.dtype.kind not in "fiu":
                raise ValueError(f"{what}: expected numbers, got dtype {arr.dtype}")
    if arr.ndim == 1 and arr.size == 0:
        arr = arr.reshape(0, cols)
    if arr.ndim != 2 or arr.shape[1] != cols:
        raise ValueError(f"{what}: expected shape (n, {cols}), got {arr.shape}")
    if arr.dtype == _np.float64 and arr.size:
        big = _np.abs(arr[_np.isfinite(arr)])
        if big.size and big.max() > _np.finfo(_np.float32).max:
            raise MeshError(f"{what}: a value overflows float32", face=None, corner=None, vertex=None)
    if keep_f64 and arr.dtype == _np.float64:
        return _np.ascontiguousarray(arr)
    return _np.ascontiguousarray(arr, dtype=_np.float32)


def _indices(a: Any, what: str) -> _np.ndarray:
    """1-D uint32, C-contiguous; negative, huge or fractional values refused."""
    try:
        arr = _np.asarray(a)
    except Exception as e:
        raise ValueError(f"{what}: not an array ({e})") from None
    if arr.size == 0:
        return _np.zeros(0, dtype=_np.uint32)
    if arr.dtype.kind == "f":
        if not _np.all(_np.isfinite(arr)) or _np.any(arr != _np.round(arr)):
            raise ValueError(f"{what}: indices must be integers")
    elif arr.dtype.kind not in "iub":
        raise ValueError(f"{what}: expected integers, got dtype {arr.dtype}")
    arr = arr.reshape(-1)
    if arr.min() < 0:
        k = int(_np.argmin(arr))
        raise ValueError(f"{what}[{k}] = {arr[k]}: negative index")
    if arr.max() > _U32_MAX:
        k = int(_np.argmax(arr))
        raise ValueError(f"{what}[{k}] = {arr[k]}: index too large")
    return _np.ascontiguousarray(arr, dtype=_np.uint32)


def _faces(faces: Any) -> Tuple[_np.ndarray, _np.ndarray]:
    if isinstance(faces, tuple) and len(faces) == 2:
        counts, idx = _indices(faces[0], "face counts"), _indices(faces[1], "face indices")
        return counts, idx
    if isinstance(faces, _np.ndarray) and faces.ndim == 2:
        m, k = faces.shape
        return _np.full(m, k, dtype=_np.uint32), _indices(faces, "faces")
    if isinstance(faces, _np.ndarray) and faces.ndim != 2:
        raise ValueError(f"faces: expected an (m, k) array, got shape {faces.shape}")
    try:
        lists = [list(f) for f in faces]
    except TypeError:
        raise ValueError("faces: an (m, k) array, a list of index lists or (counts, indices)") from None
    counts = _np.array([len(f) for f in lists], dtype=_np.int64)
    flat = [i for f in lists for i in f]
    return _indices(counts, "face counts"), _indices(_np.array(flat) if flat else [], "faces")


def _tags(a: Any, sharpness: Any, cols: int, what: str) -> Tuple[_np.ndarray, _np.ndarray]:
    if a is None:
        return _np.zeros((0, cols), dtype=_np.uint32).reshape(-1) if cols == 1 else _np.zeros((0, 2), dtype=_np.uint32), _np.zeros(0, dtype=_np.float32)
    arr = _np.asarray(a)
    if cols == 2:
        if arr.ndim == 2 and arr.shape[1] == 3 and sharpness is None:
            pairs, s = arr[:, :2], arr[:, 2]
        elif arr.ndim == 2 and arr.shape[1] == 2 and sharpness is not None:
            pairs, s = arr, sharpness
        else:
            raise ValueError(f"{what}: a (c, 2) array with a sharpness array, or one (c, 3) array")
        p = _indices(pairs, what).reshape(-1, 2)
    else:
        if arr.ndim == 2 and arr.shape[1] == 2 and sharpness is None:
            pairs, s = arr[:, 0], arr[:, 1]
        elif arr.ndim == 1 and sharpness is not None:
            pairs, s = arr, sharpness
        else:
            raise ValueError(f"{what}: a (c,) array with a sharpness array, or one (c, 2) array")
        p = _indices(pairs, what)
    s = _np.asarray(s, dtype=_np.float64)
    if s.ndim == 0:
        # One value for every tag.
        s = _np.full(len(p), s)
    s = _np.ascontiguousarray(s, dtype=_np.float32).reshape(-1)
    if len(s) != len(p):
        raise ValueError(f"{what}: {len(p)} tags, {len(s)} sharpness values")
    if _np.any(_np.isnan(s)):
        raise MeshError(f"{what}: sharpness is NaN")
    return p, s


class Mesh:
    """A polygon mesh with subdivision tags and options (immutable).

    Parameters
    ----------
    positions : (n, 3) float array of vertex positions: float64 is kept as given (``refine``
        then works in float64), other types become float32. A mesh read from a file is
        float32 here (its writes keep the file's digits)
    faces : (m, k) integer array, list of index lists, or ``(counts, indices)`` as USD stores them
    creases : (c, 2) vertex pairs with ``crease_sharpness`` (c,) or one value for all, or one
        (c, 3) array; sharpness 10 or more is infinitely sharp
    corners : (c,) vertices with ``corner_sharpness`` ((c,) or one value), or one (c, 2) array
    holes : face indices
    uvs : (u, 2) float array; ``uv_indices`` one per face corner (default: the face indices)
    scheme : "catmark" | "bilinear" | "loop" (Loop: triangles only)
    boundary : "none" | "edge-only" | "edge-and-corner"
    crease_method : "uniform" | "chaikin"
    triangle_subdivision : "catmark" | "smooth" (the Catmull-Clark triangle rule)
    uv_interpolation : "none" | "corners-only" | "corners-plus1" | "corners-plus2" | "boundaries" | "linear"

    The names are those of the command line (``--scheme``, ``--boundary``, ...); see
    ``docs/vocabulary.md``. An unknown value raises ``ValueError`` listing the accepted ones.

    Raises ``MeshError`` (with ``.face``, ``.corner``, ``.vertex``) on bad content.
    """

    __slots__ = ("_m",)

    @_keywords
    def __init__(self, positions: Any, faces: Any, *, creases: Any = None, crease_sharpness: Any = None,
                 corners: Any = None, corner_sharpness: Any = None, holes: Any = None,
                 uvs: Any = None, uv_indices: Any = None, scheme: str = "catmark",
                 boundary: str = "edge-only", crease_method: str = "uniform",
                 triangle_subdivision: str = "catmark", uv_interpolation: str = "linear") -> None:
        p = _floats(positions, 3, "positions", keep_f64=True)
        counts, idx = _faces(faces)
        cp, cs = _tags(creases, crease_sharpness, 2, "creases")
        cv, csh = _tags(corners, corner_sharpness, 1, "corners")
        h = _indices([] if holes is None else holes, "holes")
        uv = None if uvs is None else _floats(uvs, 2, "uvs")
        ui = None if uv_indices is None else _indices(uv_indices, "uv_indices")
        for name, v in (("scheme", scheme), ("boundary", boundary), ("crease_method", crease_method),
                        ("triangle_subdivision", triangle_subdivision),
                        ("uv_interpolation", uv_interpolation)):
            if not isinstance(v, str):
                raise ValueError(f"{name}: expected a string, got {type(v).__name__}")
        self._m = _subsurf._Mesh(p, counts, idx, cp.reshape(-1, 2), cs, cv.reshape(-1), csh, h, uv, ui,
                                 scheme, boundary, crease_method, triangle_subdivision, uv_interpolation)

    @classmethod
    def _wrap(cls, m: Any) -> "Mesh":
        obj = cls.__new__(cls)
        obj._m = m
        return obj

    positions = property(lambda self: self._m.positions,
                         doc="(n, 3) vertex positions: float64 when given as float64, else float32")

    @property
    def points(self) -> Any:
        """Renamed ``positions`` (docs/vocabulary.md)."""
        raise AttributeError("Mesh.points was renamed Mesh.positions (docs/vocabulary.md)")

    face_counts = property(lambda self: self._m.face_counts, doc="(m,) uint32 corners per face")
    face_indices = property(lambda self: self._m.face_indices, doc="uint32 vertex of every face corner")
    uvs = property(lambda self: self._m.uvs, doc="(u, 2) float32 UVs or None")
    uv_indices = property(lambda self: self._m.uv_indices, doc="uint32 UV of every face corner or None")
    creases = property(lambda self: self._m.creases, doc="((c, 2) uint32 pairs, (c,) float32 sharpness)")
    corners = property(lambda self: self._m.corners, doc="((c,) uint32 vertices, (c,) float32 sharpness)")
    holes = property(lambda self: self._m.holes, doc="(h,) uint32 hole faces")
    num_vertices = property(lambda self: self._m.num_vertices, doc="number of vertices")
    num_faces = property(lambda self: self._m.num_faces, doc="number of faces")

    @property
    def options(self) -> dict:
        """Scheme options as the constructor's keyword arguments."""
        keys = ("scheme", "boundary", "crease_method", "triangle_subdivision", "uv_interpolation")
        return dict(zip(keys, self._m.options))

    def faces(self) -> list:
        """The faces as a list of index lists."""
        idx = self.face_indices.tolist()
        out, s = [], 0
        for c in self.face_counts.tolist():
            out.append(idx[s:s + c])
            s += c
        return out

    @_keywords
    def write(self, path: Union[str, "os.PathLike[str]"], normals: Any = None, *,
              keep_holes: bool = False) -> None:
        """Writes the mesh: .obj (with OpenSubdiv tags), .ply, .glb or USD, by extension.
        Hole faces are left out, as viewers that ignore hole tags would draw them closed;
        ``keep_holes=True`` writes them tagged (OBJ ``t hole``, USD ``holeIndices``), so that
        refining the file again continues the same surface (PLY and glb refuse it)."""
        n = None if normals is None else _floats(normals, 3, "normals")
        self._m.write(str(path), n, bool(keep_holes))

    def without_holes(self) -> "Mesh":
        """The mesh with its hole faces left out (every vertex kept, so per-point data still
        lines up): what a viewer should draw."""
        return Mesh._wrap(self._m.without_holes())

    def triangles(self) -> _np.ndarray:
        """(t, 3) uint32 fan triangulation of the faces (holes kept)."""
        tris = []
        for f in self.faces():
            tris.extend([f[0], f[k], f[k + 1]] for k in range(1, len(f) - 1))
        return _np.array(tris, dtype=_np.uint32).reshape(-1, 3)

    @classmethod
    def from_trimesh(cls, t: Any, /, **kwargs: Any) -> "Mesh":
        """A mesh from a ``trimesh.Trimesh`` (vertices, faces, and UVs when it has them);
        ``kwargs`` are the keywords of ``Mesh``."""
        uv = getattr(getattr(t, "visual", None), "uv", None)
        if uv is not None and len(uv) == len(t.vertices):
            kwargs.setdefault("uvs", uv)
        return cls(_np.asarray(t.vertices), _np.asarray(t.faces), **kwargs)

    def to_trimesh(self, **kwargs: Any) -> Any:
        """A ``trimesh.Trimesh`` (faces fan-triangulated, hole faces left out, vertices not
        merged)."""
        import trimesh

        return trimesh.Trimesh(vertices=self.positions.astype(_np.float64),
                               faces=self.without_holes().triangles(),
                               process=False, **kwargs)

    def __repr__(self) -> str:
        return f"subsurf.Mesh({self.num_vertices} vertices, {self.num_faces} faces)"


@_keywords
def read(path: Union[str, "os.PathLike[str]"]) -> Mesh:
    """Reads a mesh file by extension: .obj (v, vt, f, OpenSubdiv's ``t`` tags), .ply (ASCII
    or binary), .glb / .gltf, or a USD stage (.usda, .usdc, .usd, .usdz; its one mesh prim).
    Raises ``ParseError`` with ``.path`` and ``.line``, ``OSError``, ``MeshError``."""
    return Mesh._wrap(_subsurf._Mesh.read(str(path)))


def _mesh(m: Any) -> Any:
    if not isinstance(m, Mesh):
        raise TypeError(f"expected a subsurf.Mesh, got {type(m).__name__}")
    return m._m


def _int(v: Any, what: str, lo: int = 0) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, _np.integer)):
        raise ValueError(f"{what}: expected an integer, got {v!r}")
    v = int(v)
    if v < lo or v > 1_000_000:
        raise ValueError(f"{what} = {v}: out of range")
    return v


@_keywords
def refine(mesh: Mesh, level: int, *, limit: bool = False, backend: str = "cpu") -> Mesh:
    """Uniform refinement ``level`` times (vertex order as OpenSubdiv: children of vertices,
    face points, edge points). ``limit=True`` moves the last level and its UVs to the limit.
    UVs are refined in the mesh's ``uv_interpolation`` mode. ``backend``: "cpu" or "gpu"
    (positions and UVs refined on the GPU). The result keeps every face of the last level,
    hole faces included and listed in ``holes``, with the crease and corner sharpness that
    remains, so it refines on as the level itself would; UVs are the last level's values and
    per-corner indices. ``Mesh.write`` leaves the hole faces out unless ``keep_holes=True``
    (as ``subsurf refine`` does without and with ``--keep-holes``); ``without_holes()``
    gives the faces a viewer should draw. Same numbers and faces as
    ``subsurf --keep-holes refine`` writes to OBJ. A mesh given float64 positions is
    refined in float64 on the CPU, as ``subsurf refine --f64``, and the result is float64."""
    return Mesh._wrap(_subsurf.refine(_mesh(mesh), _int(level, "level"), bool(limit), backend))


class Refiner:
    """Refinement tables of ``mesh`` to ``level``, built once and applied to any per-vertex
    data (positions per animation frame, colours, weights).

    ``refine(values)``: (n, d) base-vertex data -> (n_last, d) float32 (float64 data:
    float64, every step's masks in double precision).
    ``limit(values)``: (n_last, d) last-level data -> its limit.
    ``refine_uvs(uvs, uv_indices=None)``: -> (values, per-corner indices) of the last level.
    ``mesh(positions)``: the refined ``Mesh`` with these positions.
    ``stencils()``: ``(offsets, indices, weights)`` CSR rows, base -> last level.
    """

    __slots__ = ("_r", "_mesh", "level")

    @_keywords
    def __init__(self, mesh: Mesh, level: int) -> None:
        self._mesh = mesh
        self.level = _int(level, "level")
        self._r = _subsurf._Refiner(_mesh(mesh), self.level)

    @property
    def num_vertices(self) -> int:
        """Vertices of the last level."""
        return self._r.num_vertices

    @_keywords
    def refine(self, values: Any) -> _np.ndarray:
        """(n_base, d) float data -> (n_last, d) float32; float64 data stays float64 (masks in
        double precision)."""
        v = _np.asarray(values)
        one = v.ndim == 1
        arr = _floats(v.reshape(-1, 1) if one else v, v.shape[1] if v.ndim == 2 else 1, "values",
                      keep_f64=True)
        if arr.dtype == _np.float64:
            return self._r.refine_f64(arr)
        return self._r.refine(arr)

    @_keywords
    def limit(self, values: Any) -> _np.ndarray:
        """(n_last, d) last-level data -> limit values (n_last, d) float32."""
        v = _np.asarray(values)
        return self._r.limit(_floats(v, v.shape[1] if v.ndim == 2 else 1, "values"))

    @_keywords
    def refine_uvs(self, uvs: Any, uv_indices: Any = None) -> Tuple[_np.ndarray, _np.ndarray]:
        """Face-varying (u, 2) UVs with one index per base face corner (default the face
        indices) -> the last level's (values, indices), in the mesh's interpolation mode."""
        idx = self._mesh.face_indices if uv_indices is None else _indices(uv_indices, "uv_indices")
        return self._r.refine_uvs(_floats(uvs, 2, "uvs"), idx)

    @_keywords
    def mesh(self, positions: Any) -> Mesh:
        """The refined mesh (every face, holes and remaining sharpness tagged, as ``refine``)
        with ``positions`` (n_last, 3)."""
        return Mesh._wrap(self._r.mesh(_floats(positions, 3, "positions")))

    def stencils(self) -> Tuple[_np.ndarray, _np.ndarray, _np.ndarray]:
        """(offsets (n_last + 1,) uint32, indices uint32, weights float32): row i of the last
        level is ``sum(weights[k] * base[indices[k]] for k in offsets[i]:offsets[i+1])``."""
        return self._r.stencils()

    def stencil_matrix(self) -> Any:
        """The stencils as a ``scipy.sparse.csr_matrix`` of shape (n_last, n_base)."""
        from scipy.sparse import csr_matrix

        o, i, w = self.stencils()
        return csr_matrix((w, i, o), shape=(len(o) - 1, self._mesh.num_vertices))


class LimitSurface:
    """The limit surface of ``mesh``, extraordinary features isolated to ``isolation`` levels
    (0..=10). A Catmull-Clark or bilinear mesh: B-spline, single-crease and Gregory patches
    over ptex faces (one per quad, one per n-gon corner), parameters in [0, 1]^2, float32.
    A Loop mesh: quartic box-spline patches and Gregory-triangle end caps over its base
    triangles, parameters ``u, v >= 0, u + v <= 1``, evaluated in float64 (``domain`` says
    which: ``"square"`` or ``"triangle"``). A mesh given float64 positions gets the
    double-precision surface (``f64`` is true): masks, patch points and evaluation in float64,
    from the positions as given, and float64 results from ``evaluate`` and ``tessellate``.

    ``evaluate(faces, u, v)`` -> (positions, du, dv), each (k, 3), NaN at holes.
    ``tessellate(tess)`` -> (positions, normals, triangles), ``tess`` samples per face side.
    ``update(positions)``: new control points (same count), e.g. after a deformation.
    ``set_sharpness(creases, crease_sharpness, corners=, corner_sharpness=)``: live crease edits
    (Catmull-Clark and bilinear meshes). With ``editable=True`` the patch table keeps its
    refinement levels from the start (about 3x its memory), so that the first edit that keeps
    the isolation structure is made in place as the later ones are; otherwise the first edit
    rebuilds the table to keep them (Loop surfaces take no edits: ``UnsupportedError``).
    """

    __slots__ = ("_s",)

    @_keywords
    def __init__(self, mesh: Mesh, isolation: int = 4, editable: bool = False) -> None:
        if not isinstance(editable, (bool, _np.bool_)):
            raise TypeError(f"editable: expected a bool, got {type(editable).__name__}")
        self._s = _subsurf._LimitSurface(_mesh(mesh), _int(isolation, "isolation"),
                                         bool(editable))

    @property
    def num_ptex_faces(self) -> int:
        """Number of faces a query may name (ptex faces, or a Loop mesh's triangles)."""
        return self._s.num_ptex_faces

    @property
    def domain(self) -> str:
        """``"square"`` (ptex faces, [0, 1]^2) or ``"triangle"`` (Loop, u + v <= 1)."""
        return self._s.domain

    @property
    def f64(self) -> bool:
        """Whether the surface is double precision (built from float64 positions)."""
        return self._s.f64

    @_keywords
    def evaluate(self, faces: Any, u: Any, v: Any) -> Tuple[_np.ndarray, _np.ndarray, _np.ndarray]:
        """Positions and first derivatives at (face, u, v), vectorized."""
        f = _indices(faces, "faces")
        uu = _np.ascontiguousarray(_np.asarray(u, dtype=_np.float64).reshape(-1))
        vv = _np.ascontiguousarray(_np.asarray(v, dtype=_np.float64).reshape(-1))
        return self._s.evaluate(f, uu, vv)

    @_keywords
    def tessellate(self, tess: int = 8) -> Tuple[_np.ndarray, _np.ndarray, _np.ndarray]:
        """Watertight (positions (p, 3) float32 (float64 when ``f64``), unit normals (p, 3),
        triangles (t, 3) uint32), ``tess`` samples per side of every ptex face (Loop: of every
        base triangle)."""
        return self._s.tessellate(_int(tess, "tess"))

    @_keywords
    def update(self, positions: Any) -> None:
        """Replaces the control points (the patch table is kept; a double-precision surface
        takes them in float64)."""
        if self._s.f64:
            arr = _floats(positions, 3, "positions", keep_f64=True)
            self._s.update_f64(_np.ascontiguousarray(arr, dtype=_np.float64))
        else:
            self._s.update(_floats(positions, 3, "positions"))

    @_keywords
    def set_sharpness(self, creases: Any = None, crease_sharpness: Any = None, *,
                      corners: Any = None, corner_sharpness: Any = None) -> str:
        """New crease sharpness for base edges and corner sharpness for base vertices, as
        ``Mesh`` takes them (``creases``: (c, 2) vertex pairs with ``crease_sharpness`` (c,) or
        one value for all, or one (c, 3) array; ``corners``: (c,) vertices with
        ``corner_sharpness`` ((c,) or one value), or one (c, 2) array; 0 smooth, 10 or more
        infinitely sharp), later entries of the same element winning. The patch table is updated in place where
        its isolation structure is kept, rebuilt locally (the faces around the edit) where it
        changes over a bounded region, and rebuilt otherwise (from the first isolation level
        whose faces change, the levels above kept); either way the surface is,
        bit for bit, that of a ``LimitSurface`` of the edited mesh at the current control
        points. Returns ``"unchanged"``, ``"updated"``, ``"local"`` or ``"rebuilt"``.

        Every edit is checked before any work: an edge that is not in the mesh, a vertex out
        of range or a negative or NaN sharpness raises ``MeshError`` with ``.edit`` (its
        index: creases first, then corners) and the surface is left as it was. A Loop
        surface raises ``UnsupportedError``.
        """
        if creases is None and crease_sharpness is not None:
            raise ValueError("crease_sharpness without creases")
        if corners is None and corner_sharpness is not None:
            raise ValueError("corner_sharpness without corners")
        cp, cs = _tags(creases, crease_sharpness, 2, "creases")
        cv, csh = _tags(corners, corner_sharpness, 1, "corners")
        return self._s.set_sharpness(cp.reshape(-1, 2), cs, cv.reshape(-1), csh)


class Prep:
    """The p-rep (Myles, Yeo & Peters 2008) of a closed, oriented quad mesh, built in float64:
    one bi-3 patch per quad plus a bi-5 perturbation near non-4-valent vertices (G1).

    ``bezier()`` -> (faces, 6, 6, 3) float64 Bezier control points.
    ``tessellate(tess)`` -> (positions, normals, triangles) float64, ``tess`` samples per
    patch side.
    """

    __slots__ = ("_p",)

    @_keywords
    def __init__(self, mesh: Mesh) -> None:
        self._p = _subsurf._Prep(_mesh(mesh))

    @property
    def num_faces(self) -> int:
        """Number of patches (quads)."""
        return self._p.num_faces

    def bezier(self) -> _np.ndarray:
        """(faces, 6, 6, 3) float64 bi-5 Bezier control points."""
        return self._p.bezier()

    @_keywords
    def tessellate(self, tess: int = 8) -> Tuple[_np.ndarray, _np.ndarray, _np.ndarray]:
        """Watertight (positions, normals, triangles), ``tess`` samples per patch side,
        bit-identical along shared edges."""
        return self._p.tessellate(_int(tess, "tess"))


@_keywords
def tessellate(mesh: Mesh, method: str = "limit", *, level: Optional[int] = None,
               tess: Optional[int] = None, backend: str = "cpu", isolation: int = 4,
               tolerance: Optional[float] = None, max_edge_length: Optional[float] = None,
               edge_rates: Any = None) -> Tuple[_np.ndarray, _np.ndarray, _np.ndarray]:
    """The surface API: ``(positions (p, 3) float32, unit normals (p, 3) float32, triangles
    (t, 3) uint32)``.

    method : "refine" (uniform refinement to ``level``, fan-triangulated, Newell normals),
        "limit" (``tess`` samples per ptex-face side), "prep" (``tess`` samples per patch
        side; one Catmull-Clark step first for non-quad meshes) or "prep-bicubic" (without
        the perturbation)
    level : refinement level (method "refine", default 3)
    tess : samples per side (methods "limit", "prep", "prep-bicubic", default 8)
    backend : "cpu" or "gpu"
    isolation : levels of feature-adaptive isolation of the limit patches (0..=10, default 4)

    As ``subsurf render --method M --level L / --tess N``: ``level`` with another method, or
    ``tess`` with "refine", raises ``ValueError``.

    Adaptive per-edge rates (method "limit", Catmull-Clark and bilinear meshes; at most one,
    watertight with any mix of rates): ``tolerance`` (chordal error as a fraction of the
    bounding-box diagonal), ``max_edge_length`` (world units) or ``edge_rates`` ((k, 3)
    integers ``v0 v1 rate``: the base edge joining v0 and v1 gets ``rate`` segments, 1..=4096;
    unlisted edges get ``tess - 1``), as ``subsurf limit --tolerance / --max-edge-length /
    --edge-rates``.
    """
    rates = None
    if edge_rates is not None:
        rates = _np.ascontiguousarray(_np.asarray(edge_rates, dtype=_np.int64).reshape(-1, 3))
        if (rates < 0).any():
            raise ValueError("edge_rates: vertex indices and rates must be non-negative")
        rates = rates.astype(_np.uint64)
    return _subsurf.tessellate(_mesh(mesh), method,
                               level=None if level is None else _int(level, "level"),
                               tess=None if tess is None else _int(tess, "tess"),
                               backend=backend, isolation=_int(isolation, "isolation"),
                               tolerance=None if tolerance is None else float(tolerance),
                               max_edge_length=None if max_edge_length is None else float(max_edge_length),
                               edge_rates=rates)


@_keywords
def render(mesh: Mesh, size: Tuple[int, int] = (800, 600), method: str = "limit", *,
           level: Optional[int] = None, tess: Optional[int] = None, view: str = "iso",
           up: str = "y", color_by: str = "none", cage: bool = False,
           background: Union[str, Sequence[int]] = "white",
           output: Optional[Union[str, "os.PathLike[str]"]] = None) -> _np.ndarray:
    """A headless render (wgpu; lavapipe without a GPU): ``(height, width, 4)`` uint8 RGBA.

    size : (width, height) in pixels
    method : "refine" | "limit" | "prep" | "prep-bicubic"; ``level`` (refine, default 3) or
        ``tess`` (samples per side of the others, default 8), as ``tessellate``
    view : "front" | "back" | "left" | "right" | "top" | "iso"; up : "y" | "z"
    color_by : "none" | "patch-kind" | "level" | "sharpness"
    cage : draw the base mesh's edges; background : "white", "black", "transparent",
        "RRGGBB" or (r, g, b, a)
    output : also write a PNG there

    The keywords are those of ``subsurf render`` (``--level``, ``--tess``, ``--color-by``,
    ``-o/--output``, ...); see ``docs/vocabulary.md``.
    """
    if not isinstance(background, str):
        background = tuple(int(x) for x in background)
        if len(background) != 4:
            raise ValueError(f"background {background!r}: a name, RRGGBB or (r, g, b, a)")
    w, h = (_int(size[0], "width", 1), _int(size[1], "height", 1))
    return _subsurf.render(_mesh(mesh), w, h, method,
                           None if level is None else _int(level, "level"),
                           None if tess is None else _int(tess, "tess"),
                           view, up, color_by, bool(cage), background,
                           None if output is None else str(output))


del annotations  # the future import's name, not part of the package
