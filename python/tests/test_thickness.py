"""bemshape.thickness against the ball's closed form (support.Ball), its arrays (shapes,
dtypes, no copies, aligned with the caller's V and F), its report against the command
line's, and the mapping of errors to exceptions."""

import json
import os
import subprocess

import numpy as np
import pytest

import bemshape
from support import Ball, icosphere, max_relative_deviation

H0, A, RADIUS = 0.3, 0.2, 0.5
BALL = Ball(RADIUS, H0, A)
DATA = os.environ.get("BEMSHAPE_TEST_DATA_DIR", "")


@pytest.fixture(scope="module")
def ball():
    """The geodesic ball of 1280 faces (edge ≈ 0.09 = the default rule 1.5·a·h0) and its
    thickness at h0 = 0.3."""
    V, F = icosphere(RADIUS, 3)
    return V, F, bemshape.thickness(V, F, h0=H0, measure="principal")


def test_ball_thickness_within_2_percent_of_the_closed_form_on_vertices_and_faces(ball):
    V, F, result = ball
    assert result["measure"] == "h_p"
    assert max_relative_deviation(result["vertex"]["h_p"], BALL.h_p) < 0.02
    assert max_relative_deviation(result["face"]["h_p"], BALL.h_p) < 0.02
    assert max_relative_deviation(result["vertex"]["h_f"], BALL.h_f) < 0.02
    assert max_relative_deviation(result["vertex"]["f_h"], BALL.f_h) < 0.02
    for key in ("min", "max", "mean", "median", "p05", "p95"):
        assert result["statistics"][key] == pytest.approx(BALL.h_p, rel=0.02)
    # s = A·x: n_f is the outward normal at every vertex.
    normals = V / np.linalg.norm(V, axis=1)[:, None]
    assert np.min(np.einsum("ij,ij->i", result["vertex"]["n_f"], normals)) > 0.999


def test_arrays_line_up_with_the_callers_mesh_and_are_views_not_copies(ball):
    V, F, result = ball
    for where, count in (("vertex", len(V)), ("face", len(F))):
        arrays = result[where]
        for key in ("thickness", "f_h", "h_f", "h_p"):
            assert arrays[key].shape == (count,) and arrays[key].dtype == np.float64
        assert arrays["n_f"].shape == (count, 3) and arrays["n_f"].dtype == np.float64
        # Views of one matrix the module owns: thickness is the h_p column itself.
        for key in ("thickness", "h_p", "n_f"):
            assert not arrays[key].flags.owndata and arrays[key].base is not None
        assert np.shares_memory(arrays["thickness"], arrays["h_p"])
        assert arrays["h_p"].base is arrays["n_f"].base  # columns of one matrix, one owner
    solver = result["solver_mesh"]
    assert solver["V"].shape[1] == 3 and solver["F"].dtype == np.int64
    assert solver["face"]["h_p"].shape == (len(solver["F"]),)
    assert result["report"]["mesh"]["solver_faces"] == len(solver["F"])


def test_report_is_the_command_lines_report(ball):
    report = ball[2]["report"]
    assert report["command"] == "thickness" and report["input"] == "numpy arrays"
    assert report["parameters"]["h0"] == H0 and report["parameters"]["measure"] == "principal"
    assert report["parameters"]["kappa"] == pytest.approx(2 / (A * H0))
    assert report["mesh"]["input_faces"] == 1280
    assert report["check"] is None and ball[2]["passed"] is None
    assert report["solver"]["method"] == "dense-lu"
    assert set(report["timing"]) >= {"prepare", "refine", "assemble", "solve", "features",
                                     "map_back", "total"}


def test_min_thickness_check_finds_the_ball_thinner_than_a_threshold_above_its_wall():
    V, F = icosphere(RADIUS, 2)
    failed = bemshape.thickness(V, F, h0=H0, min_thickness=1.2 * BALL.h_p, max_edge=0.15)
    assert failed["passed"] is False
    assert len(failed["regions"]) == 1  # the whole surface, one connected region
    region = failed["regions"][0]
    assert region["area"] == pytest.approx(failed["report"]["mesh"]["area"], rel=0.02)
    assert region["solver_faces"].dtype == np.int64
    assert len(region["solver_faces"]) == len(failed["solver_mesh"]["F"])
    passed = bemshape.thickness(V, F, h0=H0, min_thickness=0.8 * BALL.h_p, max_edge=0.15)
    assert passed["passed"] is True and passed["regions"] == []


def test_paper_measure_selects_h_f():
    V, F = icosphere(RADIUS, 2)
    result = bemshape.thickness(V, F, h0=H0, measure="paper", max_edge=0.15)
    assert result["measure"] == "h_f"
    assert np.array_equal(result["vertex"]["thickness"], result["vertex"]["h_f"])
    assert result["report"]["parameters"]["measure"] == "paper"


def test_same_triangles_from_python_and_the_command_line_give_the_same_thickness(tmp_path):
    mesh = os.path.join(DATA, "meshes", "unit_sphere.STL")
    V, F = bemshape.read_mesh(mesh)
    result = bemshape.thickness(V, F, h0=0.6)
    report_file = tmp_path / "report.json"
    subprocess.run([os.environ["BEMSHAPE_EXECUTABLE"], "thickness", mesh, "--h0", "0.6",
                    "--report", str(report_file), "--quiet"], check=True, capture_output=True)
    cli = json.loads(report_file.read_text())
    assert cli["mesh"]["solver_faces"] == result["report"]["mesh"]["solver_faces"]
    for key in ("min", "max", "mean", "median", "p05", "p95", "measured_area"):
        assert result["statistics"][key] == pytest.approx(cli["thickness"][key], rel=1e-9)


