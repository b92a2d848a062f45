"""Validation of the input polygon (``planar/polygon.py``), case by case: what is refused, with which line, and what is
not.

Each case is built by hand at the edge of one check: a repeated vertex that
sorting by y alone would not find, a fold-back that a sum over all vertices
would miss, a bottom edge of three collinear vertices (the orientation must
be read at the lowest-leftmost vertex), angles exactly at the REL_TOL
tolerance of Problem 1 and a hair beyond it, an extent exactly at
``MAX_EXTENT l``, coordinates whose span overflows, object arrays of
fractions (accepted) and of complex numbers (refused).  Messages are compared
in full: they are the caller's only account of what is wrong.
"""

import math
import re
import warnings
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given
from strategies import problems

import equimesh
from equimesh import InvalidLengthError, InvalidPolygonError
from equimesh.planar.increment import validate_problem1
from equimesh.planar.polygon import as_polygon, check_edges_at_least
from equimesh.testing.generators import rectangle, regular_polygon
from equimesh.tolerance import MAX_EXTENT

REFUSED = [
    # Sorted by y alone, the two copies of (2, 0) are not neighbours: (0, 0), (2, 0), (4, 0), (2, 0).
    ([[0, 0], [2, 0], [4, 0], [4, 3], [2, 0]], None, "vertices 1 and 4 coincide at (2, 0)"),
    ([[0, 0], [1, 1], [2, 2]], None, "polygon has zero area (all vertices collinear)"),
    # Folds back at vertex 4; the dot products of all vertices sum to +1 (the straight vertex 1 gives +25).
    (
        [[0, 0], [5, 0], [10, 0], [10, 10], [4, 10], [6, 10], [0, 10]],
        None,
        "polygon folds back on itself at vertex 4 at (4, 10)",
    ),
    ([[-1e308, 0], [1e308, 0], [0, 1e308]], None, "polygon coordinates span more than the floating-point range"),
    (
        [[0, 0], [3e5, 0], [0, 1]],
        2.0,
        "polygon spans 300000.0 = 150000.0 l, more than the 65536 l within which edge lengths "
        "are exact to REL_TOL; use l >= 4.57763671875",
    ),
    (
        [[0, 0], [2.0**16 + 2.0**-30, 0], [0, 1]],
        1.0,
        "polygon spans 65536.00000000093 = 65536.00000000093 l, more than the "
        "65536 l within which edge lengths are exact to REL_TOL; use l >= 1.0000000000000142",
    ),
    ([[0, 0], [1]], None, "polygon vertices must be an array of numbers"),
    ([[0, 0], ["a", 1], [2, 2]], None, "polygon vertices must be an array of numbers"),
    ([[1, 1]], None, "a polygon needs at least 3 distinct vertices, got 1"),
    # Edges 1 and 3 cross; the boxes of the segments (x_a, x_b)-(y_a, y_b) would not overlap.
    (
        [[6, 2], [3, 6], [0, 2], [0, 3]],
        None,
        "polygon is not simple (self-intersecting): edge (1, 2) intersects edge (3, 0)",
    ),
    ([[0, 0], [4, 0], [4, float("nan")], [0, 4]], None, "vertex 2 has a non-finite coordinate (4.0, nan)"),
    ([[Decimal(0), 0], [1, 1j], [2, 3]], None, "polygon vertices must be real numbers, got complex values"),
    ([[0, 0], [1, 1j], [2, 3]], None, "polygon vertices must be real numbers, got complex values"),
]


