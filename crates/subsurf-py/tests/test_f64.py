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
