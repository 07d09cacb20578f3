#!/usr/bin/env python3
"""Python overhead against the Rust calls: `refine(car, 3)` and `Refiner.refine` per frame.

    python bench/overhead.py [--runs 11] [--cli target/release/subsurf]

The Rust side is `subsurf bench examples/car.obj --level 3` (medians of topology+stencils
and positions, in-process); the Python side times the same work through the package, median
of --runs runs each. Prints both and the ratio.
"""

import argparse
import re
import statistics
import subprocess
import time
from pathlib import Path

import numpy as np

import subsurf

REPO = Path(__file__).resolve().parents[3]


def median_time(fn, runs):
    ts = []
    for _ in range(runs):
        t0 = time.perf_counter()
        fn()
        ts.append(time.perf_counter() - t0)
    return statistics.median(ts)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=11)
    ap.add_argument("--level", type=int, default=3)
    ap.add_argument("--cli", default=str(REPO / "target" / "release" / "subsurf"))
    a = ap.parse_args()
    car = subsurf.read(REPO / "examples" / "car.obj")
    pts = car.points
    r = subsurf.Refiner(car, a.level)
    subsurf.refine(car, a.level)
    r.refine(pts)
    py_refine = median_time(lambda: subsurf.refine(car, a.level), a.runs)
    py_frame = median_time(lambda: r.refine(pts), a.runs)
    print(f"python refine(car, {a.level}):        {py_refine * 1e3:8.2f} ms (median of {a.runs})")
    print(f"python Refiner.refine per frame:  {py_frame * 1e3:8.2f} ms")
    if Path(a.cli).exists():
        out = subprocess.run([a.cli, "bench", str(REPO / "examples" / "car.obj"), "--level", str(a.level)],
                             capture_output=True, text=True)
        print("rust (subsurf bench):\n" + out.stdout + out.stderr)
    else:
        print(f"(no CLI at {a.cli}: cargo build --release -p subsurf-cli for the Rust figures)")


if __name__ == "__main__":
    main()