@pytest.mark.parametrize("vertices, l, message", REFUSED)
def test_refused_with_one_line_naming_the_problem(vertices, l, message):
    """No warning on the way (an overflowing span is expected and handled), then our error with its message."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(InvalidPolygonError) as err:
            as_polygon(
                np.array(vertices, dtype=object)
                if any(isinstance(x, Decimal) for row in vertices for x in row)
                else vertices,
                l,
            )
    assert str(err.value) == message


def test_extent_exactly_max_extent_l_is_accepted():
    """The bound is inclusive: a span of exactly MAX_EXTENT l is within the exact range."""
    poly = as_polygon([[0, 0], [MAX_EXTENT, 0], [0, 1]], 1.0)
    assert poly.local.max() == MAX_EXTENT


def test_fractions_are_real_numbers():
    """An object array of exact fractions is accepted and converted to floats."""
    poly = as_polygon(np.array([[Fraction(0), 0], [Fraction(4), 0], [0, Fraction(4)]], dtype=object))
    assert poly.vertices.dtype == float
    np.testing.assert_array_equal(poly.vertices, [[0, 0], [4, 0], [0, 4]])


def test_orientation_is_read_at_the_lowest_leftmost_vertex():
    """Three collinear vertices on the bottom edge, the middle one first: a counter-clockwise ring is kept as it is,
    the same ring clockwise is reversed (the first vertex with the smallest y alone would give orientation 0)."""
    ccw = np.array([[2, 0], [4, 0], [4, 4], [0, 4], [0, 0]], float)
    np.testing.assert_array_equal(as_polygon(ccw).vertices, ccw)
    np.testing.assert_array_equal(as_polygon(ccw[::-1]).vertices, ccw)
    hole = as_polygon(np.array([[-1, -1], [5, -1], [5, 5], [-1, 5]], float), None, [ccw[::-1] * 0.5 + 0.5]).holes[0]
    np.testing.assert_array_equal(hole.vertices, ccw[::-1] * 0.5 + 0.5)  # a hole stays clockwise


@pytest.mark.parametrize(
    "ccw",
    [
        [[0, 0], [10, 1], [40, 0.5], [40, 2], [0, 5]],  # vertex -2 lies right of the edge leaving the corner
        [[0, 0], [5, 0], [2, 40], [0.5, 40], [1, 10]],  # vertex 2 lies right of the edge entering the corner
    ],
)
def test_orientation_is_read_from_the_two_neighbours_of_the_corner(ccw):
    """Non-convex rings: only the corner's own neighbours tell the orientation, no other vertex does."""
    ccw = np.array(ccw, float)
    np.testing.assert_array_equal(as_polygon(ccw).vertices, ccw)
    np.testing.assert_array_equal(as_polygon(ccw[::-1]).vertices, ccw)


def test_inner_angle_of_a_reflex_vertex():
    """Polygon.inner_angle is in [0, 360): 270 degrees at the notch of an L."""
    poly = as_polygon([[0, 0], [4, 0], [4, 2], [2, 2], [2, 4], [0, 4]])
    assert [poly.inner_angle(i) for i in range(6)] == [90.0, 90.0, 90.0, 270.0, 90.0, 90.0]


# Problem 1 (Section 2): convex, inner angles >= 90 degrees, each up to REL_TOL relative to the edges' lengths.
# Vertex 1 turns right by exactly REL_TOL (cross = -1e-9 |e_in| |e_out|), vertex 2 is 90 degrees less exactly
# REL_TOL (dot = -1e-9 |e_in| |e_out|): both exactly at the tolerance, accepted, at unit and at longer edges.
AT_TOLERANCE = np.array([[0, 1e-9], [1, 1e-9], [2, 0], [2, 2], [0, 2]])


@pytest.mark.parametrize("scale", [1.0, 4.0])
def test_problem1_angles_exactly_at_the_tolerance_are_accepted(scale):
    poly, _ = validate_problem1(AT_TOLERANCE * scale, 1.0)
    assert len(poly.vertices) == 5


@pytest.mark.parametrize(
    "vertices, message",
    [
        (
            [[0, 2e-9], [1, 2e-9], [2, 0], [2, 2], [0, 2]],
            "polygon is not convex: reflex angle at vertex 1 at (1, 2e-09)",
        ),
        (
            [[0, 0], [2, 0], [2 - 4e-9, 2], [0, 2]],
            "inner angle 89.99999989 degrees at vertex 1 at (2, 0) is below 90 degrees",
        ),
    ],
)
def test_problem1_angles_twice_the_tolerance_away_are_refused(vertices, message):
    with pytest.raises(InvalidPolygonError) as err:
        validate_problem1(vertices, 1.0)
    assert str(err.value) == message


def _square(x, y, side):
    return [[x, y], [x + side, y], [x + side, y + side], [x, y + side]]


OUTER = [[0, 0], [10, 0], [10, 10], [0, 10]]


L_SHAPE = [[0, 0], [10, 0], [10, 4], [4, 4], [4, 10], [0, 10]]


TALL = [[0, 5], [10, 5], [10, 15], [0, 15]]