def test_errors_map_to_the_python_exceptions_users_expect():
    V, F = icosphere(RADIUS, 2)
    with pytest.raises(ValueError, match="measure must be"):
        bemshape.thickness(V, F, h0=H0, measure="median")
    with pytest.raises(ValueError, match="solver"):
        bemshape.thickness(V, F, h0=H0, solver="magic")
    with pytest.raises(ValueError, match="threads"):
        bemshape.thickness(V, F, h0=H0, threads=0)
    with pytest.raises(ValueError, match="open boundary edge"):
        bemshape.thickness(V, F[1:], h0=H0)
    # The dense system of the ball at edge 0.05 (about 2900 faces, 5800 unknowns) needs about
    # 270 MB: 10 MB are refused before the assembly.
    with pytest.raises(MemoryError) as refused:
        bemshape.thickness(V, F, h0=H0, solver="dense", max_edge=0.05, max_memory=10e6)
    assert isinstance(refused.value, bemshape.ResourceError)


def resident_bytes():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) * 1024
    raise RuntimeError("no VmRSS in /proc/self/status")


def test_fit_memory_solves_on_the_coarser_mesh_the_refusal_names_within_the_budget():
    # The dense system of the ball at edge 0.05 (about 2900 faces) needs about 270 MB; 40 MB
    # above what the interpreter holds fits a few hundred faces.
    V, F = icosphere(RADIUS, 2)
    budget = resident_bytes() + 40e6
    with pytest.raises(MemoryError, match=r"a mesh that fits: --max-edge [0-9.]+ \(") as refused:
        bemshape.thickness(V, F, h0=H0, solver="dense", max_edge=0.05, max_memory=budget)
    assert str(refused.value).endswith("or --fit-memory to take it")
    result = bemshape.thickness(V, F, h0=H0, solver="dense", max_edge=0.05, max_memory=budget,
                                fit_memory=True)
    fit = result["report"]["mesh"]["memory_fit"]
    assert fit["fitted"] and fit["max_edge"] > 0.05
    assert fit["solver_faces"] == result["report"]["mesh"]["solver_faces"] < fit["refused_faces"]
    # The solver's bound on the peak fits (peak_mb is this interpreter's lifetime peak, taken
    # by the earlier tests; the memory watch would have raised had the solve outgrown it).
    assert result["report"]["memory"]["estimate_mb"] * 1e6 <= budget
    assert np.all(np.isfinite(result["face"]["thickness"]))


def test_wall_measure_is_the_default_and_reads_the_diameter_with_thick_regions():
    V, F = icosphere(RADIUS, 3)
    result = bemshape.thickness(V, F, h0=H0, max_thickness=0.5 * RADIUS)
    assert result["measure"] == "wall"
    assert result["report"]["parameters"]["measure"] == "wall"
    assert np.array_equal(result["face"]["thickness"], result["face"]["wall"])
    # The wall of a ball is its diameter: h_p at the centre, the offset a·h0 removed.
    assert max_relative_deviation(result["solver_mesh"]["face"]["wall"], 2 * RADIUS) < 0.02
    regions = result["thick_regions"]["regions"]
    assert len(regions) == 1  # the whole ball is thicker than its radius
    assert regions[0]["max"] == pytest.approx(2 * RADIUS, rel=0.02)


def test_h0_defaults_to_twice_volume_over_area():
    V, F = icosphere(RADIUS, 2)
    result = bemshape.thickness(V, F, max_edge=0.15)
    report = result["report"]
    assert report["parameters"]["h0_rule"] == "2*volume/area of the part"
    # 2·V/A of a ball is 2R/3 (to the polyhedron's own volume and area).
    assert report["parameters"]["h0"] == pytest.approx(
        2 * report["mesh"]["volume"] / report["mesh"]["area"], rel=1e-12)
    assert report["parameters"]["h0"] == pytest.approx(2 * RADIUS / 3, rel=0.02)


def test_a_ball_in_metres_checked_in_millimetres_fails_and_warns_about_units():
    """The ball of diameter 1 (mm) written in metres, checked at 0.3 "mm": the faces reading
    below the limit cover far more than the speck area (at most 0.1 % of the part), so the
    check fails, and the units warning names the mix-up; units_check=False silences it and
    keeps the verdict."""
    V, F = icosphere(RADIUS, 2)
    V = V * 1e-3
    result = bemshape.thickness(V, F, min_thickness=0.3)
    assert result["passed"] is False
    check = result["report"]["check"]
    area = result["report"]["mesh"]["area"]
    assert check["speck_area"] <= 1e-3 * area * (1 + 1e-9)
    assert check["thin_area"] > 0.5 * area
    warning = result["units_warning"]
    assert isinstance(warning, str) and "metres" in warning and "millimetres" in warning
    assert "units_check=False" in warning
    assert result["report"]["units_warning"] == warning
    quiet = bemshape.thickness(V, F, min_thickness=0.3, units_check=False)
    assert quiet["passed"] is False and quiet["units_warning"] is None
