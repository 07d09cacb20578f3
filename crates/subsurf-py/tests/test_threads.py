"""The GIL is released during the work: a refinement in one thread leaves other threads'
Python code running; objects are shared safely between threads."""

import threading
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import subsurf
from conftest import CAR


def test_refinement_does_not_block_python_threads():
    car = subsurf.read(CAR)
    subsurf.refine(car, 1)  # warm up
    done = threading.Event()
    ticks = [0]

    def count():
        while not done.is_set():
            ticks[0] += 1

    t0 = time.perf_counter()
    subsurf.refine(car, 4)
    alone = time.perf_counter() - t0
    th = threading.Thread(target=count)
    th.start()
    time.sleep(0.02)
    before = ticks[0]
    t0 = time.perf_counter()
    subsurf.refine(car, 4)
    during = ticks[0] - before
    elapsed = time.perf_counter() - t0
    done.set()
    th.join()
    # With the GIL held, the counter would advance by at most a few switch intervals'
    # worth; released, it runs for the whole call.
    per_s = during / elapsed
    assert during > 1000 and elapsed > 0.5 * alone, (during, elapsed, alone)
    assert per_s > 1e4


def test_shared_objects_across_threads_give_identical_results():
    car = subsurf.read(CAR)
    r = subsurf.Refiner(car, 2)
    s = subsurf.LimitSurface(car)
    ref_p = r.refine(car.positions)
    ref_t = s.tessellate(3)[0]
    rng = np.random.default_rng(0)
    frames = [car.positions + rng.normal(0, 0.01, car.positions.shape).astype(np.float32) for _ in range(8)]
    serial = [r.refine(f) for f in frames]

    def job(k):
        out = r.refine(frames[k % 8])
        assert np.array_equal(out, serial[k % 8])
        assert np.array_equal(s.tessellate(3)[0], ref_t)
        assert np.array_equal(subsurf.refine(car, 2).positions, ref_p)
        return k

    with ThreadPoolExecutor(4) as ex:
        assert sorted(ex.map(job, range(16))) == list(range(16))
