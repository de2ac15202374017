"""bemshape.dask (python/bemshape/dask.py) on a LocalCluster of 2 worker processes listening
on 127.0.0.1 only: six small parts, one of them unreadable, get the same verdicts and
statistics as serial calls of bemshape.read_mesh and bemshape.thickness in this process,
and as `bemshape check-all` gives for the same files; the unreadable part is reported and
the others finish. The parts are plates and a ball at a coarse mesh, about a second each.
"""
import json
import os
import subprocess

import numpy as np
import pytest

import bemshape
import bemshape.dask
from distributed import Client, LocalCluster
from support import box, icosphere

# Every part's options: h0 near the plates' walls, a coarse mesh (a few hundred solver faces).
OPTIONS = dict(h0=0.3, max_edge=0.3)
THRESHOLD = 0.25
# Statistics of the same triangles by the same code agree to rounding (the OpenMP sums may
# differ in order between thread counts).
TOLERANCE = 1e-9


def write_ascii_stl(path, V, F):
    with open(path, "w") as f:
        f.write("solid part\n")
        for a, b, c in F:
            n = np.cross(V[b] - V[a], V[c] - V[a])
            n /= np.linalg.norm(n)
            f.write("facet normal %r %r %r\n outer loop\n" % tuple(float(x) for x in n))
            for v in (a, b, c):
                f.write("  vertex %r %r %r\n" % tuple(float(x) for x in V[v]))
            f.write(" endloop\nendfacet\n")
        f.write("endsolid part\n")


@pytest.fixture(scope="module")
def parts(tmp_path_factory):
    folder = tmp_path_factory.mktemp("parts")
    shapes = {
        "a_plate_04.stl": box((2.0, 2.0, 0.4)),
        "b_plate_015.stl": box((2.0, 2.0, 0.15)),  # thinner than the threshold
        "c_ball.stl": icosphere(0.5, 2),  # wall: the diameter, 1
        "d_plate_03.stl": box((2.0, 1.5, 0.3)),
        "f_plate_02.stl": box((1.5, 2.0, 0.2)),  # thinner than the threshold
    }
    paths = []
    for name, (V, F) in shapes.items():
        write_ascii_stl(folder / name, V, F)
        paths.append(str(folder / name))
    unreadable = folder / "e_unreadable.stl"
    unreadable.write_text("solid broken\nfacet normal 0 0 1\n outer loop\n  vertex 0 0\n")
    paths.insert(4, str(unreadable))
    return sorted(paths)


@pytest.fixture(scope="module")
def cluster():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None) as local, Client(local) as client:
        yield client


def serial(path):
    """The figures of one part by direct calls in this process, None for a part that cannot
    be read."""
    try:
        V, F = bemshape.read_mesh(path)
    except ValueError:
        return None
    r = bemshape.thickness(V, F, min_thickness=THRESHOLD, threads=1, name=path, **OPTIONS)
    return r


def test_dask_records_match_serial_calls(parts, cluster):
    workers = cluster.scheduler_info()["workers"]
    assert len(workers) == 2
    assert cluster.scheduler.address.startswith("tcp://127.0.0.1:")
    assert all(address.startswith("tcp://127.0.0.1:") for address in workers)

    records = bemshape.dask.check_parts(parts, cluster, min_thickness=THRESHOLD, **OPTIONS)
    assert [r["part"] for r in records] == parts
    # The tasks ran in the worker processes, not here, with the worker's memory share.
    verdicts = {}
    for path, record in zip(parts, records):
        expected = serial(path)
        verdicts[os.path.basename(path)] = record["verdict"]
        if expected is None:
            assert record["verdict"] == "error"
            assert record["exit_code"] == 2
            assert "e_unreadable.stl" in record["error"]
            assert record["min_thickness"] is None
            continue
        s = expected["statistics"]
        assert record["verdict"] == ("pass" if expected["passed"] else "thin")
        assert record["exit_code"] == (0 if expected["passed"] else 1)
        assert record["error"] is None
        assert record["threshold"] == THRESHOLD
        assert record["h0"] == pytest.approx(OPTIONS["h0"], abs=0)
        assert record["min_thickness"] == pytest.approx(s["min"], rel=TOLERANCE)
        assert np.allclose(record["min_location"], s["min_location"], rtol=0, atol=TOLERANCE)
        assert record["regions"] == len(expected["regions"])
        assert record["thin_area"] == pytest.approx(
            sum(region["area"] for region in expected["regions"]), rel=TOLERANCE, abs=TOLERANCE)
        assert record["seconds"] > 0 and record["peak_mb"] > 0
    # The designed walls decide the verdicts.
    assert verdicts == {"a_plate_04.stl": "pass", "b_plate_015.stl": "thin", "c_ball.stl": "pass",
                        "d_plate_03.stl": "pass", "e_unreadable.stl": "error",
                        "f_plate_02.stl": "thin"}


def test_dask_records_match_check_all(parts, cluster, tmp_path):
    """The records of bemshape.dask and the JSON lines of `bemshape check-all` agree field
    by field for the same parts (the times and memory aside): one summary, two front ends."""
    records = bemshape.dask.check_parts(parts, cluster, min_thickness=THRESHOLD, **OPTIONS)
    reports = tmp_path / "reports"
    run = subprocess.run(
        [os.environ["BEMSHAPE_EXECUTABLE"], "check-all", *parts, "--reports", str(reports),
         "--jobs", "2", "--min-thickness", str(THRESHOLD), "--h0", str(OPTIONS["h0"]),
         "--max-edge", str(OPTIONS["max_edge"]), "--quiet"],
        capture_output=True, text=True, timeout=600)
    assert run.returncode == 2, run.stderr
    with open(reports / "summary.jsonl") as f:
        lines = [json.loads(line) for line in f]
    assert [line["part"] for line in lines] == parts
    for record, line in zip(records, lines):
        assert set(record) == set(line)
        for field in ("verdict", "exit_code", "threshold", "regions"):
            assert record[field] == line[field], field
        for field in ("min_thickness", "thin_area", "h0"):
            if line[field] is None:
                assert record[field] is None
            else:
                assert record[field] == pytest.approx(line[field], rel=TOLERANCE, abs=TOLERANCE)
        if line["min_location"] is not None:
            assert np.allclose(record["min_location"], line["min_location"], rtol=0,
                               atol=TOLERANCE)


def test_check_part_reports_problems_in_the_record(parts):
    """check_part, the task itself, run here: a timeout and an unreadable file are records,
    a wrong keyword is the caller's TypeError."""
    unreadable = [p for p in parts if p.endswith("e_unreadable.stl")][0]
    record = bemshape.dask.check_part(unreadable, min_thickness=THRESHOLD, **OPTIONS)
    assert record["verdict"] == "error" and record["exit_code"] == 2
    slow = bemshape.dask.check_part(parts[0], min_thickness=THRESHOLD, timeout=1e-6, threads=1,
                                    **OPTIONS)
    assert slow["verdict"] == "timeout" and slow["exit_code"] == 3
    assert "timeout" in slow["error"]
    with pytest.raises(TypeError):
        bemshape.dask.check_part(parts[0], min_thickness=THRESHOLD, not_an_option=1)
