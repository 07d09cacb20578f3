"""render() returns an RGBA image of the surface (skipped without a GPU adapter)."""

import numpy as np
import pytest

import subsurf
from conftest import SHAPES


def test_render_shows_the_surface(tmp_path):
    m = subsurf.read(SHAPES / "catmark_cube.obj")
    try:
        img = subsurf.render(m, size=(64, 48), method="limit", tess=5, output=tmp_path / "c.png")
    except subsurf.GpuError as e:
        pytest.skip(f"SKIPPED: no GPU adapter ({e})")
    assert img.shape == (48, 64, 4) and img.dtype == np.uint8
    assert tuple(img[0, 0]) == (255, 255, 255, 255)  # background in the corner
    assert tuple(img[24, 32]) != (255, 255, 255, 255)  # surface in the centre
    png = (tmp_path / "c.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    # IHDR: 64 x 48, 8-bit RGBA; encoded by the render crate as the CLI's files are (sRGB tagged).
    assert png[12:16] == b"IHDR" and png[16:24] == (64).to_bytes(4, "big") + (48).to_bytes(4, "big")
    assert png[24:26] == bytes([8, 6]) and b"sRGB" in png[:64]


def test_a_headless_render_prints_no_error_line():
    """Without a display server, Mesa's device-select layer would print a Wayland
    `error: XDG_RUNTIME_DIR ...` line on every GPU start; the package switches it off at import."""
    import os
    import subprocess
    import sys

    env = {k: v for k, v in os.environ.items()
           if k not in ("XDG_RUNTIME_DIR", "WAYLAND_DISPLAY", "DISPLAY", "NODEVICE_SELECT")}
    code = ("import subsurf\n"
            f"m = subsurf.read({str(SHAPES / 'catmark_cube.obj')!r})\n"
            "try:\n"
            "    subsurf.render(m, size=(32, 24), method='refine', level=1)\n"
            "except subsurf.GpuError:\n"
            "    print('no adapter')\n")
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    if "no adapter" in r.stdout:
        pytest.skip("SKIPPED: no GPU adapter")
    assert not any(line.startswith("error:") for line in r.stderr.splitlines()), r.stderr
