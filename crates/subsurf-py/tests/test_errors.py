"""Errors are Python exceptions of the documented classes; no input, however bad, surfaces
as a Rust panic (pyo3_runtime.PanicException)."""

import itertools

import numpy as np
import pytest

import subsurf
from conftest import SHAPES

TRI = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], dtype=np.float64)
QUAD = [[0, 1, 3, 2]]


def test_mesh_error_names_the_element():
    with pytest.raises(subsurf.MeshError) as e:
        subsurf.Mesh(TRI, [[0, 1, 3, 7]])
    assert isinstance(e.value, ValueError)
    assert (e.value.face, e.value.corner, e.value.vertex) == (0, 3, 7)
    with pytest.raises(subsurf.MeshError) as e:
        subsurf.Mesh(TRI, [[0, 1, 3, 2], [0, 1]])
    assert e.value.face == 1
    bad = TRI.copy()
    bad[2, 1] = np.nan
    with pytest.raises(subsurf.MeshError) as e:
        subsurf.Mesh(bad, QUAD)
    assert e.value.vertex == 2


def test_loop_refuses_a_quad_naming_it():
    tris = [[0, 1, 2], [1, 3, 2]]
    assert subsurf.refine(subsurf.Mesh(TRI, tris, scheme="loop"), 1).num_faces == 8
    m = subsurf.Mesh(TRI, [[0, 1, 2], [1, 3, 2], [0, 1, 3, 2]], scheme="loop")
    assert m.options["scheme"] == "loop"
    with pytest.raises(subsurf.MeshError) as e:
        subsurf.refine(m, 1)
    assert e.value.face == 2 and "face 2 has 4 vertices" in str(e.value)


def test_parse_error_has_path_and_line(tmp_path):
    p = tmp_path / "bad.obj"
    p.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 x 0\nf 1 2 3\n")
    with pytest.raises(subsurf.ParseError) as e:
        subsurf.read(p)
    assert isinstance(e.value, ValueError)
    assert e.value.path == str(p) and e.value.line == 4
    assert "line 4" in str(e.value)
    with pytest.raises(OSError):
        subsurf.read(tmp_path / "missing.obj")


def test_gltf_parse_error_names_the_part(tmp_path):
    # A valid one-triangle glTF whose accessor points past the end of its buffer.
    import base64
    import json

    data = np.array([0, 0, 0, 1, 0, 0, 0, 1, 0], dtype=np.float32).tobytes()
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteLength": len(data)}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    }
    good = tmp_path / "good.gltf"
    good.write_text(json.dumps(doc))
    assert subsurf.read(good).num_faces == 1
    doc["accessors"][0]["count"] = 30
    bad = tmp_path / "bad.gltf"
    bad.write_text(json.dumps(doc))
    with pytest.raises(subsurf.ParseError) as e:
        subsurf.read(bad)
    assert isinstance(e.value, ValueError)
    assert e.value.path == str(bad) and e.value.line is None
    assert e.value.location is not None and "accessors[0]" in e.value.location
    assert str(bad) in str(e.value) and "glTF" in str(e.value)


def test_gpu_error_is_a_runtime_error():
    assert issubclass(subsurf.GpuError, RuntimeError)
    assert "lavapipe" in subsurf.GpuError.__doc__


def _bad_inputs():
    pts = [TRI, TRI.astype(np.float32), np.zeros((0, 3)), np.full((4, 3), np.nan), np.full((4, 3), np.inf),
           np.full((4, 3), 1e39), TRI[:, :2], TRI.reshape(-1), TRI.astype(object), "abc", None,
           TRI.astype(np.int8), np.asfortranarray(TRI), TRI[::2], [[1, 2, 3], [4, 5]]]
    faces = [QUAD, [], [[]], [[0, 1]], [[0, 1, 2, -1]], [[0, 1, 2, 2**32 + 1]], [[0, 1, 2, 2**40]],
             np.array([[0.5, 1, 2]]), (np.array([3, -1]), np.array([0, 1, 2])), (np.array([5]), np.array([0, 1, 2])),
             (np.array([3]), np.array([0, 1, 2, 3])), np.zeros((0, 4), dtype=int), [[0, 1, 2], [0, 1, 3, 2, 1, 0]],
             [[0, 0, 0]], np.array([[0, 1, 3, 2]], dtype=np.uint64), "faces", 7]
    return list(itertools.product(range(len(pts)), range(len(faces)))), pts, faces


def _call(fn, *a, **k):
    try:
        return fn(*a, **k)
    except BaseException as e:  # noqa: B036 — PanicException derives from BaseException
        assert type(e).__name__ != "PanicException", f"Rust panic: {e}"
        assert isinstance(e, (ValueError, TypeError, RuntimeError, OSError)), repr(e)
        return None


