"""Sound joints (``surface/optimize/joints.py``): every triangle angle on the surface at least its bound.

What must hold: the angles are the triangles' interior angles, at the vertex they are listed at; the barrier is zero
from one margin above a bound and grows as the square of the depth below that, and its Jacobian is its derivative
(on the surface, with sliding nodes, with nodes off the surface, next to a degenerate triangle); the bounds are 30
degrees except at a corner sharper than that; the test of soundness holds at the bounds exactly and fails below.
On the tiny grids of ``optimize_cases``; the driver's refusal of an end below the bounds is in ``test_driver.py``.
"""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays
from optimize_cases import finite_difference, moved, problem

import equimesh
from equimesh.metrics import triangle_angles
from equimesh.surface.optimize import UVProblem, joints
from equimesh.surface.optimize.joints import Joints, joint_bounds, surface_angles
from equimesh.testing.surfaces import dome

MARGIN = joints.JOINT_MARGIN


class Flat:
    """The plane z = 0 as a chart on [0, 1]^2: every point is its (u, v), exactly."""

    def evaluate(self, u, v):
        return np.column_stack([u, v, np.zeros_like(u)])

    def derivatives(self, u, v):
        one, zero = np.ones_like(u), np.zeros_like(u)
        return np.column_stack([one, zero, zero]), np.column_stack([zero, one, zero])


def test_surface_angles_by_hand():
    """A right isosceles triangle listed from each of its vertices, an obtuse one (135 degrees) and an equilateral
    one off every coordinate plane."""
    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    triangles = np.array([[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 1, 3], [1, 2, 4]])
    expected = [[90, 45, 45], [45, 45, 90], [45, 90, 45], [135, 26.56505117707799, 18.43494882292201], [60, 60, 60]]
    np.testing.assert_allclose(np.degrees(surface_angles(points, triangles)), expected, rtol=1e-13)


def test_surface_angles_are_the_metrics_angles():
    p, triangles = problem(seed=1)
    points = p.points_of(p.x0)
    np.testing.assert_allclose(
        np.degrees(surface_angles(points, triangles)), triangle_angles(points, triangles), atol=1e-9
    )


def numpys_angles(points, triangles):
    """The angles as NumPy computes them: ``atan2(|u x v|, u . v)`` by ``np.cross``, ``np.linalg.norm``, ``np.sum``."""
    angles = np.empty(triangles.shape)
    for k in range(3):
        u, v = (
            points[triangles[:, (k + 1) % 3]] - points[triangles[:, k]],
            points[triangles[:, (k + 2) % 3]] - points[triangles[:, k]],
        )
        angles[:, k] = np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.sum(u * v, axis=1))
    return angles


@given(
    st.integers(3, 40).flatmap(
        lambda n: st.tuples(
            arrays(np.float64, (n, 3), elements=st.floats(-1e3, 1e3, allow_subnormal=False)),
            arrays(np.int64, (2 * n, 3), elements=st.integers(0, n - 1)),
        )
    )
)
def test_surface_angles_are_numpys_to_the_bit(case):
    """The compiled angles are NumPy's formula's to the last bit, degenerate triangles (a node twice, coincident
    points: the sign of a zero decides ``atan2``) included: the optimisation's iterates do not depend on which ran."""
    points, triangles = case
    np.testing.assert_array_equal(surface_angles(points, triangles), numpys_angles(points, triangles))


def test_the_barrier_is_the_squared_depth_below_one_margin_above_the_bound():
    """``weight (1 - (theta - bound) / margin)^2`` per angle, corner by corner (all triangles' first angles, then
    their second, their third), zero from one margin above the bound."""
    p, triangles = problem(rise=0.0)
    angles = surface_angles(p.points_of(p.x0), triangles)
    depth = np.zeros_like(angles)
    depth[0, 0], depth[3, 1], depth[7, 2] = 0.5, 2.0, 1.0  # bounds half a margin, one margin above and at the angle
    bounds = angles - (1.0 - depth) * MARGIN  # depth 0 elsewhere: each angle one margin above its bound
    bounds[5, 0] = angles[5, 0] - 4.0 * MARGIN  # four margins above: no term either
    residuals, _ = Joints(p, triangles, bounds).barrier(3.0)
    np.testing.assert_allclose(residuals(p.x0).reshape(3, -1).T, 3.0 * depth**2, atol=1e-12)


def active_bounds(p, triangles, x):
    """Bounds within a margin of most angles at ``x`` (the barrier acts), the first triangle's far below its angles
    (its terms zero)."""
    angles = surface_angles(p.points_of(x), triangles)
    bounds = angles - MARGIN * np.random.default_rng(7).uniform(0.2, 0.9, angles.shape)
    bounds[0] = angles[0] - 5 * MARGIN
    return bounds


@pytest.mark.parametrize(
    "slides, tolerance, offset",
    [(False, 0.0, 0.0), (True, 0.0, 0.0), (True, 0.8, 0.6)],
    ids=["inner", "sliding", "off"],
)
def test_the_barriers_jacobian_is_its_derivative(slides, tolerance, offset):
    """Inner nodes free; the rim sliding along the square; and every moving node off the surface, far enough that
    the normal's own derivative counts."""
    p, triangles = problem(seed=2, slides=slides, surface_tolerance=tolerance)
    x = moved(p, 5, offset=offset)
    residuals, jacobian = Joints(p, triangles, active_bounds(p, triangles, x)).barrier(3.0)
    assert np.count_nonzero(residuals(x)) > 20 and not np.any(residuals(x)[:: len(triangles)])
    expected = finite_difference(residuals, x)
    got = jacobian(x)
    assert got.shape == (3 * len(triangles), len(x))
    np.testing.assert_allclose(got.toarray(), expected, atol=1e-6 * np.abs(expected).max())


