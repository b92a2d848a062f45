"""The ring resampler (Section 4, step 3, :func:`equimesh.surface.ring.resample_ring`) and sharp corners on surfaces.

What must hold: the corners of the polyline are kept bit for bit, every
vertex lies on the polyline with its parameters interpolated there, every
polygon edge is at least l and at most 2l except the straight edge kept
next to a sharp corner, and Problem 2 meshes the polygon with every edge in
[l, 2l] at any corner angle down to 10 degrees (staggering that edge); a
surface whose flattened outline has such a corner is meshed with every
member of the plane triangulation in [l, 2l].
"""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from invariants import check_edge_lengths
from surface_invariants import assert_valid_surface_mesh

import equimesh
from equimesh._geometry import inner_angle
from equimesh.errors import SurfaceTooSmallError
from equimesh.planar.boundary.sides import stagger_reach
from equimesh.surface.charts.bezier import BezierSurface
from equimesh.surface.ring import resample_ring
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
    angle=st.floats(10.0, 160.0),  # the other two corners of the wedge at least 10 degrees too
    side=st.floats(8.0, 40.0),
    per_side=st.integers(1, 7),
    spacing=st.sampled_from([1.5, 2.0]),
)
def test_ring_is_a_step2_boundary_that_problem2_meshes_in_l_2l(angle, side, per_side, spacing):
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
    # Edges at least l; longer than 2l only as a straight edge from a sharp corner.
    edges = np.linalg.norm(np.roll(ring.points, -1, axis=0) - ring.points, axis=1)
    assert edges.min() >= 1.0 - REL_TOL
    sharp = [
        np.flatnonzero(np.all(ring.points == xy[c], axis=1))[0]
        for c in corners
        if stagger_reach(inner_angle(xy, c), 1.0)
    ]
    for j in np.flatnonzero(edges > 2.0 * (1.0 + REL_TOL)):
        assert j in sharp or (j + 1) % len(edges) in sharp
    # Problem 2 staggers the corner on those straight edges: Theorem 3 holds.
    check_edge_lengths(equimesh.uniform_triangulation(ring.points, 1.0, boundary_spacing=spacing), 1.0)


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


def test_sharp_corner_on_a_curved_nurbs_is_meshed_in_l_2l():
    """A bicubic NURBS on a skewed net (25-degree corners), domed and with uneven weights: every plane member in [l,
    2l]."""
    a = np.radians(25.0)
    s, t = np.meshgrid(np.linspace(0.0, 1.0, 4), np.linspace(0.0, 1.0, 4), indexing="ij")
    net = np.stack(
        [30.0 * s + 30.0 * np.cos(a) * t, 30.0 * np.sin(a) * t, 6.0 * np.sin(np.pi * s) * np.sin(np.pi * t)], axis=-1
    )
    weights = np.ones((4, 4))
    weights[1:3, 1:3] = 1.5
    surface = equimesh.NurbsSurface((3, 3), [0.0] * 4 + [1.0] * 4, [0.0] * 4 + [1.0] * 4, net, weights)
    mesh = equimesh.mesh_surface(surface, 1.5, optimize="none")
    corners = [mesh.stages.outline.vertices[mesh.stages.outline.side != np.roll(mesh.stages.outline.side, 1)]]
    assert len(corners[0]) == 4
    check_edge_lengths(mesh.stages.plane, 1.5)
    assert_valid_surface_mesh(mesh, surface)
