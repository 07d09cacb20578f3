#!/usr/bin/env python3
"""Refine or tessellate every mesh under a folder (or a list of OBJ/PLY files) on a
dask.distributed cluster, writing each result next to a summary table.

    python batch.py MESHES_OR_FOLDERS... -o OUT [--method refine|limit|prep]
                    [--level 2] [--tess 9]
                    [--workers 2] [--scheduler tcp://host:8786]

Without --scheduler a LocalCluster with --workers single-threaded worker processes runs
on this machine; with it, the same tasks go to an existing cluster (every worker needs
`pip install subsurf` and read access to the input paths, and OUT must be shared storage).
A bad file is reported in the table (error column) and does not stop the batch.
"""

from __future__ import annotations

import argparse
import csv
import os
import sys
import time
from pathlib import Path
from typing import Dict, List, Optional

MESH_EXTS = {".obj", ".ply"}


def find_meshes(inputs: List[str]) -> List[Path]:
    """Files given, and mesh files under the folders given (sorted)."""
    out: List[Path] = []
    for s in inputs:
        p = Path(s)
        if p.is_dir():
            out.extend(sorted(q for q in p.rglob("*") if q.suffix.lower() in MESH_EXTS))
        else:
            out.append(p)
    return out


def process(path: str, out_path: str, method: str, level: int, tess: int) -> Dict[str, object]:
    """One task: read, refine to ``level`` or tessellate with ``tess`` samples per side,
    write. Never raises: errors land in the row."""
    import subsurf

    row: Dict[str, object] = {"file": path, "output": out_path, "faces_in": "", "faces_out": "",
                              "seconds": "", "error": ""}
    t0 = time.perf_counter()
    try:
        mesh = subsurf.read(path)
        row["faces_in"] = mesh.num_faces
        if method == "refine":
            out = subsurf.refine(mesh, level)
            out.write(out_path)  # hole faces left out, as a viewer should see the mesh
            row["faces_out"] = out.num_faces - len(out.holes)
        else:
            p, normals, tris = subsurf.tessellate(mesh, method, tess=tess)
            subsurf.Mesh(p, tris).write(out_path, normals=normals)
            row["faces_out"] = len(tris)
    except Exception as e:  # reported, not raised: one bad file does not stop the batch
        row["error"] = f"{type(e).__name__}: {e}"
    row["seconds"] = round(time.perf_counter() - t0, 4)
    return row


def output_name(src: Path, root_out: Path, index: int, method: str, ext: str) -> Path:
    return root_out / f"{index:05d}_{src.stem}.{method}{ext}"


def run(inputs: List[str], out_dir: str, method: str = "refine", level: int = 2, tess: int = 9,
        workers: int = 2, scheduler: Optional[str] = None,
        ext: str = ".obj") -> List[Dict[str, object]]:
    """Runs the batch and writes OUT/summary.csv; returns the rows in input order."""
    from dask.distributed import Client, LocalCluster

    # Ship `process` by value: workers then need subsurf, not this script on their path
    # (it may be loaded from a file, as the tests do, rather than imported).
    try:
        import cloudpickle

        cloudpickle.register_pickle_by_value(sys.modules[process.__module__])
    except (ImportError, KeyError, ValueError):
        pass
    files = find_meshes(inputs)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    cluster = None
    if scheduler:
        client = Client(scheduler)
    else:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    try:
        futures = [client.submit(process, str(f), str(output_name(f, out, i, method, ext)), method,
                                 level, tess, pure=False)
                   for i, f in enumerate(files)]
        rows = client.gather(futures)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    with open(out / "summary.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=["file", "output", "faces_in", "faces_out", "seconds", "error"])
        w.writeheader()
        w.writerows(rows)
    return rows


def main(argv: Optional[List[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("inputs", nargs="+", help="mesh files or folders")
    ap.add_argument("-o", "--output", required=True, help="output folder (summary.csv and results)")
    # The names of `subsurf refine|limit|prep` (docs/vocabulary.md).
    ap.add_argument("--method", choices=["refine", "limit", "prep", "prep-bicubic"], default="refine")
    ap.add_argument("--level", type=int, default=2, help="refinement level (method refine)")
    ap.add_argument("--tess", type=int, default=9, help="samples per side (the other methods)")
    ap.add_argument("--workers", type=int, default=max(1, (os.cpu_count() or 2)), help="LocalCluster workers")
    ap.add_argument("--scheduler", help="address of an existing dask scheduler")
    ap.add_argument("--format", choices=["obj", "ply", "glb"], default="obj")
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    rows = run(a.inputs, a.output, a.method, a.level, a.tess, a.workers, a.scheduler, "." + a.format)
    bad = sum(1 for r in rows if r["error"])
    print(f"{len(rows)} files, {bad} errors, {time.perf_counter() - t0:.2f} s -> {a.output}/summary.csv")
    return 1 if bad == len(rows) and rows else 0


if __name__ == "__main__":
    sys.exit(main())