HOLES_REFUSED = [
    (OUTER, 5, None, "holes must be a list of polygons, got int"),
    (OUTER, [_square(8, 8, 3)], 1.0, "hole 0 is not inside the polygon: its vertex 1 at (11, 8) lies outside"),
    (
        OUTER,
        [[[0, 4], [2, 4], [2, 6]]],
        None,
        "hole 0 overlaps the boundary of the polygon (their edges cross or touch)",
    ),
    (L_SHAPE, [_square(6, 6, 2)], None, "hole 0 lies outside the polygon"),
    (OUTER, [_square(2, 2, 3), _square(4, 4, 3)], None, "hole 0 and hole 1 overlap"),
    (
        OUTER,
        [_square(0.5, 4, 2)],
        1.0,
        "hole 0 is 0.5 from the boundary of the polygon, closer than l = 1.0 (Lemma 3 (1)); move it or use l <= 0.5",
    ),
    (
        OUTER,
        [_square(6, 6, 2), _square(1.5, 1.5, 2), _square(4.25, 1.5, 2)],
        1.0,
        "hole 1 and hole 2 are 0.75 apart, closer than l = 1.0 (Lemma 3 (1)); move them apart or use l <= 0.75",
    ),
    # The same two at l = 4 (local frame scaled by 1/4): distances in the caller's units.
    (
        np.multiply(OUTER, 4),
        [_square(2, 16, 8)],
        4.0,
        "hole 0 is 2.0 from the boundary of the polygon, closer than l = 4.0 (Lemma 3 (1)); move it or use l <= 2.0",
    ),
    (
        np.multiply(OUTER, 4),
        [_square(24, 24, 8), _square(6, 6, 8), _square(17, 6, 8)],
        4.0,
        "hole 1 and hole 2 are 3.0 apart, closer than l = 4.0 (Lemma 3 (1)); move them apart or use l <= 3.0",
    ),
    # The bounding box is read per axis: x from 0 to 10, y from 5 to 15.
    (TALL, [_square(2, 2, 2)], None, "hole 0 is not inside the polygon: its vertex 0 at (2, 2) lies outside"),
    (TALL, [_square(11, 6, 2)], None, "hole 0 is not inside the polygon: its vertex 0 at (11, 6) lies outside"),
    # A vertex on the box's edge is not outside it; the hole touches the boundary.
    (
        TALL,
        [[[8, 6], [10, 7], [8, 8]]],
        None,
        "hole 0 overlaps the boundary of the polygon (their edges cross or touch)",
    ),
    (OUTER, [[[2, 2], [3, np.nan], [2, 3]]], None, "vertex 1 of hole 0 has a non-finite coordinate (3.0, nan)"),
    (OUTER, [[[2, 2], [3, 3], [2, 2]]], None, "hole 0 needs at least 3 distinct vertices, got 2"),
    (OUTER, [[[2, 2], [4, 2], [4, 4], [4, 2], [2, 4]]], None, "vertices 1 and 3 of hole 0 coincide at (4, 2)"),
    (
        OUTER,
        [[[2, 2], [4, 2], [2, 4], [4, 4]]],
        None,
        "hole 0 is not simple (self-intersecting): edge (1, 2) of hole 0 intersects edge (3, 0) of hole 0",
    ),
    (OUTER, [_square(6, 6, 2), _square(1, 1, 2), _square(2, 2, 2)], None, "hole 1 and hole 2 overlap"),
]


@pytest.mark.parametrize("outer, holes, l, message", HOLES_REFUSED)
def test_holes_refused_naming_the_hole(outer, holes, l, message):
    with pytest.raises(InvalidPolygonError) as err:
        as_polygon(outer, l, holes)
    assert str(err.value) == message


def test_holes_are_clockwise_rings_in_the_outer_frame():
    """Two holes 2 apart (>= l), either orientation given: clockwise, same frame, labelled; no l, no distance check."""
    poly = as_polygon(OUTER, 1.0, [_square(2, 2, 2), _square(6, 6, 2)[::-1]])
    assert poly.label == "" and [h.label for h in poly.holes] == ["hole 0", "hole 1"]
    assert [h.vertices.tolist() for h in poly.holes] == [
        [[2, 4], [4, 4], [4, 2], [2, 2]],
        [[6, 8], [8, 8], [8, 6], [6, 6]],
    ]
    assert all(h.frame == poly.frame for h in poly.holes)
    assert len(as_polygon(OUTER, None, [_square(2, 2, 2), _square(4.5, 2, 2)]).holes) == 2
    assert as_polygon(OUTER, 1.0, []).holes == ()


def test_holes_whose_bounding_boxes_overlap_are_apart():
    """Two triangles with overlapping bounding boxes, 1.06 apart: no overlap (the shapes are compared, not the
    boxes)."""
    holes = [[[2, 2], [6, 2], [2, 6]], [[6.5, 3], [6.5, 7], [2.5, 7]]]
    assert len(as_polygon(OUTER, 1.0, holes).holes) == 2


SQUARE = rectangle(4.0, 4.0)


