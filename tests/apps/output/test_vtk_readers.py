"""The files of apps/output as the programs users open them with read them: VTK's own readers
(vtkXMLPolyDataReader for .vtp, vtkXMLImageDataReader for .vti, vtkPLYReader for .ply; the
readers ParaView uses), at the sizes of real parts: 10⁵ and 10⁶ faces, 10⁵ and 10⁶ grid
points.

write_analytic_outputs (write_analytic_outputs.cpp beside this file, path in
$BEMSHAPE_WRITE_ANALYTIC_OUTPUTS) writes a saddle surface and two grids whose every number is
a closed form; each test reads a file with VTK and compares the counts, the connectivity and
every value with the same closed form computed here in numpy. The forms are chosen so that
IEEE double arithmetic gives the same bits in C++ and numpy (one rounded division of an exact
numerator), so the Float64 arrays are compared exactly, and Float32 ones to float(value).

VTK 9.1's vtkPLYReader passes on positions, faces and colours but not other vertex
properties (thickness, quality): those are read with numpy from the binary body as the PLY
header declares it.

Run by ctest (tests/apps/CMakeLists.txt) as /usr/bin/python3 -m pytest; vtk, numpy and pytest
are Debian's python3-vtk9, python3-numpy and python3-pytest (scripts/setup).
"""

import os
import subprocess
import time

import numpy as np
import pytest

try:
    from vtkmodules.vtkCommonCore import vtkCommand
    from vtkmodules.vtkIOPLY import vtkPLYReader
    from vtkmodules.vtkIOXML import vtkXMLImageDataReader, vtkXMLPolyDataReader
    from vtkmodules.util.misc import calldata_type
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.util.vtkConstants import VTK_STRING
except ImportError as error:  # a missing VTK is a failure, never a skip
    raise ImportError(f"{error}: these tests need VTK's Python module; "
                      "install Debian's python3-vtk9 (scripts/setup does)") from error

WRITER = os.environ.get("BEMSHAPE_WRITE_ANALYTIC_OUTPUTS", "")

# Squares per side of the saddle surface: 2·N² faces.
N_1E5 = 224  # 100 352 faces, 50 625 vertices
N_1E6 = 708  # 1 002 528 faces, 502 681 vertices

GRID_CELLS = (103, 99, 97)  # grid.vti: 1 019 200 points, 989 109 cells
GRID_ORIGIN = (-1.0, -0.5, 0.25)
GRID_SPACING = (1 / 64, 1 / 32, 1 / 16)
IMAGE_CELLS = (400, 300)  # image.vti: 120 000 cells, 120 701 points
IMAGE_ORIGIN = (-1.0, -0.5, 0.0)
IMAGE_SPACING = (1 / 256, 1 / 128, 1.0)


def g(k, x, y, z):
    """g_k(x, y, z) = (k + x − 2y + 3z)/(2k + 1), as write_analytic_outputs computes it."""
    return (k + x - 2.0 * y + 3.0 * z) / (2.0 * k + 1.0)


def write_files(folder, n, *files):
    """Runs write_analytic_outputs; returns {file: seconds the writer took}."""
    assert WRITER and os.path.isfile(WRITER), (
        "set BEMSHAPE_WRITE_ANALYTIC_OUTPUTS to the write_analytic_outputs program "
        f"(ctest does); got {WRITER!r}")
    run = subprocess.run([WRITER, str(folder), str(n), *files], capture_output=True, text=True,
                         check=True)
    seconds = {}
    for line in run.stdout.splitlines():
        name, _, rest = line.partition(": ")
        if name in files:
            seconds[name] = float(rest.split(", ")[1].split()[0])
    assert set(seconds) == set(files), run.stdout
    return seconds


