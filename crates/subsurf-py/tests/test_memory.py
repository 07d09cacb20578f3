"""2,000 calls of refine on the car grow the process by less than 10 MB."""

import gc
import os

import subsurf
from conftest import CAR


def rss_bytes():
    with open(f"/proc/{os.getpid()}/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def test_refine_does_not_leak():
    car = subsurf.read(CAR)
    for _ in range(50):  # allocator warm-up
        subsurf.refine(car, 1).positions
    gc.collect()
    before = rss_bytes()
    for _ in range(2000):
        m = subsurf.refine(car, 1)
        m.positions, m.face_indices
    del m
    gc.collect()
    grown = rss_bytes() - before
    assert grown < 10 * 2**20, f"grew {grown / 2**20:.1f} MiB"
