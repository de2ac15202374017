"""`bemshape thickness` end to end, its files read by VTK: the same run (same input, options
and threads, so bit-identical results: test_determinism.cpp) written as .csv, .vtp and .ply,
with --solver-output in the same three formats. VTK's readers must find in the .vtp exactly
the CSV's numbers, in the .ply the CSV's numbers rounded to float, and the triangles of the
input STL (as VTK's own STL reader reads them) with their orientation.

The part is tests/data/meshes/unit_sphere.STL (1280 faces, radius 1; the dense solver takes
a few seconds). Paths come from the environment ($BEMSHAPE_EXECUTABLE,
$BEMSHAPE_TEST_DATA_DIR), set by ctest (tests/apps/CMakeLists.txt).
"""

import csv
import os
import subprocess

import numpy as np
import pytest

from test_vtk_readers import read_ply_body, read_with_vtk

from vtkmodules.vtkIOGeometry import vtkSTLReader
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy

H0 = 0.5
A = 0.2  # the default of --a
FIELDS = ["thickness", "h_f", "h_p", "f_h", "n_f", "wall"]


def environment_path(name):
    path = os.environ.get(name, "")
    assert path and os.path.exists(path), f"set {name} (ctest does); got {path!r}"
    return path


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The three runs' files by extension: {"csv": (output, solver output), …}."""
    bemshape = environment_path("BEMSHAPE_EXECUTABLE")
    part = os.path.join(environment_path("BEMSHAPE_TEST_DATA_DIR"), "meshes", "unit_sphere.STL")
    folder = tmp_path_factory.mktemp("thickness")
    files = {}
    for ext in ("csv", "vtp", "ply"):
        out, solver_out = folder / f"sphere.{ext}", folder / f"sphere_solver.{ext}"
        subprocess.run([bemshape, "thickness", part, "--solver", "dense", "--h0", str(H0),
                        "--threads", "2", "--quiet", "-o", str(out), "--solver-output",
                        str(solver_out)], check=True, capture_output=True)
        files[ext] = (out, solver_out)
    files["stl"] = part
    return files


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["x", "y", "z", "thickness", "h_f", "h_p", "n_x", "n_y", "n_z", "wall"]
    values = np.array(rows[1:], dtype=np.float64)  # Python's float() is correctly rounded
    return {name: values[:, k] for k, name in enumerate(rows[0])}


def triangles(points, faces):
    """The faces as rows of their 9 corner coordinates, each rotated to start at its
    lexicographically smallest corner (orientation kept), rows sorted: comparable between
    readers that number the vertices differently."""
    corners = points[faces]  # #F×3×3
    first = np.array([min(range(3), key=lambda k: tuple(c[k])) for c in corners])
    rolled = np.stack([np.roll(c, -k, axis=0) for c, k in zip(corners, first)])
    rows = rolled.reshape(len(faces), 9)
    return rows[np.lexsort(rows.T[::-1])]


def polydata_faces(surface):
    return vtk_to_numpy(surface.GetPolys().GetConnectivityArray()).reshape(-1, 3)


@pytest.mark.parametrize("which", [0, 1], ids=["output", "solver_output"])
def test_vtp_holds_the_csv_values_exactly(runs, which):
    table = read_csv(runs["csv"][which])
    surface = read_with_vtk(vtkXMLPolyDataReader, runs["vtp"][which])
    points = vtk_to_numpy(surface.GetPoints().GetData())
    assert len(points) == len(table["x"])
    np.testing.assert_array_equal(points, np.column_stack([table["x"], table["y"], table["z"]]))
    point_data, cell_data = surface.GetPointData(), surface.GetCellData()
    for name in ("thickness", "h_f", "h_p", "wall"):
        np.testing.assert_array_equal(vtk_to_numpy(point_data.GetArray(name)), table[name],
                                      err_msg=name)
    np.testing.assert_array_equal(vtk_to_numpy(point_data.GetArray("n_f")),
                                  np.column_stack([table["n_x"], table["n_y"], table["n_z"]]))
    # f_h has no CSV column: h_f = h0(1/f_h − a) holds to rounding.
    f_h = vtk_to_numpy(point_data.GetArray("f_h"))
    np.testing.assert_allclose(H0 * (1.0 / f_h - A), table["h_f"], rtol=1e-13)
    # The default measure is the wall: the thickness is the wall column, the sphere's
    # diameter 2 within 2 % at every vertex (docs/theory.md section 5).
    np.testing.assert_array_equal(table["thickness"], table["wall"])
    np.testing.assert_allclose(table["wall"], 2.0, rtol=0.02)

    faces = polydata_faces(surface)
    assert surface.GetNumberOfCells() == len(faces) == 1280
    for name in FIELDS:
        values = vtk_to_numpy(cell_data.GetArray(name))
        assert len(values) == len(faces), name
    # Face values are means of solver-face values: within the range of the surface's values.
    face_thickness = vtk_to_numpy(cell_data.GetArray("thickness"))
    assert face_thickness.min() >= 0.99 * table["thickness"].min()
    assert face_thickness.max() <= 1.01 * table["thickness"].max()
    # The triangles of the input, oriented as there, as VTK reads the STL (float32 corners).
    stl = read_with_vtk(vtkSTLReader, runs["stl"])
    np.testing.assert_array_equal(
        triangles(points, faces),
        triangles(vtk_to_numpy(stl.GetPoints().GetData()).astype(np.float64),
                  polydata_faces(stl)))


@pytest.mark.parametrize("which", [0, 1], ids=["output", "solver_output"])
def test_ply_holds_the_csv_values_as_float(runs, which):
    table = read_csv(runs["csv"][which])
    path = runs["ply"][which]
    surface = read_with_vtk(vtkPLYReader, path)
    xyz = np.column_stack([table["x"], table["y"], table["z"]])
    np.testing.assert_array_equal(vtk_to_numpy(surface.GetPoints().GetData()),
                                  xyz.astype(np.float32))
    vtp = read_with_vtk(vtkXMLPolyDataReader, runs["vtp"][which])
    np.testing.assert_array_equal(polydata_faces(surface), polydata_faces(vtp))
    _, body = read_ply_body(path)
    thickness = table["thickness"].astype(np.float32)
    np.testing.assert_array_equal(body["vertex"]["thickness"], thickness)
    np.testing.assert_array_equal(body["vertex"]["quality"], thickness)
