"""`LimitSurface` on Loop meshes: the Loop limit surface (box-spline patches and
Gregory-triangle end caps over the base triangles, float64), against the files the CLI writes
from the same library (`subsurf limit`, `subsurf eval --at`), bit for bit, and against its own
derivatives and a fresh build."""

import numpy as np
import pytest

import subsurf
from conftest import SHAPES

LOOP_SHAPES = ["loop_icosahedron", "loop_cube_creases1", "loop_pole8", "loop_triangle_edgecorner"]


def _queries(num_faces, rng, k=40):
    f = rng.integers(0, num_faces, k).astype(np.uint32)
    u = rng.random(k)
    v = rng.random(k) * (1.0 - u)
    # The three corners and an edge midpoint of face 0, where patches meet.
    f = np.concatenate([f, np.zeros(4, dtype=np.uint32)])
    u = np.concatenate([u, [0.0, 1.0, 0.0, 0.5]])
    v = np.concatenate([v, [0.0, 0.0, 1.0, 0.5]])
    return f, u, v


@pytest.mark.parametrize("name", LOOP_SHAPES)
def test_loop_tessellation_matches_cli(cli, tmp_path, name):
    src = SHAPES / f"{name}.obj"
    out = tmp_path / "cli.ply"
    cli("limit", src, "--tess", 5, "-o", out)
    ref = subsurf.read(out)
    s = subsurf.LimitSurface(subsurf.read(src))
    assert s.domain == "triangle"
    p, n, t = s.tessellate(5)
    assert np.array_equal(ref.positions, p)
    assert np.array_equal(ref.face_indices.reshape(-1, 3), t)
    # The surface API builds the same triangles.
    p2, n2, t2 = subsurf.tessellate(subsurf.read(src), "limit", tess=5)
    assert np.array_equal(p2, p) and np.array_equal(n2, n) and np.array_equal(t2, t)


@pytest.mark.parametrize("name", LOOP_SHAPES)
def test_loop_evaluate_matches_cli_eval(cli, tmp_path, name):
    src = SHAPES / f"{name}.obj"
    mesh = subsurf.read(src)
    s = subsurf.LimitSurface(mesh)
    assert s.num_ptex_faces == len(mesh.face_counts)
    f, u, v = _queries(s.num_ptex_faces, np.random.default_rng(7))
    q = tmp_path / "q.txt"
    q.write_text("".join(f"{a} {b!r} {c!r}\n" for a, b, c in zip(f.tolist(), u.tolist(), v.tolist())))
    out = tmp_path / "e.txt"
    cli("eval", src, "--at", q, "-o", out)
    rows = np.array([[float(x) for x in line.split()] for line in out.read_text().splitlines()])
    p, du, dv = s.evaluate(f, u, v)
    assert p.dtype == np.float64 and p.shape == (len(f), 3)
    keep = ~np.isnan(p[:, 0])
    assert keep.sum() == len(rows)
    assert np.array_equal(rows[:, 0], f[keep]) and np.array_equal(rows[:, 1], u[keep])
    assert np.array_equal(rows[:, 3:6], p[keep])
    assert np.array_equal(rows[:, 6:9], du[keep]) and np.array_equal(rows[:, 9:12], dv[keep])


def test_loop_derivatives_are_the_slopes_of_the_points():
    s = subsurf.LimitSurface(subsurf.read(SHAPES / "loop_icosahedron.obj"))
    h = 1e-6
    # Off the sub-triangle seams of isolation 4 (multiples of 1/16 in u, v and u + v), where
    # an end cap meets its neighbour only to within ~1e-8.
    for face, u, v in [(0, 0.3, 0.3), (7, 0.1, 0.6), (19, 0.41, 0.07)]:
        _, du, dv = s.evaluate([face], [u], [v])
        a, _, _ = s.evaluate([face, face], [u + h, u - h], [v, v])
        b, _, _ = s.evaluate([face, face], [u, u], [v + h, v - h])
        assert np.allclose((a[0] - a[1]) / (2 * h), du[0], atol=1e-6)
        assert np.allclose((b[0] - b[1]) / (2 * h), dv[0], atol=1e-6)


def test_loop_update_equals_a_fresh_surface():
    mesh = subsurf.read(SHAPES / "loop_cube_creases1.obj")
    moved = mesh.positions * np.float32(1.5) + np.float32(0.25)
    s = subsurf.LimitSurface(mesh)
    s.update(moved)
    edges, sharpness = mesh.creases
    assert len(edges) > 0
    fresh = subsurf.LimitSurface(subsurf.Mesh(moved, (mesh.face_counts, mesh.face_indices),
                                              scheme="loop", creases=edges,
                                              crease_sharpness=sharpness))
    f, u, v = _queries(s.num_ptex_faces, np.random.default_rng(3))
    assert np.array_equal(s.evaluate(f, u, v)[0], fresh.evaluate(f, u, v)[0])
    assert np.array_equal(s.tessellate(4)[0], fresh.tessellate(4)[0])


def test_catmark_surface_keeps_the_square_domain():
    s = subsurf.LimitSurface(subsurf.read(SHAPES / "catmark_cube.obj"))
    assert s.domain == "square"
    p, _, _ = s.evaluate([0], [1.0], [1.0])
    assert p.dtype == np.float32


def test_loop_queries_off_the_triangle_are_errors():
    s = subsurf.LimitSurface(subsurf.read(SHAPES / "loop_icosahedron.obj"))
    with pytest.raises(ValueError, match="query 1"):
        s.evaluate([0, 0], [0.2, 0.7], [0.2, 0.6])
    with pytest.raises(ValueError, match="20"):
        s.evaluate([20], [0.1], [0.1])
    with pytest.raises(ValueError):
        s.evaluate([0], [np.nan], [0.1])
    with pytest.raises(ValueError):
        s.evaluate([0], [-0.1], [0.1])
