"""The ring resampler (Section 4, step 3, :func:`equimesh.surface.outline.resample_ring`) and sharp corners on surfaces.

What must hold: the corners of the polyline are kept bit for bit, every
vertex lies on the polyline with its parameters interpolated there, every
polygon edge is between l and 2l, and the points on the two sides of a corner
of any angle down to 10 degrees are at least l apart (Step 2 staggered as in
Problem 2); a surface whose flattened outline has such a corner is meshed
with every member of the plane triangulation in [l, 2l].
"""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from invariants import check_edge_lengths
from test_pipeline import assert_valid_surface_mesh

import equimesh
from equimesh.errors import SurfaceTooSmallError
from equimesh.surface.bezier import BezierSurface
from equimesh.surface.outline import inner_angle, resample_ring
from equimesh.tolerance import REL_TOL


def densified(corners, per_side):
    """The closed polyline through ``corners`` with ``per_side`` segments on each side, and the corners' indices."""
    corners = np.asarray(corners, dtype=float)
    t = np.arange(per_side)[:, None] / per_side
    xy = np.vstack([a + t * (b - a) for a, b in zip(corners, np.roll(corners, -1, axis=0))])
    return xy, np.arange(len(corners)) * per_side


def wedge(angle, side):
    """A counter-clockwise triangle with an ``angle``-degree corner at the origin between two sides ``side`` long."""
    a = np.radians(angle)
    return [(0.0, 0.0), (side, 0.0), (side * np.cos(a), side * np.sin(a))]


@given(
    angle=st.floats(10.0, 170.0),
    side=st.floats(8.0, 40.0),
    per_side=st.integers(1, 7),
    spacing=st.sampled_from([1.5, 2.0]),
)
def test_ring_edges_in_l_2l_and_sides_of_a_corner_l_apart(angle, side, per_side, spacing):
    xy, corners = densified(wedge(angle, side), per_side)
    params = xy @ np.array([[2.0, -1.0], [0.5, 3.0]]) + 7.0  # any affine map: interpolation must follow it
    ring = resample_ring(xy, params, corners, 1.0, spacing)
    # Corners kept bit for bit, each side in order.
    for i, c in enumerate(corners):
        first = np.flatnonzero(ring.side == i)[0]
        assert np.array_equal(ring.points[first], xy[c]) and np.array_equal(ring.params[first], params[c])
    assert np.all(np.diff(ring.side) >= 0)
    # Parameters interpolated where the vertex lies.
    np.testing.assert_allclose(ring.params, ring.points @ np.array([[2.0, -1.0], [0.5, 3.0]]) + 7.0, atol=1e-9)
    # Edges in [l, 2l].
    edges = np.linalg.norm(np.roll(ring.points, -1, axis=0) - ring.points, axis=1)
    assert edges.min() >= 1.0 - REL_TOL and edges.max() <= 2.0 * (1.0 + REL_TOL)
    # Points on the two sides of the sharp corner (at vertex 0) at least l apart.
    leaving, arriving = ring.points[ring.side == 0], ring.points[ring.side == 2]
    gaps = np.linalg.norm(leaving[1:, None] - arriving[None, :], axis=2)
    assert gaps.min() >= 1.0 - REL_TOL


def test_inner_angle_has_the_region_on_the_left():
    xy = np.array(wedge(30.0, 10.0))
    assert inner_angle(xy, 0) == pytest.approx(30.0)
    assert inner_angle(xy[::-1], 2) == pytest.approx(330.0)


def test_a_side_too_short_is_refused_by_the_callers_message():
    xy, corners = densified(wedge(80.0, 10.0), 3)
    with pytest.raises(SurfaceTooSmallError, match="side 0 of the boundary polyline is 10 long"):
        resample_ring(xy, xy, corners, 11.0, 1.5)
    with pytest.raises(KeyError):
        resample_ring(xy, xy, corners, 11.0, 1.5, too_short=lambda side, arc, chord: KeyError(side))


def parallelogram(angle, side):
    """A flat bilinear patch: a parallelogram with corners of ``angle`` and ``180 - angle`` degrees."""
    a = np.radians(angle)
    u, v = np.array([side, 0.0, 0.0]), side * np.array([np.cos(a), np.sin(a), 0.0])
    return BezierSurface(np.array([[0 * u, v], [u, u + v]]))


@pytest.mark.parametrize("angle", [10.0, 20.0, 40.0, 59.0])
def test_sharp_corner_on_a_surface_is_meshed_in_l_2l(angle):
    surface = parallelogram(angle, 30.0)
    mesh = equimesh.mesh_surface(surface, 1.5, optimize="none")
    check_edge_lengths(mesh.stages.plane, 1.5)
    assert_valid_surface_mesh(mesh, surface)
