"""bemshape.features at points of the ball against its closed form (support.Ball): s = A·x
and ∇s = A·I inside, f_h = 3·h0²·A, h_f = h0(1/f_h − a); zero features outside."""

import numpy as np
import pytest

import bemshape
from support import Ball, icosphere

H0, A, RADIUS = 0.3, 0.2, 0.5
BALL = Ball(RADIUS, H0, A)

INSIDE = np.array([[0, 0, 0], [0.1, 0.05, -0.1], [-0.2, 0.1, 0.15], [0, 0, 0.3],
                   [0.25, -0.05, 0]])
OUTSIDE = np.array([[0.7, 0, 0], [0.4, 0.4, 0.1]])


@pytest.fixture(scope="module")
def result():
    V, F = icosphere(RADIUS, 3)
    return bemshape.features(V, F, np.vstack([INSIDE, OUTSIDE]), h0=H0)


def test_inside_points_match_the_closed_form(result):
    inside = slice(0, len(INSIDE))
    assert result["inside"].dtype == np.bool_
    assert result["inside"].tolist() == [True] * len(INSIDE) + [False] * len(OUTSIDE)
    assert result["f_h"][inside] == pytest.approx(BALL.f_h, rel=0.01)
    assert result["h_f"][inside] == pytest.approx(BALL.h_f, rel=0.02)
    assert np.max(np.linalg.norm(result["s"][inside] - BALL.A * INSIDE, axis=1)) < 0.01 * BALL.A * RADIUS
    # ∇s = A·I: grad_s[p, i, j] = ∂s_i/∂x_j.
    assert np.max(np.abs(result["grad_s"][inside] - BALL.A * np.eye(3))) < 0.02 * BALL.A


def test_outside_points_have_no_features(result):
    outside = slice(len(INSIDE), None)
    assert np.all(result["winding"][outside] < 0.5)
    for key in ("f_h", "h_f", "h_p"):
        assert np.all(result[key][outside] == 0.0)


def test_shapes_dtypes_views_and_report(result):
    n = len(INSIDE) + len(OUTSIDE)
    for key in ("winding", "f_h", "h_f", "h_p"):
        assert result[key].shape == (n,) and result[key].dtype == np.float64
    for key in ("s", "eigenvalues", "n_f", "t_f", "across"):
        assert result[key].shape == (n, 3) and result[key].dtype == np.float64
    assert result["grad_s"].shape == (n, 3, 3)
    assert result["skeleton"].shape == (n,) and result["skeleton"].dtype == np.bool_
    for key in ("s", "grad_s", "h_p", "inside"):
        assert not result[key].flags.owndata
    report = result["report"]
    assert report["command"] == "features"
    assert report["points"]["count"] == n and report["points"]["inside"] == len(INSIDE)
    assert report["features"]["h_f"]["min"] == pytest.approx(BALL.h_f, rel=0.02)


def test_h0_is_required_and_bad_points_are_refused():
    V, F = icosphere(RADIUS, 1)
    with pytest.raises(TypeError):
        bemshape.features(V, F, INSIDE)
    with pytest.raises(ValueError, match=r"points must have shape \(n, 3\)"):
        bemshape.features(V, F, INSIDE[:, :2], h0=H0)
