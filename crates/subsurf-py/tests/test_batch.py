"""examples/python/batch.py on a 2-worker LocalCluster over the regression shapes: every
output equals the serial result, a bad file is reported and does not stop the batch."""

import csv
import importlib.util
import sys

import pytest

import subsurf
from conftest import REPO, SHAPE_NAMES, SHAPES

pytest.importorskip("dask.distributed")


def load_batch():
    spec = importlib.util.spec_from_file_location("batch", REPO / "examples" / "python" / "batch.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules["batch"] = mod
    spec.loader.exec_module(mod)
    return mod


def test_batch_on_two_workers_equals_serial(tmp_path):
    batch = load_batch()
    bad = tmp_path / "broken.obj"
    bad.write_text("v 0 0 0\nf 1 2 3\n")
    files = [str(SHAPES / f"{n}.obj") for n in SHAPE_NAMES] + [str(bad)]
    rows = batch.run(files, str(tmp_path / "out"), op="refine", n=2, workers=2)
    assert len(rows) == len(files)
    table = list(csv.DictReader(open(tmp_path / "out" / "summary.csv")))
    assert [r["file"] for r in table] == files
    for r in rows[:-1]:
        assert r["error"] == "", r
        serial = tmp_path / "serial.obj"
        subsurf.refine(subsurf.read(r["file"]), 2).write(serial)
        assert open(r["output"]).read() == serial.read_text(), r["file"]
        assert r["faces_out"] == subsurf.read(r["output"]).num_faces
    assert "MeshError" in rows[-1]["error"]
