#!/usr/bin/env python3
"""Python overhead against the Rust calls: `refine(car, 3)` and `Refiner.refine` per frame.

    python crates/subsurf-py/bench/overhead.py [--runs 11] [--rounds 5] [--level 3]

The Rust side is `crates/subsurf/examples/surface_timing.rs` (built here with
`cargo build --release -p subsurf --example surface_timing` unless --rust names a binary),
which times the very calls the package makes (`subsurf::surface::refine_mesh` and
`Refiner::refine_positions`) in-process. Rounds alternate Python and Rust; each round takes the
median of --runs runs; the table shows the median over rounds and the ratio Python / Rust.
"""

import argparse
import json
import statistics
import subprocess
import time
from pathlib import Path

import subsurf

REPO = Path(__file__).resolve().parents[3]


def median_ms(fn, runs):
    ts = []
    for _ in range(runs):
        t0 = time.perf_counter()
        fn()
        ts.append((time.perf_counter() - t0) * 1e3)
    return statistics.median(ts)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=11)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--level", type=int, default=3)
    ap.add_argument("--mesh", default=str(REPO / "examples" / "car.obj"))
    ap.add_argument("--rust", default=None, help="a built surface_timing binary")
    a = ap.parse_args()
    rust = a.rust
    if rust is None:
        subprocess.run(["cargo", "build", "--release", "-q", "-p", "subsurf", "--example", "surface_timing"],
                       cwd=REPO, check=True)
        rust = str(REPO / "target" / "release" / "examples" / "surface_timing")
    mesh = subsurf.read(a.mesh)
    r = subsurf.Refiner(mesh, a.level)
    pts = mesh.points
    subsurf.refine(mesh, a.level)
    r.refine(pts)
    py_ref, py_frame, rs_ref, rs_frame = [], [], [], []
    for _ in range(a.rounds):
        py_ref.append(median_ms(lambda: subsurf.refine(mesh, a.level), a.runs))
        py_frame.append(median_ms(lambda: r.refine(pts), a.runs))
        out = subprocess.run([rust, a.mesh, str(a.level), str(a.runs)], capture_output=True, text=True, check=True)
        j = json.loads(out.stdout.strip().splitlines()[-1])
        rs_ref.append(j["refine_ms"])
        rs_frame.append(j["frame_ms"])
    rows = [("refine(mesh, %d)" % a.level, py_ref, rs_ref), ("Refiner.refine per frame", py_frame, rs_frame)]
    print(f"{Path(a.mesh).name}, level {a.level}: medians of {a.runs} runs, median over {a.rounds} alternating rounds")
    print(f"{'call':28} {'python ms':>10} {'rust ms':>10} {'python/rust':>12}")
    for name, p, q in rows:
        mp, mq = statistics.median(p), statistics.median(q)
        print(f"{name:28} {mp:10.3f} {mq:10.3f} {mp / mq:11.3f}x")


if __name__ == "__main__":
    main()
