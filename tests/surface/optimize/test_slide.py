"""Boundary nodes sliding along a closed polyline between its corners (``surface/optimize/slide.py``)."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh._geometry import Polyline
from equimesh.surface.optimize.slide import along_polygon, between_corners
from equimesh.tolerance import REL_TOL

#: The square of side 1: length 4, its corners at arc positions 0, 1, 2, 3.
SQUARE = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


def test_nodes_slide_between_the_corners_before_and_after_them():
    """Each node's bounds are the corners around it, the last segment ending at the first corner one turn later."""
    loop = Polyline(SQUARE)
    nodes = np.array([10, 11, 12, 13])
    s = np.array([0.25, 1.5, 3.75, 2.0 + 1e-3])
    slide, fixed = between_corners(nodes, loop, s, np.array([0.0, 2.0, 3.0]))
    assert fixed.size == 0
    np.testing.assert_array_equal(slide.nodes, nodes)
    np.testing.assert_array_equal(slide.s, s)
    np.testing.assert_array_equal(slide.lower, [0.0, 0.0, 3.0, 2.0])
    np.testing.assert_array_equal(slide.upper, [2.0, 2.0, 4.0, 3.0])
    assert slide.loop is loop


def test_corners_need_not_start_at_zero():
    """Corners at 0.5 and 2.5 of 4: a node before 0.5 (at 4.25, one turn on) slides between 2.5 and 4.5."""
    slide, fixed = between_corners(
        np.array([0, 1, 2]), Polyline(SQUARE), np.array([1.0, 3.0, 4.25]), np.array([0.5, 2.5])
    )
    assert fixed.size == 0
    np.testing.assert_array_equal(slide.lower, [0.5, 2.5, 2.5])
    np.testing.assert_array_equal(slide.upper, [2.5, 4.5, 4.5])


def test_a_node_within_rel_tol_of_a_corner_is_at_it():
    """Within ``REL_TOL`` of the loop's length from a corner, on either side and up to that distance, a node is fixed;
    twice as far it slides.  The first corner one turn later is a corner too."""
    side = 0.9313225746154785  # REL_TOL times the square's length is 2^-28: every distance below is exact
    loop = Polyline(side * np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]))
    near, length, last = REL_TOL * loop.length, loop.length, loop.arc[-2]
    assert near == 2.0**-28 and (side + near) - side == near and side - (side - near) == near
    s = [
        0.0,
        near,
        side - near,
        side,
        side + near,
        length,
        2 * near,
        side - 2 * near,
        side + 2 * near,
        length - 2 * near,
    ]
    nodes = np.arange(len(s)) + 100
    slide, fixed = between_corners(nodes, loop, np.array(s), loop.arc[:-1])
    np.testing.assert_array_equal(fixed, nodes[:6])
    np.testing.assert_array_equal(slide.nodes, nodes[6:])
    np.testing.assert_array_equal(slide.lower, [0.0, 0.0, side, last])
    np.testing.assert_array_equal(slide.upper, [side, side, 2 * side, length])


@st.composite
def loops_and_nodes(draw):
    """A closed polyline (a jittered circle), some of its vertices as corners, nodes at positions around it."""
    n = draw(st.integers(3, 12))
    radii = np.array(draw(st.lists(st.floats(0.5, 2.0), min_size=n, max_size=n)))
    angles = 2 * np.pi * np.arange(n) / n
    loop = Polyline(radii[:, None] * np.column_stack([np.cos(angles), np.sin(angles)]))
    chosen = draw(st.lists(st.booleans(), min_size=n, max_size=n))
    first = draw(st.integers(0, n - 1))
    chosen[first] = True
    corners = loop.arc[:-1][np.array(chosen)]
    s = np.array(draw(st.lists(st.floats(0.0, 1.0), min_size=1, max_size=20)))
    s = corners[0] + s * loop.length
    at_corner = draw(st.lists(st.integers(0, len(corners) - 1), max_size=3))
    s = np.concatenate([s, corners[at_corner]])
    return loop, corners, s


@settings(max_examples=50, deadline=None)
@given(loops_and_nodes())
def test_every_node_slides_between_two_consecutive_corners_or_is_fixed(case):
    """The nodes are split, in order, into those sliding, strictly inside the arc between two consecutive corners
    (the first one turn later closing the loop) and farther than ``REL_TOL`` of its length from both, and those
    fixed, within that distance of one."""
    loop, corners, s = case
    nodes = np.arange(len(s)) * 3 + 7
    slide, fixed = between_corners(nodes, loop, s, corners)
    ends = np.append(corners, corners[0] + loop.length)
    near = REL_TOL * loop.length
    assert np.array_equal(np.sort(np.concatenate([slide.nodes, fixed])), nodes)
    sliding = np.isin(nodes, slide.nodes)
    np.testing.assert_array_equal(slide.s, s[sliding])
    assert np.all((slide.s - slide.lower > near) & (slide.upper - slide.s > near))
    k = np.searchsorted(ends, slide.lower)
    np.testing.assert_array_equal(ends[k], slide.lower)
    np.testing.assert_array_equal(ends[k + 1], slide.upper)
    distance = np.abs(s[~sliding, None] - ends[None, :]).min(axis=1, initial=np.inf)
    assert np.all(distance <= near)


def test_along_a_polygon_every_vertex_is_a_corner():
    """Nodes on the edges of a rectangle slide along the edge they lie on, at their arc position; nodes at vertices
    are fixed; the loop's points, directions and arc positions are the polygon's."""
    rectangle = [[0, 0], [2, 0], [2, 1], [0, 1]]  # integers: taken as floats
    uv = np.array([[0.5, 0.0], [2.0, 0.25], [1.5, 1.0], [0.0, 0.5], [2.0, 1.0], [0.0, 0.0]])
    slide, fixed = along_polygon(np.arange(6), rectangle, uv)
    np.testing.assert_array_equal(fixed, [4, 5])
    np.testing.assert_array_equal(slide.nodes, [0, 1, 2, 3])
    np.testing.assert_array_equal(slide.loop.points, np.array(rectangle, dtype=float))
    assert slide.loop.points.dtype == float and slide.loop.closed
    np.testing.assert_allclose(slide.s, [0.5, 2.25, 3.5, 5.5], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(slide.lower, [0.0, 2.0, 3.0, 5.0])
    np.testing.assert_array_equal(slide.upper, [2.0, 3.0, 5.0, 6.0])
    np.testing.assert_allclose(slide.uv(slide.s), uv[:4], rtol=0, atol=1e-15)
    np.testing.assert_array_equal(slide.direction(slide.s), [[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]])


def test_a_node_off_the_polygon_slides_from_its_projection():
    """A node near, not on, an edge takes the arc position of its nearest point of the polygon."""
    slide, fixed = along_polygon(np.array([3]), SQUARE, np.array([[1.1, 0.4]]))
    assert fixed.size == 0
    np.testing.assert_allclose(slide.s, [1.4], rtol=0, atol=1e-15)
    np.testing.assert_array_equal([slide.lower, slide.upper], [[1.0], [2.0]])