def read_with_vtk(reader_class, path):
    """The output of a VTK reader on `path`; any error or warning VTK reports fails the test."""
    reader = reader_class()
    reports = []

    @calldata_type(VTK_STRING)
    def report(_reader, event, message):
        reports.append(f"{event}: {message.strip()}")

    for event in (vtkCommand.ErrorEvent, vtkCommand.WarningEvent):
        reader.AddObserver(event, report)
    reader.SetFileName(str(path))
    start = time.perf_counter()
    reader.Update()
    seconds = time.perf_counter() - start
    assert not reports, f"VTK on {path}: {reports}"
    print(f"{os.path.basename(path)}: {os.path.getsize(path)} bytes, "
          f"read by {reader_class.__name__} in {seconds:.2f} s")
    return reader.GetOutput()


def saddle(n):
    """The saddle surface: vertex positions #V×3, faces #F×3 (write_analytic_outputs.cpp)."""
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1))  # i fastest
    x = i.ravel() / 512.0 - 1.0
    y = j.ravel() / 512.0 - 0.5
    points = np.column_stack([x, y, x * y])
    si, sj = np.meshgrid(np.arange(n), np.arange(n))
    si, sj = si.ravel(), sj.ravel()

    def v(a, b):
        return b * (n + 1) + a

    faces = np.empty((2 * n * n, 3), dtype=np.int64)
    faces[0::2] = np.column_stack([v(si, sj), v(si + 1, sj), v(si + 1, sj + 1)])
    faces[1::2] = np.column_stack([v(si, sj), v(si + 1, sj + 1), v(si, sj + 1)])
    return points, faces


def saddle_fields(points):
    """The point fields of the saddle by name, #V×components."""
    x, y, z = points.T
    fields = {name: g(k, x, y, z)[:, None]
              for k, name in enumerate(["thickness", "h_f", "h_p", "f_h"], start=1)}
    fields["n_f"] = np.column_stack([x / 3.0, y / 5.0, z / 7.0])
    return fields