def test_generated_bad_inputs_never_panic():
    combos, pts, faces = _bad_inputs()
    made = 0
    for i, j in combos:
        m = _call(subsurf.Mesh, pts[i], faces[j])
        if m is None:
            continue
        made += 1
        for fn in (lambda: subsurf.refine(m, 2), lambda: subsurf.refine(m, 1, limit=True),
                   lambda: subsurf.tessellate(m, "limit", tess=3), lambda: subsurf.tessellate(m, "prep", tess=3),
                   lambda: subsurf.tessellate(m, "refine", level=1), lambda: subsurf.Prep(m).bezier(),
                   lambda: subsurf.LimitSurface(m).tessellate(3), lambda: subsurf.Refiner(m, 1).stencils()):
            _call(fn)
    assert made >= 3  # the valid combinations went through


def test_bad_arguments_never_panic():
    mesh = subsurf.read(SHAPES / "catmark_cube.obj")
    r = subsurf.Refiner(mesh, 1)
    s = subsurf.LimitSurface(mesh)
    cases = [
        lambda: subsurf.refine(mesh, -1), lambda: subsurf.refine(mesh, 99), lambda: subsurf.refine(mesh, 1.5),
        lambda: subsurf.refine(mesh, 1, backend="tpu"), lambda: subsurf.refine("mesh", 1),
        lambda: r.refine(np.zeros((3, 3))), lambda: r.refine(np.zeros((8, 0))), lambda: r.refine("x"),
        lambda: r.limit(np.zeros((2, 3))), lambda: r.mesh(np.zeros((5, 3))),
        lambda: r.refine_uvs(np.zeros((1, 2)), np.zeros(24, dtype=int)),
        lambda: r.refine_uvs(np.zeros((4, 2)), [99] * 24), lambda: r.refine_uvs(np.zeros((4, 2)), [0] * 3),
        lambda: s.evaluate([10**6], [0.5], [0.5]), lambda: s.evaluate([0], [np.nan], [0.5]),
        lambda: s.evaluate([0], [2.0], [0.5]), lambda: s.evaluate([0, 1], [0.5], [0.5]),
        lambda: s.evaluate([-1], [0.5], [0.5]), lambda: s.tessellate(0), lambda: s.tessellate(10**7),
        lambda: s.update(np.zeros((3, 3))), lambda: s.update(np.full((8, 3), np.nan)),
        lambda: subsurf.LimitSurface(mesh, isolation=99), lambda: subsurf.tessellate(mesh, "nope"),
        lambda: subsurf.tessellate(mesh, "limit", tess=1), lambda: subsurf.Prep(subsurf.read(SHAPES / "catmark_tent.obj")),
        lambda: subsurf.Mesh(TRI, QUAD, scheme="loop3"), lambda: subsurf.Mesh(TRI, QUAD, boundary=3),
        lambda: subsurf.Mesh(TRI, QUAD, creases=[[0, 3, 1.0]]), lambda: subsurf.Mesh(TRI, QUAD, creases=[[0, 1, np.nan]]),
        lambda: subsurf.Mesh(TRI, QUAD, creases=[[0, 9]], crease_sharpness=[1.0]),
        lambda: subsurf.Mesh(TRI, QUAD, corners=[[9, 1.0]]), lambda: subsurf.Mesh(TRI, QUAD, holes=[5]),
        lambda: subsurf.Mesh(TRI, QUAD, uvs=np.zeros((2, 2))), lambda: subsurf.Mesh(TRI, QUAD, uv_indices=[0, 1, 2, 3]),
        lambda: subsurf.Mesh(TRI, QUAD, uvs=np.zeros((4, 2)), uv_indices=[0, 1]),
        lambda: subsurf.Mesh(TRI, QUAD, uvs=np.full((4, 2), np.nan)),
        lambda: mesh.write("/nonexistent-dir/x.obj"), lambda: mesh.write("x.unknown"),
        lambda: subsurf.render(mesh, size=(0, 10)), lambda: subsurf.render(mesh, view="up"),
    ]
    for k, c in enumerate(cases):
        try:
            c()
        except BaseException as e:  # noqa: B036
            assert type(e).__name__ != "PanicException", f"case {k}: Rust panic: {e}"
            assert isinstance(e, (ValueError, TypeError, RuntimeError, OSError)), f"case {k}: {e!r}"
        else:
            if k != 10:  # case 10 is valid (one UV for every corner)
                pytest.fail(f"case {k} did not raise")
