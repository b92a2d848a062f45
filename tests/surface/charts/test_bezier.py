"""Tensor-product Bezier surfaces: evaluation, derivatives, validation (Section 4, step 1)."""

import numpy as np
import pytest
from chart_checks import assert_derivatives_consistent
from hypothesis import given, settings
from hypothesis import strategies as st
from invariants import check_edge_lengths

import equimesh
from equimesh.errors import InvalidSurfaceError
from equimesh.surface.charts.bezier import BezierSurface, bernstein, de_casteljau
from equimesh.surface.charts.chart import UNIT, Chart

degrees = st.integers(min_value=1, max_value=5)


seeds = st.integers(min_value=0, max_value=2**32 - 1)


def random_net(m, n, seed):
    return np.random.default_rng(seed).uniform(-10.0, 10.0, size=(m + 1, n + 1, 3))


@settings(max_examples=40, deadline=None)
@given(m=degrees, n=degrees, seed=seeds)
def test_evaluate_matches_de_casteljau(m, n, seed):
    """Bernstein evaluation equals repeated linear interpolation for every degree 1..5."""
    net = random_net(m, n, seed)
    surface = BezierSurface(net)
    uv = np.random.default_rng(seed + 1).uniform(0.0, 1.0, size=(7, 2))
    got = surface.evaluate(uv[:, 0], uv[:, 1])
    want = np.array([de_casteljau(net, u, v) for u, v in uv])
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-11 * np.abs(net).max())


@settings(max_examples=40, deadline=None)
@given(m=degrees, n=degrees, seed=seeds)
def test_derivatives_match_finite_differences(m, n, seed):
    """First and second partials against central differences (of X^s, and of the first partials)."""
    surface = BezierSurface(random_net(m, n, seed))
    uv = np.random.default_rng(seed + 2).uniform(0.05, 0.95, size=(5, 2))
    scale = np.abs(surface.control_points).max() * max(m, n) ** 2
    assert_derivatives_consistent(surface, uv[:, 0], uv[:, 1], atol=1e-6 * scale)


def test_corners_interpolate_control_net_exactly():
    net = random_net(3, 2, 7)
    s = BezierSurface(net)
    for (u, v), (i, j) in {(0, 0): (0, 0), (1, 0): (-1, 0), (0, 1): (0, -1), (1, 1): (-1, -1)}.items():
        assert np.array_equal(s.evaluate(u, v), net[i, j])


def test_evaluation_broadcasts_and_keeps_shape():
    s = BezierSurface(random_net(2, 3, 1))
    u = np.linspace(0, 1, 12).reshape(3, 4)
    assert s.evaluate(u, u.T.T).shape == (3, 4, 3)
    assert s.evaluate(0.3, np.linspace(0, 1, 5)).shape == (5, 3)
    su, sv = s.derivatives(np.zeros((2, 2)), 0.5)
    assert su.shape == sv.shape == (2, 2, 3)
    assert s.evaluate(0.5, 0.5).shape == (3,)


def test_bernstein_partition_of_unity():
    t = np.linspace(0, 1, 11)
    for degree in range(1, 7):
        np.testing.assert_allclose(bernstein(degree, t).sum(axis=-1), 1.0, rtol=0, atol=1e-14)


def test_bilinear_patch_is_bilinear():
    net = np.array([[[0, 0, 0], [0, 2, 1]], [[3, 0, 2], [3, 2, 5]]], dtype=float)
    s = BezierSurface(net)
    u, v = 0.25, 0.6
    want = (1 - u) * (1 - v) * net[0, 0] + u * (1 - v) * net[1, 0] + (1 - u) * v * net[0, 1] + u * v * net[1, 1]
    np.testing.assert_allclose(s.evaluate(u, v), want, atol=1e-14)


def test_satisfies_protocol():
    s = BezierSurface(random_net(3, 3, 5))
    assert isinstance(s, Chart)
    assert s.degree == (3, 3) and s.domain == UNIT


@pytest.mark.parametrize(
    "net, fragment",
    [
        (np.zeros((3, 3)), "shape (m+1, n+1, 3), got (3, 3)"),
        (np.zeros((3, 3, 2)), "got (3, 3, 2)"),
        (np.zeros((1, 4, 3)), "at least 2 x 2 points, got 1 x 4"),
        (np.full((2, 2, 3), np.inf), "control point [0][0] has a non-finite coordinate"),
        ([[[0, 0, 0], [1, 1, 1]], [[0, 0, 0]]], "equal row lengths"),
        ([[["a", 0, 0], [1, 1, 1]], [[0, 0, 0], [1, 1, 1]]], "array of numbers"),
    ],
)
def test_constructor_validation_messages(net, fragment):
    with pytest.raises(InvalidSurfaceError) as err:
        BezierSurface(net)
    assert fragment in str(err.value)
    assert isinstance(err.value, ValueError)


def test_bezier_degree_above_the_limit_is_refused():
    """A net one degree above MAX_DEGREE is refused by name, saying why; one at MAX_DEGREE is meshed."""
    from equimesh.surface.charts.bezier import MAX_DEGREE

    net = np.zeros((MAX_DEGREE + 2, 2, 3))
    net[..., 0] = np.linspace(0.0, 80.0, MAX_DEGREE + 2)[:, None]
    net[:, 1, 1] = 80.0
    with pytest.raises(
        InvalidSurfaceError, match=rf"degree {MAX_DEGREE + 1} x 1; at most degree {MAX_DEGREE} .* evaluating"
    ):
        BezierSurface(net)
    mesh = equimesh.mesh_surface(BezierSurface(net[1:]), 10.0, optimize="none")
    check_edge_lengths(mesh.stages.plane, 10.0)
