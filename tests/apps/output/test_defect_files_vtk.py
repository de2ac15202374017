"""`bemshape thickness` on a part that crosses itself where no solid can be recovered, its
files read by their consumers: a plate 4 x 4 x 0.5 with a round patch of its top 5 % of its
diagonal across pushed through its bottom (pushed_through_5 of the damaged-mesh corpus,
tests/support/damaged_meshes.hpp, written by make_test_mesh with its intact copy). The run
must finish (exit 0) with a warning naming the region and its size, list the region in the
JSON report, and mark the faces within h0 of it with a `defect` field in the .vtp (read by
VTK), the .csv and the .ply (read by VTK's PLY reader: magenta there); away from the
marked faces the thickness must be the intact plate's (median within 0.5 %).

Paths come from the environment ($BEMSHAPE_EXECUTABLE, $BEMSHAPE_MAKE_TEST_MESH), set by
ctest (tests/apps/CMakeLists.txt).
"""

import csv
import os
import re
import subprocess

import numpy as np
import pytest

from test_vtk_readers import read_ply_body, read_with_vtk

from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy

H0 = 0.5
MAX_EDGE = 0.35
CROSSING = np.array([2.0, 2.0, 0.0])  # where the patch crosses the bottom
DEFECT_RGB = (230, 0, 180)  # kDefectColour, apps/output/colour_map.hpp


def environment_path(name):
    path = os.environ.get(name, "")
    assert path and os.path.exists(path), f"set {name} (ctest does); got {path!r}"
    return path


def thickness(bemshape, stl, *outputs):
    return subprocess.run([bemshape, "thickness", str(stl), "--h0", str(H0), "--max-edge",
                           str(MAX_EDGE), "--threads", "2", "--quiet", *outputs],
                          capture_output=True, text=True)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    bemshape = environment_path("BEMSHAPE_EXECUTABLE")
    folder = tmp_path_factory.mktemp("defect")
    damaged, intact = folder / "damaged.stl", folder / "intact.stl"
    subprocess.run([environment_path("BEMSHAPE_MAKE_TEST_MESH"), "damaged", "pushed_through_5",
                    str(damaged), str(intact)], check=True, capture_output=True)
    files = {"report": folder / "damaged.json"}
    first = thickness(bemshape, damaged, "-o", str(folder / "damaged.csv"), "--solver-output",
                      str(folder / "solver.vtp"), "--report", str(files["report"]))
    files["process"] = first
    for ext in ("vtp", "ply"):
        r = thickness(bemshape, damaged, "-o", str(folder / f"damaged.{ext}"))
        assert r.returncode == 0, r.stderr
    r = thickness(bemshape, intact, "-o", str(folder / "intact.csv"))
    assert r.returncode == 0, r.stderr
    for name in ("damaged.csv", "damaged.vtp", "damaged.ply", "solver.vtp", "intact.csv"):
        files[name] = folder / name
    return files


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    values = np.array(rows[1:], dtype=np.float64)
    return {name: values[:, k] for k, name in enumerate(rows[0])}


def poly_data(path):
    return read_with_vtk(vtkXMLPolyDataReader, path)


