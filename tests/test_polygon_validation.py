"""Validation of the input polygon (``planar/polygon.py``), case by case: what is refused, with which line, and what is not.

Each case is built by hand at the edge of one check: a repeated vertex that
sorting by y alone would not find, a fold-back that a sum over all vertices
would miss, a bottom edge of three collinear vertices (the orientation must
be read at the lowest-leftmost vertex), angles exactly at the REL_TOL
tolerance of Problem 1 and a hair beyond it, an extent exactly at
``MAX_EXTENT l``, coordinates whose span overflows, object arrays of
fractions (accepted) and of complex numbers (refused).  Messages are compared
in full: they are the caller's only account of what is wrong.
"""

import warnings
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest

from equimesh import InvalidLengthError, InvalidPolygonError
from equimesh._checks import check_length, real_array, real_number
from equimesh.planar.increment import validate_problem1
from equimesh.planar.polygon import as_polygon
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


def test_real_array_returns_floats():
    """Integers in, floats out: every later step computes in floating point."""
    out = real_array([[0, 1], [2, 3]], "x", InvalidPolygonError)
    assert out.dtype == float and out.tolist() == [[0.0, 1.0], [2.0, 3.0]]


def test_a_zero_dimensional_complex_array_is_named_complex():
    with pytest.raises(InvalidLengthError) as err:
        real_number(np.array(1j), "target length l", InvalidLengthError)
    assert str(err.value) == "target length l must be a real number, got complex value array(0.+1.j)"


def test_length_out_of_range_says_to_rescale():
    with pytest.raises(InvalidLengthError) as err:
        check_length(1e200)
    assert str(err.value) == (
        "target length l = 1e+200 is outside the supported range [1e-150, 1e+150]; rescale the coordinates"
    )


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
    """Two triangles with overlapping bounding boxes, 1.06 apart: no overlap (the shapes are compared, not the boxes)."""
    holes = [[[2, 2], [6, 2], [2, 6]], [[6.5, 3], [6.5, 7], [2.5, 7]]]
    assert len(as_polygon(OUTER, 1.0, holes).holes) == 2