# One case per validation rule: (vertices, l, error type, regex the message must match).
BAD_INPUTS = {
    "not an (n, 2) array": ([[0, 0, 0], [1, 0, 0], [1, 1, 0]], 1.0, InvalidPolygonError, r"\(n, 2\) array"),
    "flat list": ([0.0, 0.0, 4.0, 0.0, 4.0, 4.0], 1.0, InvalidPolygonError, r"\(n, 2\) array"),
    "not numbers": ([["a", 0], [4, 0], [4, 4]], 1.0, InvalidPolygonError, r"array of numbers"),
    "nan coordinate": ([[0, 0], [4, 0], [4, np.nan], [0, 4]], 1.0, InvalidPolygonError, r"vertex 2 .*non-finite"),
    "inf coordinate": ([[0, 0], [np.inf, 0], [4, 4], [0, 4]], 1.0, InvalidPolygonError, r"vertex 1 .*non-finite"),
    "fewer than 3 distinct vertices": (
        [[0, 0], [4, 0], [0, 0], [4, 0]],
        1.0,
        InvalidPolygonError,
        r"at least 3 distinct",
    ),
    "two vertices only": ([[0, 0], [4, 0]], 1.0, InvalidPolygonError, r"at least 3 distinct"),
    "repeated vertex": (
        [[0, 0], [4, 0], [4, 4], [4, 0], [0, 4]],
        1.0,
        InvalidPolygonError,
        r"vertices 1 and 3 coincide",
    ),
    "self-intersecting bow-tie": (
        [[0, 0], [6, 4], [6, 0], [0, 6]],
        1.0,
        InvalidPolygonError,
        r"self-intersecting.*: edge \(0, 1\) intersects edge \(2, 3\)",
    ),
    "zero area, collinear": ([[0, 0], [2, 0], [4, 0], [6, 0]], 1.0, InvalidPolygonError, r"zero area"),
    "non-convex": (
        [[0, 0], [8, 0], [8, 8], [4, 3], [0, 8]],
        1.0,
        InvalidPolygonError,
        r"not convex: reflex angle at vertex 3",
    ),
    "inner angle below 90": (
        [[0, 0], [8, 0], [0, 8]],
        1.0,
        InvalidPolygonError,
        r"inner angle 45 degrees at vertex [12] .*below 90",
    ),
    "inner angle 89 degrees": (
        [[0, 0], [4, 0], [4 + 4 * math.cos(math.radians(91)), 4 * math.sin(math.radians(91))], [0, 4]],
        1.0,
        InvalidPolygonError,
        r"at vertex 1 .*below 90",
    ),
    "edge shorter than l": (
        [[0, 0], [4, 0], [4, 0.5], [0, 0.5]],
        1.0,
        InvalidPolygonError,
        r"edge \(1, 2\) has length 0.5, shorter than l",
    ),
    "l zero": (SQUARE, 0.0, InvalidLengthError, r"positive and finite"),
    "l negative": (SQUARE, -1.0, InvalidLengthError, r"positive and finite"),
    "l nan": (SQUARE, float("nan"), InvalidLengthError, r"positive and finite"),
    "l inf": (SQUARE, float("inf"), InvalidLengthError, r"positive and finite"),
    "l not a number": (SQUARE, "one", InvalidLengthError, r"must be a real number"),
    "l None": (SQUARE, None, InvalidLengthError, r"must be a real number"),
}


@pytest.mark.parametrize("name", sorted(BAD_INPUTS))
def test_each_invalid_input_raises_a_named_error(name):
    """Every validation rule of Problem 1 raises its own error naming the vertex or edge at fault."""
    vertices, l, error, message = BAD_INPUTS[name]
    with pytest.raises(error, match=message):
        equimesh.increment(vertices, l)
    with pytest.raises(error, match=message):
        equimesh.node_lower_bound(vertices, l)


def test_error_names_vertex_in_caller_order_for_clockwise_input():
    """Vertex indices in messages count in the caller's order, also when the input is clockwise."""
    cw = np.array([[0, 0], [0, 8], [4, 3], [8, 8], [8, 0]], float)  # reflex vertex 2, clockwise
    with pytest.raises(InvalidPolygonError, match=r"reflex angle at vertex 2 at \(4, 3\)"):
        equimesh.increment(cw, 1.0)


def test_closing_copy_of_first_vertex_is_accepted():
    """A ring given closed (last vertex = first) is the same polygon."""
    closed = np.vstack([SQUARE, SQUARE[:1]])
    assert np.array_equal(equimesh.increment(closed, 1.0).points, equimesh.increment(SQUARE, 1.0).points)


