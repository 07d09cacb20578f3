"""render() returns an RGBA image of the surface (skipped without a GPU adapter)."""

import numpy as np
import pytest

import subsurf
from conftest import SHAPES


def test_render_shows_the_surface(tmp_path):
    m = subsurf.read(SHAPES / "catmark_cube.obj")
    try:
        img = subsurf.render(m, size=(64, 48), method="limit", n=5, path=tmp_path / "c.png")
    except subsurf.GpuError as e:
        pytest.skip(f"SKIPPED: no GPU adapter ({e})")
    assert img.shape == (48, 64, 4) and img.dtype == np.uint8
    assert tuple(img[0, 0]) == (255, 255, 255, 255)  # background in the corner
    assert tuple(img[24, 32]) != (255, 255, 255, 255)  # surface in the centre
    assert (tmp_path / "c.png").read_bytes()[:4] == b"\x89PNG"
