"""Round trips through constructors, files and trimesh."""

import os
import numpy as np
import pytest

import subsurf
from conftest import SHAPES


def test_face_layouts_agree():
    pts = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]], dtype=np.float64)
    a = subsurf.Mesh(pts, [[0, 1, 2, 3], [1, 4, 2]])
    b = subsurf.Mesh(pts, (np.array([4, 3]), np.array([0, 1, 2, 3, 1, 4, 2])))
    c = subsurf.Mesh(pts.astype(np.float32), np.array([[0, 1, 2, 3]]))
    assert np.array_equal(a.face_counts, b.face_counts) and np.array_equal(a.face_indices, b.face_indices)
    # float64 in stays float64 (as given); float32 in stays float32.
    assert a.positions.dtype == np.float64 and np.array_equal(a.positions, pts)
    assert c.positions.dtype == np.float32 and np.array_equal(c.positions, pts.astype(np.float32))
    assert c.num_faces == 1 and c.num_vertices == 5
    assert a.faces() == [[0, 1, 2, 3], [1, 4, 2]]


def test_crease_forms_agree():
    m = subsurf.read(SHAPES / "catmark_cube_creases1.obj")
    pairs, sharp = m.creases
    a = subsurf.Mesh(m.positions, (m.face_counts, m.face_indices), creases=pairs, crease_sharpness=sharp)
    b = subsurf.Mesh(m.positions, (m.face_counts, m.face_indices),
                     creases=np.column_stack([pairs, sharp.astype(np.float64)]))
    assert np.array_equal(subsurf.refine(a, 2).positions, subsurf.refine(m, 2).positions)
    assert np.array_equal(subsurf.refine(b, 2).positions, subsurf.refine(m, 2).positions)


@pytest.mark.parametrize("ext", ["obj", "ply", "usda"])
@pytest.mark.parametrize("name", ["catmark_cube_creases1", "catmark_hole_test2", "catmark_fvar_bound1"])
def test_file_round_trip(tmp_path, ext, name):
    m = subsurf.read(SHAPES / f"{name}.obj")
    p = tmp_path / f"m.{ext}"
    # By default every format leaves the hole faces out (viewers ignoring the tags would
    # draw them closed), every vertex kept.
    m.write(p)
    back = subsurf.read(p)
    assert np.array_equal(back.positions, m.positions)
    holes = set(m.holes.tolist())
    assert back.faces() == [f for k, f in enumerate(m.faces()) if k not in holes]
    assert len(back.holes) == 0
    assert back.faces() == m.without_holes().faces()
    if ext == "ply":  # PLY cannot tag holes: keeping them is refused when there are any
        if holes:
            with pytest.raises(subsurf.SubsurfError, match="cannot tag hole faces"):
                m.write(p, keep_holes=True)
        return
    # keep_holes: every face, holes tagged, tags and UVs kept: the same surface again.
    m.write(p, keep_holes=True)
    back = subsurf.read(p)
    assert np.array_equal(back.face_indices, m.face_indices)
    assert np.array_equal(back.creases[1], m.creases[1])
    assert np.array_equal(back.holes, m.holes)
    assert np.array_equal(subsurf.refine(back, 2).positions, subsurf.refine(m, 2).positions)


def test_trimesh_leaves_holes_out():
    pytest.importorskip("trimesh")
    m = subsurf.refine(subsurf.read(SHAPES / "catmark_hole_test1.obj"), 1)
    assert len(m.holes) > 0
    t = m.to_trimesh()
    drawn = m.num_faces - len(m.holes)
    assert len(t.faces) == 2 * drawn  # quads after one step, two triangles each
    assert len(t.vertices) == m.num_vertices


def test_glb_is_written(tmp_path):
    m = subsurf.refine(subsurf.read(SHAPES / "catmark_cube.obj"), 1)
    m.write(tmp_path / "m.glb")
    assert (tmp_path / "m.glb").read_bytes()[:4] == b"glTF"


def test_trimesh_round_trip():
    trimesh = pytest.importorskip("trimesh")
    box = trimesh.creation.box()
    m = subsurf.Mesh.from_trimesh(box)
    assert m.num_vertices == len(box.vertices) and m.num_faces == len(box.faces)
    r = subsurf.refine(m, 2)
    t = r.to_trimesh()
    assert isinstance(t, trimesh.Trimesh)
    assert len(t.faces) == r.num_faces * 2  # quads split in two
    assert np.allclose(t.vertices, r.positions)
    back = subsurf.Mesh.from_trimesh(t)
    assert np.array_equal(back.positions, r.positions)
    # A closed surface stays closed; the subdivided box shrinks inside the box.
    assert t.is_watertight and np.all(np.abs(t.vertices) <= 0.5 + 1e-6)


def test_outputs_own_their_buffers_and_inputs_are_not_copied():
    m = subsurf.read(SHAPES / "catmark_cube.obj")
    p = subsurf.refine(m, 2).positions
    assert p.flags.c_contiguous and p.flags.writeable
    # The array views the Rust-allocated buffer (the numpy crate's owner object as base),
    # not a numpy copy of it.
    assert p.base is not None and not isinstance(p.base, np.ndarray)
    assert type(p.base).__name__ == "PySliceContainer"
    # Inputs already float32 and C-contiguous are passed through without a copy.
    x = np.ascontiguousarray(m.positions)
    assert np.asarray(x, dtype=np.float32) is x


def test_usd_round_trip_and_errors(tmp_path):
    # Written by subsurf, read back by subsurf and by Pixar's USD library with the same values.
    if not os.environ.get("CI"):
        pytest.importorskip("pxr")
    from pxr import Usd, UsdGeom

    m = subsurf.read(SHAPES / "catmark_cube_creases1.obj")
    p = tmp_path / "cube.usda"
    m.write(p)
    back = subsurf.read(p)
    assert np.array_equal(back.positions, m.positions)
    assert np.array_equal(back.face_indices, m.face_indices)
    assert np.array_equal(subsurf.refine(back, 2).positions, subsurf.refine(m, 2).positions)
    stage = Usd.Stage.Open(str(p))
    mesh = [UsdGeom.Mesh(x) for x in stage.Traverse() if x.IsA(UsdGeom.Mesh)][0]
    assert np.allclose(np.array(mesh.GetPointsAttr().Get()), m.positions)
    text = p.read_text().replace("faceVertexIndices = [0,", "faceVertexIndices = [99,", 1)
    text = text.replace("faceVertexIndices = [0, ", "faceVertexIndices = [99, ", 1)
    bad = tmp_path / "bad.usda"
    bad.write_text(text)
    assert text != p.read_text()
    with pytest.raises(subsurf.ParseError) as e:
        subsurf.read(bad)
    assert e.value.path == str(bad) and e.value.attribute == "faceVertexIndices"
    assert e.value.prim is not None and e.value.prim.startswith("/")
