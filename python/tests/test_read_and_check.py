"""bemshape.read_mesh and bemshape.check: a file's triangles as arrays, and the validation
report of `bemshape check` for arrays (python/mesh_functions.cpp)."""

import os

import numpy as np
import pytest

import bemshape
from support import box, icosphere

DATA = os.environ.get("BEMSHAPE_TEST_DATA_DIR", "")


def test_read_mesh_gives_float64_positions_and_int64_triangles():
    V, F = bemshape.read_mesh(os.path.join(DATA, "meshes", "unit_sphere.STL"))
    assert V.dtype == np.float64 and V.ndim == 2 and V.shape[1] == 3
    assert F.dtype == np.int64 and F.ndim == 2 and F.shape[1] == 3
    assert F.min() >= 0 and F.max() < len(V)
    # A tessellated unit sphere: every vertex on it.
    assert np.allclose(np.linalg.norm(V, axis=1), 1.0, atol=1e-4)


def test_read_mesh_accepts_path_objects_and_names_a_missing_file():
    import pathlib
    V, _ = bemshape.read_mesh(pathlib.Path(DATA) / "meshes" / "cylinder.stl")
    assert len(V) > 0
    with pytest.raises(ValueError, match="no_such_file.stl"):
        bemshape.read_mesh(os.path.join(DATA, "no_such_file.stl"))


def test_check_of_a_closed_box_reports_its_volume_area_and_one_shell():
    V, F = box((1.0, 2.0, 3.0))
    report = bemshape.check(V, F)
    assert report["usable"] is True
    assert report["faces"] == 12 and report["vertices"] == 8
    assert report["shells"] == 1 and report["cavities"] == 0
    assert report["volume"] == pytest.approx(6.0, rel=1e-12)
    assert report["area"] == pytest.approx(2 * (2 + 3 + 6), rel=1e-12)
    assert report["bounding_box"]["max"] == pytest.approx([1.0, 2.0, 3.0])
    assert report["source"] == "numpy arrays"


def test_check_refuses_an_open_mesh_without_raising_and_repairs_orientation():
    V, F = icosphere(1.0, 2)
    opened = bemshape.check(V, F[1:], name="open sphere")
    assert opened["usable"] is False
    assert opened["source"] == "open sphere"
    refused = [p for p in opened["problems"] if p["status"] == "REFUSED"]
    assert refused and "open boundary edge" in refused[0]["what"]
    # Every face reversed: usable after reorientation, which the report names.
    flipped = bemshape.check(V, F[:, ::-1])
    assert flipped["usable"] is True
    assert flipped["volume"] > 0 and any("reversed 320 faces" in r for r in flipped["repairs"])


@pytest.mark.parametrize("V, F, message", [
    (np.zeros((4, 2)), np.zeros((1, 3), dtype=int), r"V must have shape \(n, 3\)"),
    (np.zeros((4, 3)), np.zeros((1, 3)), "F must hold integers"),
    (np.zeros((4, 3)), np.array([[0, 1, 7]]), r"\[0, 4\)"),
    (np.full((4, 3), np.nan), np.array([[0, 1, 2]]), "finite"),
    ("not an array", np.array([[0, 1, 2]]), "V must"),
    (np.zeros((4, 3)), np.array([[0, 1, -1]]), "F: vertex indices must lie in"),
])
def test_bad_arrays_raise_value_error_naming_the_argument(V, F, message):
    with pytest.raises(ValueError, match=message) as error:
        bemshape.check(V, F)
    assert isinstance(error.value, bemshape.InputError)