def test_a_corner_between_parallel_sides_has_no_gradient():
    """Three nodes on a line, listed from either end: at the first node the two sides are parallel and the angle
    has no gradient (zero rows, not NaN, whichever side's perpendicular part rounds to zero); the triangle after
    them still has its own."""
    uv = np.array([[0.0, 0.0], [0.125, 0.125], [0.1, 0.1], [0.125, 0.0]])
    edges = np.array([[0, 1], [1, 2], [2, 0], [0, 3], [1, 3]])
    p = UVProblem(Flat(), uv, edges, np.ones(5, dtype=np.int8), 8.0, np.ones(4, dtype=bool))
    triangles = np.array([[0, 1, 2], [0, 2, 1], [0, 3, 1]])
    bounds = np.radians([[80.0, 80.0, 80.0], [80.0, 80.0, 80.0], [50.0, 100.0, 50.0]])  # every angle below it
    residuals, jacobian = Joints(p, triangles, bounds).barrier(1.0)
    jac = jacobian(p.x0).toarray()
    assert np.all(np.isfinite(jac)) and not np.any(jac[[0, 1]])
    np.testing.assert_allclose(jac[2::3], finite_difference(residuals, p.x0)[2::3], atol=1e-6)
    assert np.all(np.abs(jac[2::3]).sum(axis=1) > 0)


def test_the_barriers_jacobian_keeps_its_structure():
    """The entries of the angles whose terms are zero are kept (as zeros): one pattern for the normal equations
    whichever angles are near their bounds."""
    p, triangles = problem(seed=2)
    angles = surface_angles(p.points_of(p.x0), triangles)
    asleep = Joints(p, triangles, angles - 5 * MARGIN).barrier(3.0)[1](p.x0)
    awake = Joints(p, triangles, angles - 0.5 * MARGIN).barrier(3.0)[1](p.x0)
    assert not np.any(asleep.data) and np.all(awake.data)
    np.testing.assert_array_equal(asleep.indptr, awake.indptr)
    np.testing.assert_array_equal(asleep.indices, awake.indices)


def test_bounds_are_30_degrees_but_at_a_sharper_corner():
    """A node whose angles sum to less than 30 degrees (a corner of the input) bounds its angles by that sum less
    the barrier's margin; every other angle is bounded by 30 degrees."""
    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [10.0, 2.0, 0.0]])
    triangles = np.array([[0, 1, 2], [1, 3, 2]])

    bounds = np.degrees(joint_bounds(Flat(), points[:, :2], triangles))
    angles = triangle_angles(points, triangles)
    sharp = angles[1, 1]  # node 3 is in one triangle only, with an angle of about 8 degrees
    assert sharp < 30 and angles[1, 0] + angles[0, 1] > 30 and angles[1, 2] + angles[0, 2] > 30
    assert bounds[1, 1] == pytest.approx(sharp - np.degrees(MARGIN))
    np.testing.assert_allclose(np.delete(bounds.ravel(), 4), 30.0, rtol=1e-14)


def test_sound_holds_at_the_bounds_and_fails_just_below():
    """The check fires: one angle a rounding below its bound makes the mesh unsound."""
    p, triangles = problem(seed=3)
    angles = surface_angles(p.points_of(p.x0), triangles)
    assert Joints(p, triangles, angles).sound(p.x0)
    bounds = angles.copy()
    bounds[4, 2] = np.nextafter(angles[4, 2], np.inf)
    assert not Joints(p, triangles, bounds).sound(p.x0)
    assert p.sound(p.x0)  # a problem without joints keeps no bounds


def test_the_violation_names_the_triangles_below_their_bounds():
    """On the flat grid every triangle has angles 90, 45 and 45 degrees."""
    p, triangles = problem(rise=0.0)
    bounds = np.full(triangles.shape, np.radians(30.0))
    assert Joints(p, triangles, bounds).violation(p.x0) == (
        "0 of 18 triangles with an angle below 0 degrees (smallest 45)"
    )
    bounds[0, 0] = bounds[3, 0] = bounds[3, 2] = np.radians(50.0)  # 45, 45 and 90 degrees
    bounds[9, 0] = np.radians(46.0)
    angles = surface_angles(p.points_of(p.x0), triangles)
    bounds[5, 1] = angles[5, 1]  # at its bound, not below
    assert Joints(p, triangles, bounds).violation(p.x0) == (
        "3 of 18 triangles with an angle below 50 degrees (smallest 45)"
    )


def test_the_papers_objective_keeps_its_angles_unbounded():
    """ "paper" is the paper's: no angle barrier, no angle check (its result on a steep dome has slivers)."""
    records = equimesh.surface.optimize.OBJECTIVES
    assert records["classes"].sound_joints and records["bounded"].sound_joints and not records["paper"].sound_joints
    mesh = equimesh.mesh_surface(dome(rise=40.0), 8.0, optimize="paper", grid=(8, 8))
    assert triangle_angles(mesh.points, mesh.triangles).min() < 30.0
