"""Shared fixtures: repository paths and the `subsurf` CLI (conformance-tested against
OpenSubdiv 3.5), whose output files the package must reproduce."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
SHAPES = REPO / "testdata" / "shapes"
CAR = REPO / "examples" / "car.obj"
# Regression shapes covering creases, Chaikin, corners, holes, boundaries, non-manifold
# topology, n-gons, smooth triangles, bilinear and UVs; small enough to keep the suite fast.
SHAPE_NAMES = [
    "catmark_cube_creases1", "catmark_chaikin1", "catmark_cube_corner3", "catmark_hole_test2",
    "catmark_edgecorner", "catmark_nonman_edge100", "catmark_pole8", "catmark_smoothtris0",
    "catmark_fvar_bound1", "catmark_pyramid_creases2", "catmark_torus_creases0",
    "catmark_xord_boundary", "bilinear_nonquads1", "catmark_car",
    "loop_pole8",
]


if os.environ.get("SUBSURF_EXPECT_INSTALLED"):
    # CI runs the suite against the wheel installed into a fresh virtual environment:
    # `subsurf` must come from that environment's site packages, not from the source tree or
    # an earlier install elsewhere.
    import sys

    import subsurf as _installed

    _at = Path(_installed.__file__).resolve()
    if Path(sys.prefix).resolve() not in _at.parents or "site-packages" not in _at.parts:
        raise RuntimeError(f"subsurf imported from {_at}, not from the wheel in {sys.prefix}")


def cli_path():
    env = os.environ.get("SUBSURF_CLI")
    if env:
        return env
    for p in (REPO / "target" / "release" / "subsurf", REPO / "target" / "debug" / "subsurf"):
        if p.exists():
            return str(p)
    return shutil.which("subsurf")


@pytest.fixture(scope="session")
def cli():
    exe = cli_path()
    if exe is None:
        if os.environ.get("CI"):
            pytest.fail("the subsurf CLI is needed (cargo build -p subsurf-cli, or SUBSURF_CLI)")
        pytest.skip("SKIPPED: no subsurf CLI binary (cargo build -p subsurf-cli)")

    def run(*args):
        r = subprocess.run([exe, "--quiet", *map(str, args)], capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        return r

    return run
