"""Every function against the Rust library's own results, through files the CLI writes
(the CLI is conformance-tested against OpenSubdiv 3.5 on these regression shapes): bit for
bit where the computation is the same."""

import numpy as np
import pytest

import subsurf
from conftest import SHAPE_NAMES, SHAPES


@pytest.mark.parametrize("name", SHAPE_NAMES)
@pytest.mark.parametrize("limit", [False, True])
def test_refine_matches_cli_file(cli, tmp_path, name, limit):
    level = 2
    src = SHAPES / f"{name}.obj"
    cli_out = tmp_path / "cli.obj"
    cli("refine", src, "--level", level, "-o", cli_out, "--keep-holes",
        *(["--limit"] if limit else []))
    mesh = subsurf.read(src)
    py = subsurf.refine(mesh, level, limit=limit)
    back = subsurf.read(cli_out)
    # Without --keep-holes the CLI leaves the hole faces out, as Mesh.write does.
    drawn = tmp_path / "drawn.obj"
    cli("refine", src, "--level", level, "-o", drawn, *(["--limit"] if limit else []))
    assert subsurf.read(drawn).faces() == py.without_holes().faces()
    # Same float32 positions (OBJ round-trips float32 exactly), faces and corner UVs.
    assert np.array_equal(back.positions, py.positions)
    # All faces, holes and the remaining sharpness tagged as in the CLI's OBJ.
    assert np.array_equal(back.face_counts, py.face_counts)
    assert np.array_equal(back.face_indices, py.face_indices)
    assert np.array_equal(back.holes, py.holes)
    for a, b in zip(back.creases + back.corners, py.creases + py.corners):
        assert np.array_equal(a, b)
    if py.uvs is not None:
        assert np.array_equal(back.uvs[back.uv_indices], py.uvs[py.uv_indices])


@pytest.mark.parametrize("name", ["catmark_cube_creases1", "catmark_pole8", "catmark_car"])
def test_limit_tessellation_matches_cli(cli, tmp_path, name):
    src = SHAPES / f"{name}.obj"
    out = tmp_path / "cli.ply"
    cli("limit", src, "--tess", 5, "-o", out)
    ref = subsurf.read(out)
    p, n, t = subsurf.LimitSurface(subsurf.read(src)).tessellate(5)
    assert np.array_equal(ref.positions, p)
    assert np.array_equal(ref.face_indices.reshape(-1, 3), t)
    p2, n2, t2 = subsurf.tessellate(subsurf.read(src), "limit", tess=5)
    assert np.array_equal(p2, p) and np.array_equal(n2, n) and np.array_equal(t2, t)


def test_prep_bezier_matches_cli(cli, tmp_path):
    src = SHAPES / "catmark_torus.obj"
    out = tmp_path / "b.npy"
    cli("prep", src, "--bezier", out)
    ref = np.load(out)
    b = subsurf.Prep(subsurf.read(src)).bezier()
    assert b.dtype == np.float64 and b.shape == ref.shape
    assert np.array_equal(b, ref)


def test_prep_tessellation_matches_cli(cli, tmp_path):
    src = SHAPES / "catmark_torus.obj"
    out = tmp_path / "p.ply"
    cli("prep", src, "--tess", 5, "--f64", "-o", out)
    ref = subsurf.read(out)
    p, n, t = subsurf.Prep(subsurf.read(src)).tessellate(5)
    assert np.array_equal(ref.positions, p.astype(np.float32))
    assert np.array_equal(ref.face_indices.reshape(-1, 3), t)


@pytest.mark.parametrize("name", ["catmark_cube_creases1", "catmark_fvar_bound1", "catmark_car"])
def test_refiner_reuses_tables_bit_for_bit(name):
    mesh = subsurf.read(SHAPES / f"{name}.obj")
    r = subsurf.Refiner(mesh, 3)
    ref = subsurf.refine(mesh, 3)
    p = r.refine(mesh.positions)
    assert np.array_equal(p, ref.positions)
    assert np.array_equal(r.limit(p), subsurf.refine(mesh, 3, limit=True).positions)
    assert np.array_equal(r.mesh(p).face_indices, ref.face_indices)
    # Any width: each column refines as positions do (linear, column by column).
    rng = np.random.default_rng(1)
    w = rng.random((mesh.num_vertices, 7)).astype(np.float32)
    rw = r.refine(w)
    assert rw.shape == (r.num_vertices, 7)
    for k in range(0, 6, 3):
        cols = np.ascontiguousarray(w[:, k:k + 3])
        assert np.allclose(r.refine(cols), rw[:, k:k + 3], atol=1e-6)
    # The composed stencils give the same values (within float32 rounding of the products).
    o, i, wt = r.stencils()
    assert len(o) == r.num_vertices + 1 and o[-1] == len(i) == len(wt)
    rows = np.repeat(np.arange(r.num_vertices), np.diff(o.astype(np.int64)))
    via = np.zeros((r.num_vertices, 3))
    np.add.at(via, rows, wt[:, None].astype(np.float64) * mesh.positions[i].astype(np.float64))
    diag = np.linalg.norm(mesh.positions.max(0) - mesh.positions.min(0))
    assert np.abs(via - p).max() < 1e-5 * diag
    assert np.allclose(np.bincount(rows, weights=wt, minlength=r.num_vertices), 1.0, atol=1e-5)