def test_exact_right_angles_and_edges_of_exactly_l_are_accepted():
    """The boundary cases of the assumptions (90 degrees, edge = l) are valid, also after rounding."""
    validate_problem1(rectangle(1.0, 1.0), 1.0)
    validate_problem1(regular_polygon(4, 1.0, rotation=0.1), 1.0)
    validate_problem1(rectangle(0.1 * 3, 0.1 * 7), 0.3)


@given(problems)
def test_orientation_is_normalised_to_counter_clockwise(problem):
    """Validation orients the polygon counter-clockwise whatever the input orientation."""
    vertices, l = problem
    for v in (vertices, vertices[::-1]):
        poly = as_polygon(v)
        assert poly.area > 0
        assert np.array_equal(v[poly.input_index], poly.vertices)


@pytest.mark.parametrize(
    "vertices, where",
    [
        ([(0, 0), (4, 0), (2, 0), (2, 3)], "vertex 1 at (4, 0)"),
        ([(0, 0), (3, 0), (3, 3), (3, 1), (0, 3)], "vertex 2 at (3, 3)"),
        ([(0, 3), (0, 0), (3, 0), (3, 3), (3, 1)], "vertex 3 at (3, 3)"),
    ],
)
def test_polygon_folding_back_names_the_vertex(vertices, where):
    """Two consecutive edges on one line in opposite directions: refused at the vertex between them."""
    with pytest.raises(InvalidPolygonError, match=r"^polygon folds back on itself at " + re.escape(where) + "$"):
        as_polygon(vertices)


def test_a_side_shorter_than_l_is_refused_as_impossible():

    with pytest.raises(InvalidPolygonError) as err:
        check_edges_at_least(as_polygon([[0, 0], [4, 0], [4, 0.5], [0, 0.5]]), 1.0)
    assert str(err.value) == (
        "no mesh with every edge in [l, 2l] exists (both ends of a side are nodes, so some mesh "
        "edge on it is no longer than the side): edge (1, 2) has length 0.5, shorter than l = 1.0"
    )


SQUARE10 = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


def test_polygon_wider_than_the_precision_range_is_refused():
    """More than MAX_EXTENT = 2^16 l across: refused before any work, with the l that would do."""
    with pytest.raises(InvalidPolygonError, match=r"spans 1000000.0 = 1000000.0 l, .*use l >= 15.2587890625$"):
        equimesh.increment(SQUARE10 * 1e5, 1.0, max_nodes=None)


def test_validation_of_a_10000_gon():
    """Validation is O(n log n): a 10,000-gon (edges ~6.3e-3 of its radius) validates (no timing asserted)."""
    t = 2.0 * np.pi * np.arange(10_000) / 10_000
    poly = as_polygon(np.column_stack([np.cos(t), np.sin(t)]) * 1000.0)
    assert len(poly.vertices) == 10_000 and poly.area > 0


# --------------------------------------------------------------------------- messages of Problems 1 and 2


@pytest.mark.parametrize(
    "vertices, l, error, message",
    [
        (
            [[0, 0], [10, 10], [10, 0], [0, 10]],
            1.0,
            InvalidPolygonError,
            r"self-intersecting.*edge \(0, 1\) intersects edge \(2, 3\)",
        ),
        (SQUARE10, 10.0000001, InvalidPolygonError, r"has length 10.0, shorter than l = 10.0000001$"),
        (SQUARE10 + 1j, 1.0, InvalidPolygonError, r"must be real numbers, got complex"),
        ([[0, 0], [1 + 2j, 0], [0, 1]], 1.0, InvalidPolygonError, r"must be real numbers, got complex"),
        (SQUARE10, 1.0 + 0j, InvalidLengthError, r"must be a real number, got complex"),
        (SQUARE10, np.complex128(1.0), InvalidLengthError, r"must be a real number, got complex"),
        (SQUARE10, np.float64(0.0), InvalidLengthError, r"positive and finite, got 0.0$"),
        (np.array([[0, 0], [10, np.nan], [0, 10]]), 1.0, InvalidPolygonError, r"vertex 1 .* \(10.0, nan\)$"),
        ([[0, 0], [1, 1], [np.float64(2), 2]], 1.0, InvalidPolygonError, r"zero area \(all vertices collinear\)"),
    ],
    ids=[
        "bow-tie",
        "digits",
        "complex array",
        "complex entry",
        "complex l",
        "numpy complex l",
        "numpy l",
        "nan",
        "collinear",
    ],
)
def test_messages_name_the_problem_in_plain_numbers(vertices, l, error, message):
    for verb in (equimesh.increment, equimesh.uniform_triangulation):
        with pytest.raises(error, match=message) as info:
            verb(vertices, l)
        assert "np." not in str(info.value) and "\n" not in str(info.value)
