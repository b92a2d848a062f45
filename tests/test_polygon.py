"""Input validation and Step 2 (boundary resampling) of Algorithm INCREMENT.

Problem 1 assumes a convex polygon with every inner angle >= 90 degrees and
every edge >= l, and a positive finite l.  Each violated assumption must raise
an :class:`equimesh.EquimeshError` (a ``ValueError``) naming the vertex or
edge at fault.
"""

import math
import re

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.distance import pdist

import equimesh
from equimesh import REL_TOL, EquimeshError, InvalidLengthError, InvalidPolygonError
from equimesh.testing.generators import random_convex_polygon, rectangle, regular_polygon
from equimesh.planar.increment import validate_problem1
from equimesh.planar.polygon import as_polygon, check_length, resample_boundary, split_counts
from equimesh.tolerance import MAX_LENGTH, MIN_LENGTH
from strategies import problems, seeds

SQUARE = rectangle(4.0, 4.0)


def test_errors_are_value_errors():
    """The error family: both input errors are EquimeshError and ValueError."""
    for error in (InvalidPolygonError, InvalidLengthError):
        assert issubclass(error, EquimeshError) and issubclass(error, ValueError)


# One case per validation rule: (vertices, l, error type, regex the message must match).
BAD_INPUTS = {
    "not an (n, 2) array": ([[0, 0, 0], [1, 0, 0], [1, 1, 0]], 1.0, InvalidPolygonError, r"\(n, 2\) array"),
    "flat list": ([0.0, 0.0, 4.0, 0.0, 4.0, 4.0], 1.0, InvalidPolygonError, r"\(n, 2\) array"),
    "not numbers": ([["a", 0], [4, 0], [4, 4]], 1.0, InvalidPolygonError, r"array of numbers"),
    "nan coordinate": ([[0, 0], [4, 0], [4, np.nan], [0, 4]], 1.0, InvalidPolygonError, r"vertex 2 .*non-finite"),
    "inf coordinate": ([[0, 0], [np.inf, 0], [4, 4], [0, 4]], 1.0, InvalidPolygonError, r"vertex 1 .*non-finite"),
    "fewer than 3 distinct vertices": ([[0, 0], [4, 0], [0, 0], [4, 0]], 1.0, InvalidPolygonError, r"at least 3 distinct"),
    "two vertices only": ([[0, 0], [4, 0]], 1.0, InvalidPolygonError, r"at least 3 distinct"),
    "repeated vertex": ([[0, 0], [4, 0], [4, 4], [4, 0], [0, 4]], 1.0, InvalidPolygonError, r"vertices 1 and 3 coincide"),
    "self-intersecting bow-tie": ([[0, 0], [6, 4], [6, 0], [0, 6]], 1.0, InvalidPolygonError, r"self-intersecting.*: edge \(0, 1\) intersects edge \(2, 3\)"),
    "zero area, collinear": ([[0, 0], [2, 0], [4, 0], [6, 0]], 1.0, InvalidPolygonError, r"zero area"),
    "non-convex": ([[0, 0], [8, 0], [8, 8], [4, 3], [0, 8]], 1.0, InvalidPolygonError, r"not convex: reflex angle at vertex 3"),
    "inner angle below 90": ([[0, 0], [8, 0], [0, 8]], 1.0, InvalidPolygonError, r"inner angle 45 degrees at vertex [12] .*below 90"),
    "inner angle 89 degrees": (
        [[0, 0], [4, 0], [4 + 4 * math.cos(math.radians(91)), 4 * math.sin(math.radians(91))], [0, 4]],
        1.0, InvalidPolygonError, r"at vertex 1 .*below 90",
    ),
    "edge shorter than l": ([[0, 0], [4, 0], [4, 0.5], [0, 0.5]], 1.0, InvalidPolygonError, r"edge \(1, 2\) has length 0.5, shorter than l"),
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


@given(problems)
def test_step2_boundary_points_are_between_l_and_2l(problem):
    """Step 2: consecutive boundary points are in [l, 2l], all boundary points pairwise >= l.

    The pairwise bound is the docstring argument of ``resample_boundary``
    (convexity and inner angles >= 90 degrees).
    """
    vertices, l = problem
    poly, l = validate_problem1(vertices, l)
    boundary = resample_boundary(poly, l)
    pts, l = boundary.points, poly.local_length(l)  # both in the polygon's local frame
    steps = np.linalg.norm(np.roll(pts, -1, axis=0) - pts, axis=1)
    assert steps.min() >= (1.0 - REL_TOL) * l
    assert steps.max() <= 2.0 * l * (1.0 + REL_TOL)
    assert pdist(pts).min() >= (1.0 - REL_TOL) * l
    assert np.array_equal(pts[boundary.is_vertex], poly.local)


@given(
    seeds,
    st.integers(4, 16),
    st.floats(1.0, 1000.0),
    st.floats(1.0, 100.0),
    st.sampled_from([0.0, 0.5, 0.99]),
)
def test_generator_builds_valid_problem1_polygons(seed, k, area, elongation, min_turn):
    """``random_convex_polygon`` gives a valid input by construction, of at least the target area."""
    rng = np.random.default_rng(seed)
    v = random_convex_polygon(rng, n_vertices=k, area=area, elongation=elongation, min_turn=min_turn)
    poly, _ = validate_problem1(v, 1.0)
    assert len(poly.vertices) == k
    assert poly.area >= area * (1.0 - 1e-12)
    capped = random_convex_polygon(np.random.default_rng(seed), n_vertices=k, area=area, elongation=elongation, max_area=60.0)
    assert validate_problem1(capped, 1.0)[0].area <= 60.0 * (1.0 + 1e-12)


@given(
    st.floats(0.5, 60.0, exclude_max=True),
    st.floats(1.0, 1.5),
    st.sampled_from([1.0, 1.5, 2.0]),
    st.sampled_from([1.0, 2.0 ** -5, 2.0 ** 7]),
)
def test_staggered_step2_separates_the_sides_of_a_sharp_corner(angle, stretch, spacing, l):
    """docs/proofs.md, "Sharp corners": at any corner angle down to 0.5 degrees, with both sides at least
    ``stagger_reach + l`` long, the Step 2 points of the two sides are pairwise at least l apart, and every
    boundary part is in [l, 2l]."""
    from equimesh.planar.polygon import stagger_reach
    from equimesh.testing.shapes import sharp_wedge

    side = max(stagger_reach(angle, 1.0) + 2.0, 1.2 / math.sin(math.radians(angle) / 2.0)) * stretch
    poly = as_polygon(sharp_wedge(angle, side, 2.0) * l, l)
    boundary = resample_boundary(poly, l, spacing)
    lp = poly.local_length(l)
    parts = np.linalg.norm(np.roll(boundary.points, -1, axis=0) - boundary.points, axis=1)
    assert parts.min() >= (1.0 - REL_TOL) * lp and parts.max() <= 2.0 * (1.0 + REL_TOL) * lp
    tip = np.flatnonzero(np.all(poly.local == poly.frame.to_local(np.zeros((1, 2))), axis=1))[0]
    sides = [boundary.points[boundary.edge == (tip - 1) % 5], boundary.points[boundary.edge == tip]]
    sides[0] = np.vstack([sides[0], boundary.points[boundary.edge == tip][:1]])  # the tip closes the arriving side
    gaps = np.linalg.norm(sides[0][:, None, :] - sides[1][None, :, :], axis=2)
    gaps[-1, 0] = np.inf  # the tip with itself
    assert gaps.min() >= (1.0 - REL_TOL) * lp


# Step 2 by hand: (l, spacing, edge length L, parts k).  k = ceil(L / (spacing l)) kept in
# [ceil(L / 2l), floor(L / l)], each bound up to REL_TOL; l = 2 tells l from 1 / l.
SPLIT_COUNTS = [
    (1.0, 2.0, 1.0, 1),  # shorter than 2l: one part
    (1.0, 2.0, 2.0, 1),  # exactly 2l: still one part
    (1.0, 2.0, 4.0, 2),  # exactly 4l: two parts of 2l, not three
    (1.0, 2.0, 4.0 * (1.0 + 0.5 * REL_TOL), 2),  # 2l up to REL_TOL
    (1.0, 2.0, 4.0 * (1.0 + 2.0 * REL_TOL), 3),
    (2.0, 2.0, 8.0, 2),
    (1.0, 1.5, 3.0, 2),  # the spacing decides: parts of 1.5 l
    (2.0, 1.5, 6.0, 2),
    (1.0, 1.5, 4.0, 3),
    (1.0, 3.0, 5.0, 3),  # spacing above 2: the lower bound ceil(L / 2l) decides
    (1.0, 0.5, 3.0, 3),  # spacing below 1: the upper bound floor(L / l) decides
    (2.0, 0.5, 6.0, 3),
    (1.0, 0.5, 3.0 * (1.0 - 0.5 * REL_TOL), 3),  # parts of l up to REL_TOL
    (1.0, 0.5, 3.0 * (1.0 - 2.0 * REL_TOL), 2),
]


@pytest.mark.parametrize("l, spacing, length, parts", SPLIT_COUNTS)
def test_split_counts_by_hand(l, spacing, length, parts):
    """Step 2: the number of equal parts of a boundary edge, each part in [l, 2l] (up to REL_TOL)."""
    assert split_counts([length], l, spacing).tolist() == [parts]
    if spacing == 2.0:
        assert split_counts([length], l).tolist() == [parts]  # 2 is the default (Problem 1)


def test_resample_boundary_uses_the_spacing():
    """A square of side 4l: parts of at most 2l (default) give 8 boundary points, of at most 1.5 l give 12."""
    poly = as_polygon(rectangle(4.0, 4.0), 1.0)
    assert len(resample_boundary(poly, 1.0).points) == 8
    boundary = resample_boundary(poly, 1.0, 1.5)
    assert len(boundary.points) == 12 and boundary.is_vertex.sum() == 4
    assert boundary.edge.tolist() == [0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3]


@pytest.mark.parametrize("vertices, where", [
    ([(0, 0), (4, 0), (2, 0), (2, 3)], "vertex 1 at (4, 0)"),
    ([(0, 0), (3, 0), (3, 3), (3, 1), (0, 3)], "vertex 2 at (3, 3)"),
    ([(0, 3), (0, 0), (3, 0), (3, 3), (3, 1)], "vertex 3 at (3, 3)"),
])
def test_polygon_folding_back_names_the_vertex(vertices, where):
    """Two consecutive edges on one line in opposite directions: refused at the vertex between them."""
    with pytest.raises(InvalidPolygonError, match=r"^polygon folds back on itself at " + re.escape(where) + "$"):
        as_polygon(vertices)


@pytest.mark.parametrize("l", [MIN_LENGTH, MAX_LENGTH, np.float64(2.0), np.int64(3), np.array(0.5), np.float32(0.25)])
def test_lengths_at_the_ends_of_the_range_and_numpy_scalars_are_accepted(l):
    assert check_length(l) == float(l) and type(check_length(l)) is float


@pytest.mark.parametrize("l, message", [
    (1 + 2j, "got complex value (1+2j)"),
    (np.complex128(2.0), "got complex value (2+0j)"),
    (np.array([1.0]), "got array([1.])"),
    ("1", "got '1'"),
])
def test_a_length_that_is_not_one_real_number_is_named(l, message):
    with pytest.raises(InvalidLengthError, match=r"^target length l must be a real number, " + re.escape(message) + "$"):
        check_length(l)


@given(
    st.lists(st.tuples(st.floats(1.0, 12.0), st.floats(5.0, 355.0)), min_size=3, max_size=6),
    st.sampled_from([1.0, 1.5, 2.0]),
)
def test_step2_parts_stay_in_l_2l_on_sides_too_short_for_their_stagger(ring, spacing):
    """docs/proofs.md, "Sharp corners": whatever the corner angles and however short the sides (down to l),
    every side's Step 2 points start at its first corner, increase, and leave parts in [l, 2l]."""
    from equimesh.planar.polygon import side_positions

    lengths, angles = map(list, zip(*ring))
    for length, (num, den) in zip(lengths, side_positions(lengths, angles, 1.0, spacing)):
        at = np.append(num / den * length, length)
        assert at[0] == 0.0
        parts = np.diff(at)
        assert parts.min() >= 1.0 - 1e-9 and parts.max() <= 2.0 + 1e-9, (length, at)


@given(
    st.floats(1.0, 59.9),
    st.lists(st.floats(1.0, 2.0), min_size=1, max_size=8),
    st.lists(st.floats(1.0, 2.0), min_size=1, max_size=8),
)
def test_the_closest_pair_of_a_corner_pairs_each_point_with_the_next_one_across(angle, parts_a, parts_b):
    """The pairing lemma (docs/proofs.md, "Sharp corners"): the closest pair of points on the two sides of a
    corner pairs some point with the first point of the other side at least as far from the corner; and
    ``_corner_gap`` is that distance whenever it is below l."""
    from equimesh.planar.polygon import _corner_gap

    a, b = np.cumsum(parts_a), np.cumsum(parts_b)
    t = math.radians(angle)

    def chord(p, q):
        return np.sqrt(np.maximum(p**2 + q**2 - 2.0 * p * q * math.cos(t), 0.0))

    nearest = chord(a[:, None], b[None, :]).min()
    paired = np.inf
    for p, q in ((a, b), (b, a)):
        j = np.searchsorted(q, p)  # the first point of the other side at least as far from the corner
        paired = min(paired, chord(p[j < len(q)], q[j[j < len(q)]]).min(initial=np.inf))
    assert paired == pytest.approx(nearest, rel=1e-12)
    sides = [(np.append(0.0, a[:-1]) / a[-1], 1.0), (np.append(0.0, b[-1] - b[::-1][1:]) / b[-1], 1.0)]
    gap = _corner_gap(sides, np.array([a[-1], b[-1]]), [angle, 360.0 - angle], 1.0, 0)
    assert min(gap, 1.0) == pytest.approx(min(nearest, 1.0), rel=1e-9)