def test_stencil_matrix_is_the_stencils():
    scipy_sparse = pytest.importorskip("scipy.sparse")
    mesh = subsurf.read(SHAPES / "catmark_cube_creases1.obj")
    r = subsurf.Refiner(mesh, 2)
    m = r.stencil_matrix()
    assert isinstance(m, scipy_sparse.csr_matrix) and m.shape == (r.num_vertices, mesh.num_vertices)
    o, i, wt = r.stencils()
    assert np.array_equal(m.indptr, o) and np.array_equal(m.indices, i) and np.array_equal(m.data, wt)


def test_refined_mesh_refines_on_as_the_level():
    # refine(refine(m, 1), 2) == refine(m, 3) as surfaces (the vertex numbering differs):
    # holes and decayed sharpness carried along, so the same points and the same hole faces.
    def by_position(x):
        x = np.round(np.asarray(x, dtype=np.float64), 4)
        return x[np.lexsort(x.T[::-1])]

    def hole_centroids(m):
        f = m.face_indices.reshape(-1, 4)  # quads after one step
        return by_position(m.positions[f[m.holes]].mean(axis=1))

    for name in ("catmark_hole_test2", "catmark_cube_creases1", "catmark_chaikin1"):
        mesh = subsurf.read(SHAPES / f"{name}.obj")
        a = subsurf.refine(subsurf.refine(mesh, 1), 2)
        b = subsurf.refine(mesh, 3)
        assert a.num_faces == b.num_faces and len(a.holes) == len(b.holes), name
        assert np.allclose(by_position(a.positions), by_position(b.positions), atol=2e-4), name
        assert np.allclose(hole_centroids(a), hole_centroids(b), atol=2e-4), name


def test_refine_uvs_match_refine():
    mesh = subsurf.read(SHAPES / "catmark_fvar_bound1.obj")
    r = subsurf.Refiner(mesh, 2)
    values, idx = r.refine_uvs(mesh.uvs, mesh.uv_indices)
    ref = subsurf.refine(mesh, 2)
    # refine() stores the last level's UV values and per-corner indices: the same values.
    assert np.array_equal(values[idx], ref.uvs[ref.uv_indices])


def test_limit_evaluate_agrees_with_tessellation_and_derivatives():
    mesh = subsurf.read(SHAPES / "catmark_cube_creases1.obj")
    s = subsurf.LimitSurface(mesh)
    n = 5
    p, _, _ = s.tessellate(n)
    # Quad meshes: ptex face f's grid, sample (i, j) at (i/(n-1), j/(n-1)).
    f = np.zeros(n, dtype=np.uint32)
    u = np.linspace(0, 1, n)
    pts, du, dv = s.evaluate(f, u, np.full(n, 0.5))
    assert pts.shape == (n, 3) and du.shape == (n, 3)
    # Central differences of points match du.
    h = 1e-3
    a, _, _ = s.evaluate([0], [0.5 + h], [0.5])
    b, _, _ = s.evaluate([0], [0.5 - h], [0.5])
    c, d1, _ = s.evaluate([0], [0.5], [0.5])
    assert np.allclose((a - b) / (2 * h), d1, rtol=1e-2, atol=1e-3)
    # Tessellation points lie on the surface: each equals some evaluated sample.
    g = np.linspace(0, 1, n, dtype=np.float32)
    uu, vv = np.meshgrid(g, g)
    e, _, _ = s.evaluate(np.zeros(n * n, dtype=np.uint32), uu.ravel(), vv.ravel())
    d = np.linalg.norm(p[None, :, :] - e[:, None, :], axis=2).min(axis=1)
    assert d.max() < 1e-5


def test_update_after_deformation_equals_new_surface():
    mesh = subsurf.read(SHAPES / "catmark_pole8.obj")
    moved = mesh.positions * np.float32(2.0) + np.float32(1.0)
    s = subsurf.LimitSurface(mesh)
    s.update(moved)
    fresh = subsurf.LimitSurface(subsurf.Mesh(moved, (mesh.face_counts, mesh.face_indices)))
    assert np.array_equal(s.tessellate(4)[0], fresh.tessellate(4)[0])


def test_surface_api_methods():
    mesh = subsurf.read(SHAPES / "catmark_cube.obj")
    for method, n in (("refine", 2), ("limit", 5), ("prep", 5), ("prep-bicubic", 5)):
        p, nn, t = subsurf.tessellate(mesh, method, **{"level" if method == "refine" else "tess": n})
        assert p.dtype == np.float32 and t.dtype == np.uint32
        assert t.max() < len(p) and len(nn) == len(p)
        assert np.allclose(np.linalg.norm(nn, axis=1), 1, atol=1e-4)
    # refine: the same vertices as refine()
    p, _, t = subsurf.tessellate(mesh, "refine", level=2)
    assert np.array_equal(p, subsurf.refine(mesh, 2).positions)
    assert len(t) == 2 * subsurf.refine(mesh, 2).num_faces