def check_polydata(surface, n):
    """Counts, positions, triangles and every point and cell value of the saddle."""
    points, faces = saddle(n)
    assert surface.GetNumberOfPoints() == len(points)
    assert surface.GetNumberOfCells() == len(faces)
    assert surface.GetNumberOfPolys() == len(faces)
    assert surface.GetNumberOfVerts() == surface.GetNumberOfLines() == 0
    read_points = vtk_to_numpy(surface.GetPoints().GetData())
    assert read_points.dtype == np.float64
    np.testing.assert_array_equal(read_points, points)

    polys = surface.GetPolys()
    offsets = vtk_to_numpy(polys.GetOffsetsArray())
    np.testing.assert_array_equal(offsets, 3 * np.arange(len(faces) + 1))
    connectivity = vtk_to_numpy(polys.GetConnectivityArray()).reshape(-1, 3)
    np.testing.assert_array_equal(connectivity, faces)
    for f in (0, 1, len(faces) // 2 + 1, len(faces) - 1):  # through VTK's cell interface
        cell = surface.GetCell(f)
        assert cell.GetCellType() == 5  # VTK_TRIANGLE
        assert [cell.GetPointId(k) for k in range(3)] == list(faces[f])

    expected = saddle_fields(points)
    point_data, cell_data = surface.GetPointData(), surface.GetCellData()
    for name, values in expected.items():
        array = point_data.GetArray(name)
        assert array is not None, f"no point array {name}"
        read = vtk_to_numpy(array).reshape(len(points), -1)
        assert read.dtype == np.float64
        np.testing.assert_array_equal(read, values, err_msg=f"point data {name}")
        cell_values = values[faces[:, 0]] + values[faces[:, 1]] + values[faces[:, 2]]
        array = cell_data.GetArray(name)
        assert array is not None, f"no cell array {name}"
        read = vtk_to_numpy(array).reshape(len(faces), -1)
        assert read.dtype == np.float64
        np.testing.assert_array_equal(read, cell_values, err_msg=f"cell data {name}")
    assert point_data.GetNumberOfArrays() == cell_data.GetNumberOfArrays() == 5


@pytest.fixture(scope="module")
def files_1e5(tmp_path_factory):
    folder = tmp_path_factory.mktemp("analytic_1e5")
    write_files(folder, N_1E5, "surface.vtp", "surface_ascii.vtp", "surface.ply", "grid.vti",
                "image.vti")
    return folder


@pytest.mark.parametrize("name", ["surface.vtp", "surface_ascii.vtp"])
def test_vtp_1e5_faces_binary_and_ascii(files_1e5, name):
    check_polydata(read_with_vtk(vtkXMLPolyDataReader, files_1e5 / name), N_1E5)


def test_vtp_ascii_indices_are_integers(files_1e5):
    """Every Int64 number of the ASCII file is written in integer digits ("100000", not
    "1e+05", which VTK reads as 1)."""
    text = (files_1e5 / "surface_ascii.vtp").read_text()
    polys = text[text.index("<Polys>"):text.index("</Polys>")]
    numbers = [t for line in polys.splitlines() if not line.lstrip().startswith("<")
               for t in line.split()]
    assert len(numbers) == 4 * 2 * N_1E5 ** 2
    assert all(t.isdigit() for t in numbers)


def test_vtp_1e6_faces(tmp_path):
    """The issue's done-when: a 10⁶-face thickness map opens in VTK with the right counts and
    values. Writing it takes well under a second (the time is printed)."""
    seconds = write_files(tmp_path, N_1E6, "surface.vtp")["surface.vtp"]
    print(f"surface.vtp, {2 * N_1E6 ** 2} faces: written in {seconds:.2f} s")
    check_polydata(read_with_vtk(vtkXMLPolyDataReader, tmp_path / "surface.vtp"), N_1E6)
    (tmp_path / "surface.vtp").unlink()  # 128 MB; kept only when the test fails


def grid_positions(cells, origin, spacing, shift):
    """Positions of a grid's points (shift 0) or cell centres (shift ½), x fastest; #items×3.
    A 2-D grid (cells of length 2) lies in z = 0."""
    counts = [c + (1 if shift == 0 else 0) for c in cells]
    axes = [origin[d] + spacing[d] * (np.arange(counts[d]) + shift) for d in range(len(cells))]
    if len(cells) == 2:
        axes.append(np.zeros(1))
    z, y, x = np.meshgrid(axes[2], axes[1], axes[0], indexing="ij")  # x fastest
    return np.column_stack([x.ravel(), y.ravel(), z.ravel()])


def check_image_array(data, name, expected):
    array = data.GetArray(name)
    assert array is not None, f"no array {name}"
    read = vtk_to_numpy(array).reshape(len(expected), -1)
    assert read.dtype == np.float32
    np.testing.assert_array_equal(read, expected.astype(np.float32), err_msg=name)


def test_vti_3d_1e6_points(files_1e5):
    image = read_with_vtk(vtkXMLImageDataReader, files_1e5 / "grid.vti")
    assert image.GetDimensions() == tuple(c + 1 for c in GRID_CELLS)
    assert image.GetOrigin() == GRID_ORIGIN
    assert image.GetSpacing() == GRID_SPACING
    assert image.GetNumberOfPoints() == np.prod([c + 1 for c in GRID_CELLS])
    assert image.GetNumberOfCells() == np.prod(GRID_CELLS)
    points = grid_positions(GRID_CELLS, GRID_ORIGIN, GRID_SPACING, 0.0)
    np.testing.assert_array_equal(image.GetPoint(len(points) - 1), points[-1])
    np.testing.assert_array_equal(image.GetPoint(GRID_CELLS[0] + 2), points[GRID_CELLS[0] + 2])
    x, y, z = points.T
    check_image_array(image.GetPointData(), "g", g(1, x, y, z)[:, None])
    check_image_array(image.GetPointData(), "v", np.column_stack([x / 3.0, y / 5.0, z / 7.0]))
    x, y, z = grid_positions(GRID_CELLS, GRID_ORIGIN, GRID_SPACING, 0.5).T
    check_image_array(image.GetCellData(), "g", g(1, x, y, z)[:, None])


def test_vti_2d_image_1e5_cells(files_1e5):
    image = read_with_vtk(vtkXMLImageDataReader, files_1e5 / "image.vti")
    assert image.GetDimensions() == (IMAGE_CELLS[0] + 1, IMAGE_CELLS[1] + 1, 1)
    assert image.GetOrigin() == IMAGE_ORIGIN
    assert image.GetSpacing() == IMAGE_SPACING
    assert image.GetNumberOfCells() == IMAGE_CELLS[0] * IMAGE_CELLS[1]
    assert image.GetPointData().GetNumberOfArrays() == 0
    x, y, z = grid_positions(IMAGE_CELLS, IMAGE_ORIGIN, IMAGE_SPACING, 0.5).T
    check_image_array(image.GetCellData(), "g", g(1, x, y, z)[:, None])


def read_ply_body(path):
    """The vertex and face elements of a binary little-endian PLY as numpy structured arrays,
    laid out as its header declares (scalar vertex properties; faces as a uchar count and
    int indices, all triangles)."""
    raw = path.read_bytes()
    end = raw.index(b"end_header\n") + len(b"end_header\n")
    header = raw[:end].decode("ascii").splitlines()
    assert header[:2] == ["ply", "format binary_little_endian 1.0"]
    types = {"float": "<f4", "double": "<f8", "uchar": "u1", "int": "<i4"}
    elements, current = [], None
    for line in header[2:]:
        words = line.split()
        if words[0] == "element":
            current = (words[1], int(words[2]), [])
            elements.append(current)
        elif words[0] == "property" and words[1] == "list":
            assert words[2:] == ["uchar", "int", "vertex_indices"], line
            current[2].extend([("count", "u1"), ("vertex_indices", "<i4", (3,))])
        elif words[0] == "property":
            current[2].append((words[2], types[words[1]]))
    assert [e[0] for e in elements] == ["vertex", "face"]
    body, at = {}, end
    for name, count, fields in elements:
        dtype = np.dtype(fields)
        body[name] = np.frombuffer(raw, dtype=dtype, count=count, offset=at)
        at += count * dtype.itemsize
    assert at == len(raw), "bytes after the face element"
    assert (body["face"]["count"] == 3).all()
    return [line.split()[-1] for line in header if line.startswith("property")], body


@pytest.mark.parametrize("n", [N_1E5, N_1E6])
def test_ply_quality_and_thickness(tmp_path, n):
    """vtkPLYReader: positions, triangles, colours; numpy per the header: thickness and
    quality (MeshLab's vertex quality) equal float(g_1) at every vertex."""
    write_files(tmp_path, n, "surface.ply")
    path = tmp_path / "surface.ply"
    points, faces = saddle(n)
    surface = read_with_vtk(vtkPLYReader, path)
    assert surface.GetNumberOfPoints() == len(points)
    assert surface.GetNumberOfCells() == len(faces)
    np.testing.assert_array_equal(vtk_to_numpy(surface.GetPoints().GetData()),
                                  points.astype(np.float32))
    connectivity = vtk_to_numpy(surface.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    np.testing.assert_array_equal(connectivity, faces)
    colours = vtk_to_numpy(surface.GetPointData().GetArray("RGB"))
    assert colours.shape == (len(points), 3)

    properties, body = read_ply_body(path)
    assert properties == ["x", "y", "z", "thickness", "quality", "red", "green", "blue",
                          "vertex_indices"]
    vertex = body["vertex"]
    expected = g(1, *points.T).astype(np.float32)
    np.testing.assert_array_equal(vertex["thickness"], expected)
    np.testing.assert_array_equal(vertex["quality"], expected)
    np.testing.assert_array_equal(np.column_stack([vertex["red"], vertex["green"],
                                                   vertex["blue"]]), colours)
    # Viridis runs from dark violet to bright yellow: the thickest vertex is the brightest.
    brightness = colours.astype(int).sum(axis=1)
    assert brightness[np.argmax(expected)] > brightness[np.argmin(expected)]
    np.testing.assert_array_equal(body["face"]["vertex_indices"], faces)
    path.unlink()  # 25 MB at 10⁶ faces; kept only when the test fails
