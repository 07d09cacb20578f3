"""`tessellate(..., tolerance= / max_edge_length= / edge_rates=)`: the adaptive per-edge
rates of the library's one surface call, against the files `subsurf limit` writes with the
same flags (bit for bit), watertight, and its bad input as ValueErrors naming the value."""

import numpy as np
import pytest

import subsurf
from conftest import SHAPES


def _cli_mesh(cli, tmp_path, src, *flags):
    out = tmp_path / "cli.ply"
    cli("limit", src, *flags, "-o", out)
    return subsurf.read(out)


@pytest.mark.parametrize("name", ["catmark_cube_creases1", "catmark_pole8", "catmark_hole_test2"])
@pytest.mark.parametrize("flag,kw,value", [("--tolerance", "tolerance", 2e-3),
                                           ("--max-edge-length", "max_edge_length", 0.3)])
def test_adaptive_policy_matches_cli(cli, tmp_path, name, flag, kw, value):
    src = SHAPES / f"{name}.obj"
    ref = _cli_mesh(cli, tmp_path, src, flag, value)
    p, n, t = subsurf.tessellate(subsurf.read(src), "limit", **{kw: value})
    assert np.array_equal(ref.positions, p)
    assert np.array_equal(ref.face_indices.reshape(-1, 3), t)
    assert np.allclose(np.linalg.norm(n, axis=1), 1, atol=1e-4)


def _open_edges(t):
    e = np.sort(np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return int((counts == 1).sum())


def test_edge_rates_match_cli_and_stay_watertight(cli, tmp_path):
    src = SHAPES / "catmark_cube.obj"
    mesh = subsurf.read(src)
    rows = [[0, 1, 7], [1, 3, 1], [2, 3, 12]]
    f = tmp_path / "rates.txt"
    f.write_text("".join(f"{a} {b} {r}\n" for a, b, r in rows))
    ref = _cli_mesh(cli, tmp_path, src, "--tess", 5, "--edge-rates", f)
    p, _, t = subsurf.tessellate(mesh, "limit", tess=5, edge_rates=rows)
    assert np.array_equal(ref.positions, p)
    assert np.array_equal(ref.face_indices.reshape(-1, 3), t)
    # A closed cube stays closed with any mix of rates.
    assert _open_edges(t) == 0
    # The uniform surface differs: the rates were applied.
    assert len(subsurf.tessellate(mesh, "limit", tess=5)[0]) != len(p)


def test_bad_adaptive_arguments_are_value_errors():
    mesh = subsurf.read(SHAPES / "catmark_cube.obj")
    for call, words in [
        (lambda: subsurf.tessellate(mesh, tolerance=1e-3, max_edge_length=1.0), "at most one"),
        (lambda: subsurf.tessellate(mesh, tolerance=-1.0), "tolerance"),
        (lambda: subsurf.tessellate(mesh, tolerance=float("nan")), "tolerance"),
        (lambda: subsurf.tessellate(mesh, max_edge_length=0.0), "maximum edge length"),
        (lambda: subsurf.tessellate(mesh, edge_rates=[[0, 99, 3]]), "edge_rates[0]"),
        (lambda: subsurf.tessellate(mesh, edge_rates=[[0, 1, 3], [0, 3, 3]]), "edge_rates[1]"),
        (lambda: subsurf.tessellate(mesh, edge_rates=[[0, 1, 3], [0, 1, 0]]), "edge_rates[1]"),
        (lambda: subsurf.tessellate(mesh, edge_rates=[[0, 1, 5000]]), "4096"),
        (lambda: subsurf.tessellate(mesh, edge_rates=[[0, -1, 3]]), "non-negative"),
        (lambda: subsurf.tessellate(mesh, "refine", level=2, tolerance=1e-3), "method 'limit'"),
    ]:
        with pytest.raises(ValueError) as e:
            call()
        assert words in str(e.value), str(e.value)


@pytest.mark.parametrize("kw,value", [("tolerance", 1e-3), ("max_edge_length", 0.05)])
def test_gpu_rates_give_the_cpu_mesh(kw, value):
    # backend="gpu": the rate curves measured by the GPU's kernels, the tessellation evaluated
    # on the CPU; the pawn's needs fall nowhere near an integer, so the rates and mesh agree.
    mesh = subsurf.read(SHAPES / "catmark_pawn.obj")
    cpu = subsurf.tessellate(mesh, "limit", **{kw: value})
    try:
        gpu = subsurf.tessellate(mesh, "limit", backend="gpu", **{kw: value})
    except subsurf.GpuError as e:
        pytest.skip(f"SKIPPED: no GPU adapter ({e})")
    for a, b in zip(cpu, gpu):
        assert np.array_equal(a, b)


def test_tolerance_chooses_the_isolation_and_refuses_the_unreachable(cli, tmp_path):
    """On the pawn (a pole of high valence) a tolerance isolates the pole deeper, the same
    way from Python as from the command line; one its end caps cannot meet at the deepest
    level is a ValueError naming the face."""
    src = SHAPES / "catmark_pawn.obj"
    pawn = subsurf.read(src)
    ref = _cli_mesh(cli, tmp_path, src, "--tolerance", 1e-3)
    p, _, t = subsurf.tessellate(pawn, tolerance=1e-3)
    assert np.array_equal(ref.positions, p)
    assert np.array_equal(ref.face_indices.reshape(-1, 3), t)
    with pytest.raises(ValueError) as e:
        subsurf.tessellate(pawn, tolerance=1e-4)
    assert "out of reach" in str(e.value) and "base face 5" in str(e.value), str(e.value)
