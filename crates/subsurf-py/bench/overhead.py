#!/usr/bin/env python3
"""Python overhead against the Rust calls: `refine(car, 3)` and `Refiner.refine` per frame.

    python crates/subsurf-py/bench/overhead.py [--runs 11] [--rounds 5] [--level 3]

The Rust side is `crates/subsurf/examples/perf/surface_timing.rs` (built here with
`cargo build --release -p subsurf --example surface_timing` unless --rust names a binary),
which times the very calls the package makes (`subsurf::surface::refine_mesh` and
`Refiner::refine_positions`) in-process. Rounds alternate Python and Rust; each round takes the
median of --runs runs; the table shows the median over rounds and the ratio Python / Rust.

Wall times on a busy two-core machine move by more than the overhead itself, so
`--instructions` also counts instructions under valgrind's callgrind (one thread, both sides):
each call's count is the difference between a run of K and of 4K calls, divided by 3K, so
start-up, file reading and table building cancel out.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
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


def instructions(cmd):
    """Instructions executed by `cmd` (all threads) under callgrind."""
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "cg.out")
        env = dict(os.environ, RAYON_NUM_THREADS="1")
        subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}"] + cmd,
                       capture_output=True, check=True, env=env)
        total = 0
        for f in os.listdir(d):
            for line in open(os.path.join(d, f)):
                if line.startswith("totals:"):
                    total += int(line.split()[1])
        return total


PY_LOOP = """
import sys, subsurf
m = subsurf.read(sys.argv[1]); level = int(sys.argv[2]); r = subsurf.Refiner(m, level); p = m.points
subsurf.refine(m, level); r.refine(p)
for _ in range(int(sys.argv[3])):
    subsurf.refine(m, level) if sys.argv[4] == "refine" else r.refine(p)
"""


def per_call(make, k):
    return (instructions(make(4 * k)) - instructions(make(k))) / (3 * k)


def count_instructions(a, rust):
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as f:
        f.write(PY_LOOP)
    py = os.path.realpath(sys.executable)
    print(f"instructions per call (callgrind, one thread):")
    print(f"{'call':28} {'python':>14} {'rust':>14} {'python/rust':>12}")
    for mode, k in (("refine", 2), ("frame", 10)):
        p = per_call(lambda n: [py, f.name, a.mesh, str(a.level), str(n), mode], k)
        q = per_call(lambda n: [rust, a.mesh, str(a.level), str(n), mode], k)
        print(f"{mode:28} {p:14.0f} {q:14.0f} {p / q:11.4f}x")
    os.unlink(f.name)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=11)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--level", type=int, default=3)
    ap.add_argument("--mesh", default=str(REPO / "examples" / "car.obj"))
    ap.add_argument("--rust", default=None, help="a built surface_timing binary")
    ap.add_argument("--instructions", action="store_true", help="also count instructions (valgrind)")
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
    if a.instructions:
        count_instructions(a, rust)


if __name__ == "__main__":
    main()