def faces_of(polydata):
    cells = vtk_to_numpy(polydata.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    return vtk_to_numpy(polydata.GetPoints().GetData()).astype(np.float64), cells


def near_box(points, faces, box, margin):
    """Faces whose bounding box comes within `margin` of `box` (max-norm gap between the
    boxes), computed here from the JSON report's box."""
    corners = points[faces]
    lo, hi = corners.min(axis=1), corners.max(axis=1)
    gap = np.maximum(0.0, np.maximum(np.array(box["min"]) - hi, lo - np.array(box["max"])))
    return gap.max(axis=1) <= margin


def test_exit_0_and_a_warning_naming_the_region_and_its_size(run):
    p = run["process"]
    assert p.returncode == 0, p.stderr
    report = read_report(run)
    size = report["defects"][0]["size"]
    m = re.search(r"warning: .*crosses itself in 1 region that could not be repaired "
                  r"\(the largest ([0-9.e+-]+) across around \(([^)]*)\)\)", p.stderr)
    assert m, p.stderr
    assert float(m.group(1)) == pytest.approx(size, rel=1e-5)
    centre = np.array([float(x) for x in m.group(2).split(",")])
    assert np.linalg.norm(centre - CROSSING) < size


def read_report(run):
    import json
    with open(run["report"]) as f:
        return json.load(f)


def test_the_json_report_lists_the_region(run):
    report = read_report(run)
    assert len(report["defects"]) == 1
    d = report["defects"][0]
    assert "crosses itself" in d["what"] and "inside out" in d["why"]
    # The region is where the patch crosses the bottom and is inside out below it: the
    # patch is 0.57 across at the top, pushed 0.1 beyond the bottom at its centre.
    assert np.linalg.norm(np.array(d["centre"]) - CROSSING) < d["size"]
    assert 0.1 < d["size"] < 1.0
    assert d["pairs"] > 0 and d["solver_faces_marked"] > 0


def test_vtp_marks_the_faces_within_h0_of_the_region(run):
    report = read_report(run)
    box = report["defects"][0]["box"]
    for name, expected_count in (("damaged.vtp", None),
                                 ("solver.vtp", report["defects"][0]["solver_faces_marked"])):
        polydata = poly_data(run[name])
        points, faces = faces_of(polydata)
        cell = vtk_to_numpy(polydata.GetCellData().GetArray("defect"))
        point = vtk_to_numpy(polydata.GetPointData().GetArray("defect"))
        assert set(np.unique(cell)) == {0.0, 1.0} and set(np.unique(point)) == {0.0, 1.0}
        expected = near_box(points, faces, box, H0)
        assert np.array_equal(cell == 1.0, expected), name
        # A vertex is marked when a marked face uses it.
        used = np.zeros(len(points), bool)
        used[faces[expected].ravel()] = True
        assert np.array_equal(point == 1.0, used), name
        assert 0 < expected.sum() < 0.5 * len(faces)
        if expected_count is not None:
            assert expected.sum() == expected_count


def test_csv_and_ply_carry_the_same_vertex_flags(run):
    table = read_csv(run["damaged.csv"])
    assert "defect" in table
    vtp = poly_data(run["damaged.vtp"])
    assert np.array_equal(table["defect"],
                          vtk_to_numpy(vtp.GetPointData().GetArray("defect")).astype(np.float64))
    properties, body = read_ply_body(run["damaged.ply"])
    assert "defect" in properties
    assert np.array_equal(body["vertex"]["defect"].astype(np.float64), table["defect"])
    # VTK's PLY reader: the marked vertices in the defect colour, the others not.
    ply = read_with_vtk(vtkPLYReader, run["damaged.ply"])
    rgb = vtk_to_numpy(ply.GetPointData().GetArray("RGB"))
    magenta = np.all(rgb == np.array(DEFECT_RGB), axis=1)
    assert np.array_equal(magenta, table["defect"] == 1.0)


def test_thickness_away_from_the_region_is_the_intact_plates(run):
    damaged, intact = read_csv(run["damaged.csv"]), read_csv(run["intact.csv"])
    key = lambda t, i: (t["x"][i], t["y"][i], t["z"][i])
    index = {key(intact, i): i for i in range(len(intact["x"]))}
    ratios = []
    for i in range(len(damaged["x"])):
        j = index.get(key(damaged, i))
        if damaged["defect"][i] == 0.0 and j is not None:
            ratios.append(damaged["thickness"][i] / intact["thickness"][j] - 1.0)
    ratios = np.abs(np.array(ratios))
    assert len(ratios) > 0.5 * len(damaged["x"])
    print(f"median |relative difference| {np.median(ratios):.2e} over {len(ratios)} vertices")
    assert np.median(ratios) < 0.005
