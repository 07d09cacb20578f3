"""examples/python/batch.py on a 2-worker LocalCluster over the regression shapes: every
output equals the serial result, a bad file is reported and does not stop the batch."""

import csv
import subprocess
import sys

import pytest

import subsurf
from conftest import REPO, SHAPE_NAMES, SHAPES

pytest.importorskip("dask.distributed")


def test_batch_on_two_workers_equals_serial(tmp_path):
    # As a user runs it (a script, __main__): worker processes then unpickle `process` by value.
    bad = tmp_path / "broken.obj"
    bad.write_text("v 0 0 0\nf 1 2 3\n")
    files = [str(SHAPES / f"{n}.obj") for n in SHAPE_NAMES] + [str(bad)]
    r = subprocess.run([sys.executable, str(REPO / "examples" / "python" / "batch.py"), *files,
                        "-o", str(tmp_path / "out"), "--method", "refine", "--level", "2", "--workers", "2"],
                       capture_output=True, text=True, timeout=240)
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader(open(tmp_path / "out" / "summary.csv")))
    assert len(rows) == len(files)
    assert [r["file"] for r in rows] == files
    for r in rows[:-1]:
        assert r["error"] == "", r
        serial = tmp_path / "serial.obj"
        subsurf.refine(subsurf.read(r["file"]), 2).write(serial)
        assert open(r["output"]).read() == serial.read_text(), r["file"]
        assert int(r["faces_out"]) == subsurf.read(r["output"]).num_faces
    assert rows[-1]["error"].startswith("ParseError") and "line 2" in rows[-1]["error"]
