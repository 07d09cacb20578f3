"""float64 in stays float64: Mesh positions as given, refine and Refiner.refine in double
precision, against the float32 path and the CLI's `refine --f64` output."""

import numpy as np

import subsurf


def _wide_cube():
    """A cube a million units from the origin, with coordinates float32 cannot hold."""
    p = np.array([[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)])
    p = p * np.pi + np.array([1e6, -3e5, 1.0 / 3.0])
    faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    return p, faces


def test_float64_positions_are_kept_as_given():
    p, faces = _wide_cube()
    mesh = subsurf.Mesh(p, faces)
    assert mesh.positions.dtype == np.float64
    assert np.array_equal(mesh.positions, p)
    m32 = subsurf.Mesh(p.astype(np.float32), faces)
    assert m32.positions.dtype == np.float32


def test_refine_in_float64_against_float32_and_the_cli(cli, tmp_path):
    p, faces = _wide_cube()
    mesh = subsurf.Mesh(p, faces)
    out = subsurf.refine(mesh, 2)
    assert out.positions.dtype == np.float64
    r = subsurf.Refiner(mesh, 2)
    via_refiner = r.refine(p)
    assert via_refiner.dtype == np.float64
    # The same masks and sums in the same order: bit for bit.
    assert np.array_equal(via_refiner, out.positions)
    # The float32 path rounds a million-unit cube by up to 3e-2: double precision does not.
    out32 = subsurf.refine(subsurf.Mesh(p.astype(np.float32), faces), 2)
    gap = np.abs(out32.positions.astype(np.float64) - out.positions).max()
    assert 1e-3 < gap < 0.2, gap
    # Translating back (exact for these magnitudes) gives the refinement of the cube near
    # the origin to float64 rounding.
    shift = np.array([1e6, -3e5, 1.0 / 3.0])
    near = subsurf.refine(subsurf.Mesh(p - shift, faces), 2).positions
    assert np.abs(out.positions - shift - near).max() < 1e-9
    # The CLI's refine --f64 of the same file writes the same values: both OBJ files hold the
    # shortest digits of the same float64 values (a file read back is float32 to Python, so
    # the text is compared).
    src = tmp_path / "wide.obj"
    mesh.write(str(src))
    cli_out, py_out = tmp_path / "cli.obj", tmp_path / "py.obj"
    cli("refine", src, "--level", 2, "-o", cli_out, "--f64", "--keep-holes")
    out.write(str(py_out), keep_holes=True)
    vertices = lambda f: [l for l in f.read_text().splitlines() if l.startswith("v ")]
    assert vertices(cli_out) == vertices(py_out)
    assert len(vertices(py_out)) == len(out.positions)
    assert float(vertices(py_out)[0].split()[1]) == out.positions[0][0]
    # float32 data through the same refiner stays float32.
    assert r.refine(p.astype(np.float32)).dtype == np.float32


def _eval_rows(path):
    """The CLI's `eval` output: (faces, u, v, (n, 9) positions and derivatives)."""
    rows = np.array([[float(x) for x in l.split()] for l in path.read_text().splitlines()])
    return rows[:, 0].astype(np.uint32), rows[:, 1], rows[:, 2], rows[:, 3:]


def _octahedron():
    """Triangles far from the origin, coordinates float32 cannot hold."""
    p = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], float)
    p = p * np.e + np.array([2e6, 1.0 / 3.0, -7e5])
    tris = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
    return p, tris


def test_limit_surface_in_float64_equals_the_clis_eval_f64(cli, tmp_path):
    for name, (p, faces), scheme in [("cube", _wide_cube(), "catmark"),
                                     ("octahedron", _octahedron(), "loop")]:
        mesh = subsurf.Mesh(p, faces, scheme=scheme)
        s = subsurf.LimitSurface(mesh, isolation=3)
        assert s.f64
        src, out = tmp_path / f"{name}.obj", tmp_path / f"{name}.txt"
        mesh.write(str(src))
        cli("eval", src, "--scheme", scheme, "--tess", 3, "--isolation", 3, "--f64", "-o", out)
        f, u, v, want = _eval_rows(out)
        pos, du, dv = s.evaluate(f, u, v)
        assert pos.dtype == du.dtype == np.float64
        # The same double-precision surface from the same float64 values: digit for digit
        # (the CLI prints every digit of its float64 results).
        assert np.array_equal(np.hstack([pos, du, dv]), want), name
        # The float32 surface of the same positions is off by their float32 rounding.
        s32 = subsurf.LimitSurface(subsurf.Mesh(p.astype(np.float32), faces, scheme=scheme),
                                   isolation=3)
        assert not s32.f64
        gap = np.abs(s32.evaluate(f, u, v)[0].astype(np.float64) - pos).max()
        assert 1e-3 < gap < 0.5, (name, gap)


def test_float64_tessellation_and_update_stay_float64():
    for (p, faces), scheme in [(_wide_cube(), "catmark"), (_octahedron(), "loop")]:
        s = subsurf.LimitSurface(subsurf.Mesh(p, faces, scheme=scheme), isolation=3)
        pos, normals, tris = s.tessellate(4)
        assert pos.dtype == np.float64 and normals.dtype == np.float64
        # The same surface translated to the origin, in float64: the shift comes back to
        # float64 rounding of a million-unit coordinate.
        shift = p.mean(axis=0)
        near = subsurf.LimitSurface(subsurf.Mesh(p - shift, faces, scheme=scheme), isolation=3)
        npos, _, ntris = near.tessellate(4)
        assert np.array_equal(tris, ntris)
        assert np.abs(pos - shift - npos).max() < 1e-8, scheme
        # update in float64: moving every control point by (1/3, 0, 0) moves the surface by
        # that, unrounded to float32.
        s.update(p + np.array([1.0 / 3.0, 0.0, 0.0]))
        moved, _, _ = s.tessellate(4)
        assert np.abs(moved - pos - np.array([1.0 / 3.0, 0.0, 0.0])).max() < 1e-8, scheme
