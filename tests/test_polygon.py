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
from strategies import problems, seeds

import equimesh
from equimesh import REL_TOL, EquimeshError, InvalidLengthError, InvalidPolygonError
from equimesh._checks import check_length
from equimesh.planar.boundary import separation
from equimesh.planar.boundary.resample import resample_boundary
from equimesh.planar.boundary.sides import split_counts
from equimesh.planar.increment import validate_problem1
from equimesh.planar.polygon import as_polygon
from equimesh.testing.generators import random_convex_polygon, rectangle, regular_polygon
from equimesh.tolerance import MAX_LENGTH, MIN_LENGTH

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
    capped = random_convex_polygon(
        np.random.default_rng(seed), n_vertices=k, area=area, elongation=elongation, max_area=60.0
    )
    assert validate_problem1(capped, 1.0)[0].area <= 60.0 * (1.0 + 1e-12)


@given(
    st.floats(0.5, 60.0, exclude_max=True),
    st.floats(1.0, 1.5),
    st.sampled_from([1.0, 1.5, 2.0]),
    st.sampled_from([1.0, 2.0**-5, 2.0**7]),
)
def test_staggered_step2_separates_the_sides_of_a_sharp_corner(angle, stretch, spacing, l):
    """docs/proofs.md, "Sharp corners": at any corner angle down to 0.5 degrees, with both sides at least
    ``stagger_reach + l`` long, the Step 2 points of the two sides are pairwise at least l apart, and every
    boundary part is in [l, 2l]."""
    from equimesh.planar.boundary.sides import stagger_reach
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
    assert split_counts([length], l, spacing).dtype.kind == "i"  # counts, for arange and repeat
    if spacing == 2.0:
        assert split_counts([length], l).tolist() == [parts]  # 2 is the default (Problem 1)


def test_resample_boundary_uses_the_spacing():
    """A square of side 4l: parts of at most 2l (default) give 8 boundary points, of at most 1.5 l give 12."""
    poly = as_polygon(rectangle(4.0, 4.0), 1.0)
    assert len(resample_boundary(poly, 1.0).points) == 8
    boundary = resample_boundary(poly, 1.0, 1.5)
    assert len(boundary.points) == 12 and boundary.is_vertex.sum() == 4
    assert boundary.edge.tolist() == [0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3]


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


@pytest.mark.parametrize("l", [MIN_LENGTH, MAX_LENGTH, np.float64(2.0), np.int64(3), np.array(0.5), np.float32(0.25)])
def test_lengths_at_the_ends_of_the_range_and_numpy_scalars_are_accepted(l):
    assert check_length(l) == float(l) and type(check_length(l)) is float


@pytest.mark.parametrize(
    "l, message",
    [
        (1 + 2j, "got complex value (1+2j)"),
        (np.complex128(2.0), "got complex value (2+0j)"),
        (np.array([1.0]), "got array([1.])"),
        ("1", "got '1'"),
    ],
)
def test_a_length_that_is_not_one_real_number_is_named(l, message):
    with pytest.raises(
        InvalidLengthError, match=r"^target length l must be a real number, " + re.escape(message) + "$"
    ):
        check_length(l)


@given(
    st.lists(st.tuples(st.floats(1.0, 12.0), st.floats(5.0, 355.0)), min_size=3, max_size=6),
    st.sampled_from([1.0, 1.5, 2.0]),
)
def test_step2_parts_stay_in_l_2l_on_sides_too_short_for_their_stagger(ring, spacing):
    """docs/proofs.md, "Sharp corners": whatever the corner angles and however short the sides (down to l),
    every side's Step 2 points start at its first corner, increase, and leave parts in [l, 2l]."""
    from equimesh.planar.boundary.sides import side_positions

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
    from equimesh.planar.boundary.sides import _corner_gap

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


# --------------------------------------------------------------------------- Step 2 at sharp corners, by hand


@pytest.mark.parametrize(
    "angle, count",
    [
        (10.0, 6),  # 1 / sin 10 = 5.76
        (30.0, 2),  # 1 / sin 30 rounds to 2.0000000000000004: K = 2 only with the (1 - REL_TOL)
        (59.0, 2),
        (60.0 * (1.0 - 2.0 * REL_TOL), 2),  # sharp up to REL_TOL
        (60.0 * (1.0 - REL_TOL), 0),  # exactly at the tolerance: not sharp
        (60.0, 0),
        (90.0, 0),
    ],
)
def teststagger_count_and_reach_by_hand(angle, count):
    """K = ceil(1 / sin angle) staggered points below SHARP_CORNER = 60 degrees (up to REL_TOL), K l from the corner."""
    from equimesh.planar.boundary.sides import stagger_count, stagger_reach

    assert stagger_count(angle) == count
    assert stagger_reach(angle, 2.0) == 2.0 * count


# 2 k sin(angle / 2) for k = 2 at these angles: exactly 1 + REL_TOL (found by stepping through the floats
# next to 2 asin((1 + REL_TOL) / 4)), and 1 up to rounding (2 asin(1 / 4)).
AT_BOTH = 28.955024401447265
BELOW_BOTH = math.degrees(2.0 * math.asin(0.25))


@pytest.mark.parametrize(
    "angle, l, reach, leaving, arriving",
    [
        (10.0, 2.0, 100.0, [2, 6, 10, 12], [4, 8, 12]),  # K = 6; 2 k sin 5 >= 1 from k = 6 on: 6 l on both sides
        (10.0, 2.0, 5.0, [2, 6], [4]),  # floor(reach / l) + 1 = 3 points
        (10.0, 2.0, 4.0, [2, 6], [4]),
        (10.0, 2.0, 3.99, [2], [4]),
        (AT_BOTH, 1.0, 100.0, [1, 2, 3], [2, 3]),  # K = 3; k = 2 exactly at 1 + REL_TOL: on both sides
        (BELOW_BOTH, 1.0, 100.0, [1, 3], [2, 3]),
        (60.0, 1.0, 100.0, [], []),
    ],
)
def test_stagger_by_hand(angle, l, reach, leaving, arriving):
    """``stagger``: the points k l, k = 1 .. min(K, floor(reach / l) + 1), odd k leaving the corner, even k
    arriving, and both where the two points k l are l apart already (2 k sin(angle / 2) >= 1, up to REL_TOL)."""
    from equimesh.planar.boundary.sides import stagger

    assert 4.0 * math.sin(math.radians(AT_BOTH) / 2.0) == 1.0 + REL_TOL
    assert 4.0 * math.sin(math.radians(BELOW_BOTH) / 2.0) < 1.0 + REL_TOL / 2.0
    out = stagger(angle, l, reach)
    assert [x.tolist() for x in out] == [leaving, arriving]


@pytest.mark.parametrize(
    "length, start, end, points, denominator",
    [
        # both chains end at 3: the start chain gives way first, its 3 dropped; middle 1 .. 2 (one part)
        (5.0, [1.0, 3.0], [2.0, 3.0], [0, 1, 2, 3], 5.0),
        # no point from the first corner: the middle 0 .. 1.5 is long enough, the point 2 from the end stays
        (3.5, [], [2.0], [0, 1.5], 3.5),
        # 6 = 6 (start first), 6 > 4, 5 > 4, 4 > 3, then 7 - 3 - 2 = 2 >= l: one part between 3 and 5
        (7.0, [1.0, 3.0, 5.0, 6.0], [2.0, 4.0, 6.0], [0, 1, 3, 5], 7.0),
        # middle 12 .. 20 split into 2 parts of 4 (spacing 2, l = 2)
        (20.0, [2.0, 6.0, 10.0, 12.0], [], [0, 2, 6, 10, 12, 16], 20.0),
        # one chain empty: the other gives way, whatever l (here 1 and 0.5)
        (1.5, [], [1.0], [0], 1.0),
        (0.75, [0.5], [], [0], 1.0),
    ],
)
def test_place_drops_the_farthest_staggered_point_until_the_middle_is_l(length, start, end, points, denominator):
    from equimesh.planar.boundary.sides import _place

    l = {20.0: 2.0, 0.75: 0.5}.get(length, 1.0)
    num, den = _place(length, np.array(start), np.array(end), l, 2.0)
    assert num.tolist() == points and den == denominator


def test_side_positions_by_hand():
    """A ring of sides 20, 3, 20 with a 10 degree corner at 0: its stagger (K = 6, reach 20) leaving
    [1, 3, 5, 6], arriving [2, 4, 6], the rest in parts of 2 (l = 1) or 4 (l = 2); the short side alone."""
    from equimesh.planar.boundary.sides import side_positions

    for l, expected in [
        (
            1.0,
            [
                ([0, 1, 3, 5, 6, 8, 10, 12, 14, 16, 18], 20.0),
                ([0, 1], 2.0),
                ([0, 2, 4, 6, 8, 10, 12, 14, 16, 18], 20.0),
            ],
        ),
        (2.0, [([0, 2, 6, 10, 12, 16], 20.0), ([0], 1.0), ([0, 4, 8, 12, 16], 20.0)]),
    ]:
        sides = side_positions([20.0, 3.0, 20.0], [10.0, 85.0, 85.0], l)
        assert [(num.tolist(), float(den)) for num, den in sides] == expected


# --------------------------------------------------------------------------- Lemma 3 (1): the checks' messages

NECK = [[0, 0], [6, 0], [6, 2.5], [8, 2.5], [8, 0], [14, 0], [14, 6], [8, 6], [8, 3.5], [6, 3.5], [6, 6], [0, 6]]
# The corridor narrows from 0.9 (left end) to 0.8 (right end): the right-end pair is the closest.
TAPERED_NECK = [
    [0, 0],
    [6, 0],
    [6, 2.6],
    [8, 2.6],
    [8, 0],
    [14, 0],
    [14, 6],
    [8, 6],
    [8, 3.4],
    [6, 3.5],
    [6, 6],
    [0, 6],
]


def _separation_message(vertices, l, holes=None, spacing=2.0):
    """``check_boundary_separation``'s refusal of the Step 2 points of ``vertices`` (and ``holes``): message, points."""
    from equimesh.planar.boundary.separation import check_boundary_separation

    poly = as_polygon(vertices, l if holes is None else None, holes)
    with pytest.raises(InvalidPolygonError) as err:
        check_boundary_separation(poly, resample_boundary(poly, l, spacing), l)
    return str(err.value), np.array(err.value.points).tolist()


def test_a_neck_of_exactly_l_is_accepted_and_a_narrower_one_refused():
    """Points exactly l apart across a corridor meet Lemma 3 (1); at l = 1.5 (a local length other than 1) a
    corridor 1.2 wide is refused."""
    from equimesh.planar.boundary.separation import check_boundary_separation

    poly = as_polygon(NECK, 1.0)
    assert check_boundary_separation(poly, resample_boundary(poly, 1.0), 1.0) is None
    message, _ = _separation_message(np.array(NECK) * 1.2, 1.5)
    assert message.startswith(
        "polygon is too narrow for l = 1.5: boundary points on edge (2, 3) and edge (9, 10) are 1.2"
    )


def test_the_closest_visible_pair_is_reported_in_the_callers_units():
    """The tapered neck at l = 4 (local frame scaled by 1/4): the pair 3.2 apart at the right end, not the one
    3.6 apart at the left end nor the first in index order; lengths in the caller's units."""
    message, points = _separation_message(np.array(TAPERED_NECK) * 4.0, 4.0)
    assert message == (
        "polygon is too narrow for l = 4.0: boundary points on edge (3, 4) and edge (8, 9) are 3.1999999999999993 "
        "apart and see each other across the polygon (Lemma 3 (1), a limit of this method); use l <= "
        "3.1999999999999993 or widen the polygon there"
    )
    assert points == [[32.0, 10.4], [32.0, 13.6]]


def test_a_pair_across_two_rings_is_a_neck_not_a_corner():
    """A hole 0.5 from the outer boundary (built without l, so only this check sees it): the points are on
    edge 0 of the outer ring and edge 3 of the hole, which would be consecutive edges of one ring."""
    message, points = _separation_message(
        [[0, 0], [10, 0], [10, 10], [0, 10]], 1.0, [[[2, 0.5], [4, 0.5], [4, 2.5], [2, 2.5]]]
    )
    assert message.startswith(
        "polygon is too narrow for l = 1.0: boundary points on edge (0, 1) and edge (0, 3) of hole 0 "
        "are 0.5 apart and see each other across the polygon"
    )
    assert points == [[2.0, 0.0], [2.0, 0.5]]


def test_a_corner_not_handled_is_named_with_its_limit_in_the_callers_units(monkeypatch):
    """A thin triangle at l = 4 (Problem 2's spacing) with sharp corners of 29.4 and 23.07 degrees sharing a side:
    each corner alone has a placement, none exists for both; with the joint proof switched off (what a ring it
    does not decide meets) it is "not handled" (docs/proofs.md, "Sharp corners"); K = 3, so sides of
    (K + 1) l = 16 are handled; the closest pair is on edges 0 and 2."""
    from equimesh.planar.boundary import chain as _coupled
    from equimesh.planar.strip import BOUNDARY_SPACING

    monkeypatch.setattr(_coupled, "chain_unplaceable", lambda *args: False)

    triangle = np.array([[0, 0], [4.25, 0], [2.1 * math.cos(math.radians(29.4)), 2.1 * math.sin(math.radians(29.4))]])
    message, points = _separation_message(triangle * 4.0, 4.0, spacing=BOUNDARY_SPACING)
    assert message == (
        "the corner at vertex 0 at (0, 0) (29.4 degrees) is not handled for l = 4.0: boundary points on edge (0, 1) "
        "and edge (2, 0) are 2.4802111916513114 apart, closer than l (Lemma 3 (1)); the staggered Step 2 is proven at "
        "29.4 degrees for sides of at least 16.0, longer if the next corner is sharp too; for these the searches "
        "found no placement and none is proven impossible, even for each corner alone (a limit of this method, not a "
        "proof that no mesh exists; docs/proofs.md, 'Sharp corners'); use a smaller l, longer sides or a wider corner"
    )
    assert points == [[5.0, 0.0], [3.4848552444807583, 1.9636150144605629]]


# --------------------------------------------------------------------------- the proven refusals (docs/proofs.md)


def _at(angle, length):
    return [length * math.cos(math.radians(angle)), length * math.sin(math.radians(angle))]


@pytest.mark.parametrize(
    "a, b, theta, chord",
    [
        (3.0, 4.0, math.pi / 2.0, 5.0),
        (3.0, 4.0, math.pi / 3.0, math.sqrt(13.0)),
        (1.0, 1.0, 0.0, 0.0),
        (2.0, 0.0, 1.0, 2.0),
    ],
)
def test_chord_by_hand(a, b, theta, chord):
    """The law of cosines; a corner of angle 0 with equal distances gives 0, not a rounding below it."""
    from equimesh.planar.boundary.separation import _chord

    assert _chord(a, b, theta) == pytest.approx(chord, rel=1e-15, abs=0.0)


LP = 1.5  # the local length of l = 3 (scale 1/2): tells l from the local length and from 1 / l


@pytest.mark.parametrize(
    "length, first",
    [
        (1.5, (1.5, 1.5)),  # below 2l: the side is one part, its far end the first node
        (2.0 * LP * (1.0 - REL_TOL), ((1.0 - REL_TOL) * LP, 2.0 * LP * (1.0 + REL_TOL))),  # 2l up to REL_TOL
        (3.0, ((1.0 - REL_TOL) * LP, 2.0 * LP * (1.0 + REL_TOL))),
        (2.0 * LP * (1.0 + REL_TOL), ((1.0 - REL_TOL) * LP, 2.0 * LP * (1.0 + REL_TOL))),
        (4.0, ((1.0 - REL_TOL) * LP, 2.5 * (1.0 + REL_TOL))),  # the first part leaves at least l: at most L - l
        (6.0, ((1.0 - REL_TOL) * LP, 3.0 * (1.0 + REL_TOL))),  # at most 2l
    ],
)
def test_first_node_by_hand(length, first):
    """Where the first node after a corner can lie on a side split into parts of [l, 2l], widened by REL_TOL."""
    from equimesh.planar.boundary.separation import _first_node

    assert _first_node(length, LP) == first


def _leaving(x, angle=20.0):
    """Corner 0 at the origin: its leaving side along the x axis, ``x`` long (caller units, l = 3), the other 18."""
    return np.array([[0.0, 0.0], [x, 0.0], [18.0, 3.0], _at(angle, 18.0)])


UNMESHABLE = (
    "no mesh with every edge in [l, 2l] exists for l = 3.0: at the corner at vertex 0 at (0, 0) (20 degrees) "
    "edge ({edge}) is {beta} long, a single mesh edge, and the third node of its triangle would be closer than "
    "l to its other end, {end} (docs/proofs.md, 'Sharp corners'); at this angle that side must be at least "
    "5.638155725 long (or at most 3.449823032)"
)


@pytest.mark.parametrize(
    "vertices, message",
    [
        (_leaving(5.4), UNMESHABLE.format(edge="0, 1", beta="5.4", end="vertex 1 at (5.4, 0)")),
        (
            np.array([[0, 0], [18, 0], [18, 9], _at(20.0, 5.4)]),
            UNMESHABLE.format(edge="3, 0", beta="5.4", end="vertex 3 at (5.074340152, 1.846908774)"),
        ),
    ],
)
def test_the_sector_lemma_names_the_side_and_its_far_end(vertices, message):
    """20 degrees, a side of 1.8 l (l = 3) leaving or arriving at the corner: between 2 - sqrt(4 cos^2 - 3) l =
    1.15 l and 2 l cos 20 = 1.879 l, so no mesh exists (docs/proofs.md, "Sharp corners", the sector lemma)."""
    from equimesh.planar.boundary.separation import _unmeshable_corner

    assert str(_unmeshable_corner(as_polygon(vertices, 3.0), 3.0)) == message


@pytest.mark.parametrize("beta, refused", [(1.14, False), (1.2, True), (4.0 / 3.0, True), (1.8, True), (1.95, False)])
def test_the_sector_lemma_holds_between_its_two_roots(beta, refused):
    """At 20 degrees a side of beta l is refused exactly for 1.15 l < beta < 1.879 l (l = 3, local length 1.5):
    below, the node at 2l on the other side is l away; above, the node at l."""
    from equimesh.planar.boundary.separation import _unmeshable_corner

    assert (_unmeshable_corner(as_polygon(_leaving(3.0 * beta), 3.0), 3.0) is not None) == refused


def test_the_sector_lemma_at_its_widened_bounds():
    """The radii l and 2l are widened by REL_TOL and the distance must stay below (1 - REL_TOL) l: a side 1e-10
    (relative) inside either root of the widened condition is refused, one 1e-10 outside is not."""
    from equimesh.planar.boundary.separation import _unmeshable_corner

    theta = math.radians(as_polygon(_leaving(5.4), 3.0).inner_angle(0))
    c, s, t, r2 = math.cos(theta), math.sin(theta), (1.0 - REL_TOL) * LP, 2.0 * LP * (1.0 + REL_TOL)
    high = 2.0 * (1.0 - REL_TOL) * LP * c  # the chord at radius (1 - REL_TOL) l is t there
    low = r2 * c - math.sqrt(t * t - r2 * r2 * s * s)  # the chord at radius 2 (1 + REL_TOL) l is t there
    for local, refused in [
        (high * (1.0 - 1e-10), True),
        (high * (1.0 + 1e-10), False),
        (low * (1.0 + 1e-10), True),
        (low * (1.0 - 1e-10), False),
    ]:
        poly = as_polygon(_leaving(2.0 * local), 3.0)
        assert poly.local_edge_lengths[0] == local
        assert (_unmeshable_corner(poly, 3.0) is not None) == refused, local


def test_no_separation_at_a_corner_names_it_with_the_handled_sides():
    """The 35.7 degree corner of a triangle with a 30 degree one (sides 1.6 and 2.5 l, l = 3): its sides are 2.5 l
    and 1.37 l, the first points closer than l wherever they lie; K = 2, so sides of 3 l are handled."""
    from equimesh.planar.boundary.separation import _unseparable_corner

    poly = as_polygon(np.array([[1.6, 0.0], _at(30.0, 2.5), [0.0, 0.0]]) * 3.0 + [6.0, 3.0], 3.0)
    assert str(_unseparable_corner(poly, 3.0)) == (
        "the corner at vertex 1 at (12.49519053, 6.75) (35.6746 degrees) cannot meet Lemma 3 (1) for l = 3.0: with sides "
        "of 7.499999999999999 and 4.115357934313905 the first boundary points of its two sides are closer than l wherever "
        "they lie, so no Step 2 separates them (a limit of the paper's method, not a proof that no mesh exists; "
        "docs/proofs.md, 'Sharp corners'); sides of at least 9.0 are handled; use a smaller l, longer sides or a wider corner"
    )


def test_no_separation_needs_the_corners_triangle_inside_the_polygon():
    """The triangle [[0, 0], [1.6, 0], 2.5 at 30 degrees], l = 1: its 30 degree corner is refused first; with a
    hole inside the triangle of that corner and the far ends of its first-point ranges (its first points may not
    see each other), the 35.7 degree corner is refused instead."""
    from equimesh.planar.boundary.separation import _unseparable_corner

    triangle = [[0.0, 0.0], [1.6, 0.0], _at(30.0, 2.5)]
    assert str(_unseparable_corner(as_polygon(triangle), 1.0)).startswith(
        "the corner at vertex 0 at (0, 0) (30 degrees)"
    )
    poly = as_polygon(triangle, None, [[[0.9, 0.2], [1.1, 0.2], [1.0, 0.35]]])
    assert str(_unseparable_corner(poly, 1.0)).startswith(
        "the corner at vertex 2 at (2.165063509, 1.25) (35.6746 degrees)"
    )


def test_corner_gap_reads_only_the_points_within_k_l():
    """A 10 degree corner (K = 6) at l = 2: points at 2 and 6 on one side, 4 on the other, within K l = 12, give the
    gap |c(2) - c(4)|; points from K l on are at least l from the whole other side and are left out."""
    from equimesh.planar.boundary.sides import _corner_gap

    lengths, angles = np.array([20.0, 20.0]), [10.0, 350.0]
    sides = [(np.array([0.0, 2.0, 6.0]), 20.0), (np.array([0.0, 16.0]), 20.0)]
    expected = math.sqrt(4.0 + 16.0 - 16.0 * math.cos(math.radians(10.0)))
    assert _corner_gap(sides, lengths, angles, 2.0, 0) == pytest.approx(expected, rel=1e-12)
    far = [(np.array([0.0, 12.0]), 20.0), (np.array([0.0, 8.0]), 20.0)]  # 12 = K l on one side, 12 on the other
    assert _corner_gap(far, lengths, angles, 2.0, 0) == math.inf
    assert _corner_gap(sides, lengths, [60.0, 300.0], 2.0, 0) == math.inf  # not sharp


def _fingerprint(lengths, angles, l, spacing):
    """``side_positions`` of a ring, its parts checked in [l, 2l]: (number of points, sum of i times the i-th position)."""
    from equimesh.planar.boundary.sides import side_positions

    at = []
    for length, (num, den) in zip(lengths, side_positions(lengths, angles, l, spacing)):
        ends = np.append(num / den * length, length)
        assert np.all(np.diff(ends) >= (1.0 - 1e-9) * l) and np.all(np.diff(ends) <= (2.0 + 1e-9) * l)
        at.extend(ends[:-1])
    return len(at), math.fsum(
        float(x) * k for k, x in enumerate(np.round(at, 9), start=1)
    )  # exactly rounded: no BLAS order


def test_short_side_search_fingerprint():
    """The search for short sides and the grid search after it (docs/proofs.md, "Sharp corners") on 60 fixed
    rings of 3 to 5 sides of 1 to 8 l and corners of 5 to 70 degrees, at both spacings: every part in [l, 2l], and
    its output pinned by two sums (a fingerprint, as in dmsh's tests; a change to the search changes them)."""
    rng = np.random.default_rng(11)
    count, weighted = 0, 0.0
    for _ in range(60):
        n = int(rng.integers(3, 6))
        lengths, angles = np.round(rng.uniform(1.0, 8.0, n), 2), np.round(rng.uniform(5.0, 70.0, n), 1)
        for spacing in (1.5, 2.0):
            c, w = _fingerprint(lengths, angles, 1.0, spacing)
            count, weighted = count + c, weighted + w
    assert (count, round(weighted, 6)) == (1498, 22813.755)


# Rings on which a step of the search decides the output (each found by changing that step, mutation testing):
# a staggered point exactly at a side's end (8 = 8 l), the neighbours marked again after a change, the corners
# compared after a trial, the sides near a mirrored corner, the chain of a non-sharp corner at l = 1.5 and 0.5.
SEARCH_RINGS = [
    ([3.0, 8.0, 2.0, 8.0, 7.0], [29.3, 36.0, 48.3, 7.1, 40.2], 1.0, 2.0, (20, 590.0)),
    ([3.0, 8.0, 2.0, 1.0, 3.0], [61.3, 18.2, 63.0, 61.4, 4.2], 1.0, 2.0, (11, 98.0)),
    ([7.0, 1.0, 5.0, 3.0], [18.4, 7.2, 39.3, 32.6], 1.0, 2.0, (11, 108.0)),
    ([4.61, 3.0, 1.38, 3.68, 3.86], [6.0, 6.3, 69.9, 46.7, 18.7], 1.0, 1.5, (12, 82.72)),
    ([4.61, 3.0, 1.38, 3.68, 3.86], [6.0, 6.3, 69.9, 46.7, 18.7], 1.5, 1.5, (12, 124.08)),
    ([4.61, 3.0, 1.38, 3.68, 3.86], [6.0, 6.3, 69.9, 46.7, 18.7], 0.5, 1.5, (12, 41.36)),
    ([3.0, 4.0, 3.0, 2.0, 5.0], [59.2, 18.2, 14.0, 37.8, 13.0], 1.0, 1.5, (12, 102.0)),
    ([2.6, 4.51, 5.25, 1.49, 7.58], [43.0, 9.9, 36.6, 66.4, 64.9], 1.0, 1.5, (16, 329.141666667)),
    ([7.05, 4.14, 5.79, 3.28, 3.36], [54.7, 26.1, 20.8, 21.2, 24.1], 1.5, 1.5, (17, 350.97)),
]


# The same rings after the grid search of the corners the short-side search leaves closer than l (None: unchanged).
# The second has no side too short for its staggers but its corners of 18.2 and 4.2 degrees are closer than l
# (0.949 and 0.073): the grid search places them too (1.096 and 1.005).
GRID_RINGS = [(18, 456.0), (10, 88.0), (10, 90.9375), None, None, None, (10, 57.0), None, (17, 354.1425)]


@pytest.mark.parametrize("ring, grid", list(zip(SEARCH_RINGS, GRID_RINGS)))
def test_short_side_search_on_rings_where_each_step_matters(ring, grid, monkeypatch):
    """Pinned without the grid search (so that each step of the short-side search still decides the output),
    then with it."""
    lengths, angles, l, spacing, pinned = ring
    with monkeypatch.context() as patch:
        patch.setattr(equimesh.planar.boundary.sides, "_place_corners_on_a_grid", lambda *args: None)
        assert _fingerprint(np.array(lengths) * l, angles, l, spacing) == pinned
    assert _fingerprint(np.array(lengths) * l, angles, l, spacing) == (grid or pinned)


def test_a_side_shorter_than_l_is_refused_as_impossible():
    from equimesh.planar.polygon import check_edges_at_least

    with pytest.raises(InvalidPolygonError) as err:
        check_edges_at_least(as_polygon([[0, 0], [4, 0], [4, 0.5], [0, 0.5]]), 1.0)
    assert str(err.value) == (
        "no mesh with every edge in [l, 2l] exists (both ends of a side are nodes, so some mesh "
        "edge on it is no longer than the side): edge (1, 2) has length 0.5, shorter than l = 1.0"
    )


def test_separation_refusal_says_first_what_is_proven():
    """Close points at a corner of the sector lemma: the refusal is the proof that no mesh exists."""
    from equimesh.planar.boundary.separation import check_boundary_separation

    poly = as_polygon(_leaving(5.4), 3.0)
    with pytest.raises(
        InvalidPolygonError, match=r"^no mesh with every edge in \[l, 2l\] exists for l = 3.0: at the corner"
    ):
        check_boundary_separation(poly, resample_boundary(poly, 3.0, 1.5), 3.0)


def test_points_closer_than_l_across_a_notch_do_not_see_each_other():
    """A V-shaped notch of 16 degrees cut into a square: points 0.5 apart on its two walls, the segment between them
    outside the polygon; Lemma 3 (1) concerns mutually visible points only, so the check accepts."""
    from equimesh.planar.boundary.separation import check_boundary_separation

    poly = as_polygon([[0, 0], [10, 0], [10, 10], [6, 10], [5, 3], [4, 10], [0, 10]], 1.0)
    boundary = resample_boundary(poly, 1.0)
    assert pdist(boundary.points).min() == pytest.approx(0.5, rel=1e-12)
    assert check_boundary_separation(poly, boundary, 1.0) is None


@pytest.mark.parametrize("opposite, refused", [(1.5, False), (1.5 * (1.0 - 2.0 * REL_TOL), True)])
def test_no_separation_when_the_first_points_are_closer_than_l_up_to_rel_tol(opposite, refused):
    """A triangle with sides 1.6 and 1.7 at corner 0 (both below 2l, l = 1.5: the first points are their far ends):
    refused when the opposite side is below (1 - REL_TOL) l, not when it is l."""
    from equimesh.planar.boundary.separation import _unseparable_corner

    x = (1.7**2 - opposite**2 + 1.6**2) / 3.2
    assert (
        _unseparable_corner(as_polygon([[0, 0], [1.6, 0], [x, math.sqrt(1.7**2 - x * x)]]), 1.5) is not None
    ) == refused


def test_no_separation_reads_the_far_ends_of_the_first_point_ranges():
    """The 30 degree triangle with a hole near the far end of its arriving side's range [l, 1.5 l]: the triangle of
    the corner and the far ends is not covered, the corner not refused (with the near end it would be)."""
    from equimesh.planar.boundary.separation import _unseparable_corner

    poly = as_polygon([[0.0, 0.0], [1.6, 0.0], _at(30.0, 2.5)], None, [[[1.1, 0.5], [1.25, 0.5], [1.2, 0.62]]])
    assert _unseparable_corner(poly, 1.0) is None


@pytest.mark.parametrize("hole_at, halvings", [(3.3, 1), (1.5, 2), (5.0, 0)])
def test_visible_radii_halve_the_sides_until_the_corners_triangle_is_in_the_polygon(hole_at, halvings):
    """A 20 degree triangle with sides 4 and a small hole at hole_at along the corner's bisector direction (none at
    5: outside): the sides are halved until the triangle they span with the corner misses the hole, then scaled up
    again by bisection to within 2^-VISIBLE_BISECTIONS of touching it."""
    from equimesh.planar.boundary.separation import VISIBLE_BISECTIONS, _sees_within, _visible_radii

    x, y = hole_at * math.cos(math.radians(7.0)), hole_at * math.sin(math.radians(7.0))
    holes = [[[x - 0.05, y - 0.03], [x + 0.05, y - 0.03], [x, y + 0.04]]] if hole_at < 4.0 else None
    poly = as_polygon([[0.0, 0.0], [4.0, 0.0], _at(20.0, 4.0)], None, holes)
    ring = poly.rings[0]
    sides = (ring.local_edge_lengths[0], ring.local_edge_lengths[-1])  # in the local frame, as the caller passes them
    radii = _visible_radii(poly.region, ring, 0, sides)
    assert _sees_within(poly.region, ring, 0, *radii)
    if not halvings:
        assert radii == sides
        return
    t = radii[0] / sides[0]
    assert radii[1] == pytest.approx(sides[1] * t, rel=1e-15) and 0.5**halvings < t < 2.0 * 0.5**halvings
    assert not _sees_within(poly.region, ring, 0, *(x * (t + 2.0**-VISIBLE_BISECTIONS * 0.5**halvings) for x in sides))


def test_a_run_of_sharp_corners_goes_on_through_coupling_sides_only():
    """The dart of 30 degrees (corners 30, 30, 270, 30; sides 3.5, 1.28, 1.28, 3.5): the run through the tip is
    barb, tip, barb (3, 0, 1), from any of them.  With a tip side longer
    than 2 l + 2 l + 4 l (K = 2) it is cut there."""
    from equimesh.planar.boundary.sides import sharp_run as _run

    angles, lengths = [30.0, 30.0, 270.0, 30.0], [3.5, 1.28, 1.28, 3.5]
    for c in (3, 0, 1):
        assert _run(lengths, angles, 1.0, c) == [3, 0, 1]
    assert _run([8.5, 1.28, 1.28, 3.5], angles, 1.0, 3) == [3, 0] and _run([8.5, 1.28, 1.28, 8.5], angles, 1.0, 0) == [
        0
    ]
    assert _run([8.0, 1.28, 1.28, 8.0], angles, 1.0, 0) == [3, 0, 1]  # 8 l is the limit, included


@pytest.mark.parametrize("threshold", [1.0, 0.7, 0.3, 0.26, 0.1, 2.0**-63, 0.9 * 2.0**-63])
def test_visible_radii_end_on_the_last_bisection_step_seen(monkeypatch, threshold):
    """With a stand-in visibility (the sides scaled by t are seen iff t <= threshold): halved to the first 2^-k seen
    (k < 64, else nothing seen: (0, 0)), then VISIBLE_BISECTIONS bisections between 2^-k and 2^-(k - 1): the largest
    t = 2^-k (1 + j 2^-VISIBLE_BISECTIONS) seen; the sides as they are when seen whole."""
    from fractions import Fraction

    monkeypatch.setattr(
        equimesh.planar.boundary.separation,
        "_sees_within",
        lambda grown, ring, i, a, b: a <= 2.0 * threshold and b <= 4.0 * threshold,
    )
    radii = separation._visible_radii(None, None, 0, (2.0, 4.0))
    if threshold >= 1.0:
        assert radii == (2.0, 4.0)
        return
    k = math.ceil(-math.log2(threshold))
    if k >= 64:
        assert radii == (0.0, 0.0)
        return
    step = Fraction(2) ** -k / 2**separation.VISIBLE_BISECTIONS
    t = Fraction(2) ** -k + math.floor((Fraction(threshold) - Fraction(2) ** -k) / step) * step
    assert radii == (float(2 * t), float(4 * t))


#: A triangle with two sharp corners on its base (29.4 and 23.07 degrees), each placeable alone, not together
#: (docs/decisions.md, "Sharp corners in a row decided jointly"); scaled by 6 with l = 6 (the local frame scales by
#: 1/4, so local and given lengths differ).
_PAIR_TRIANGLE = [[0.0, 0.0], [25.5, 0.0], _at(29.4, 12.6)]
_REFUSED_TOGETHER = (
    "cannot meet Lemma 3 (1) together for l = 6.0: no split of their sides of {sides} (the middle {middle} shared) into "
    "parts of [l, 2l] keeps every two points of different sides l apart at {at} (decided on a grid of cells), so no "
    "Step 2 separates them (a limit of the paper's method, not a proof that no mesh exists; docs/proofs.md, 'Sharp "
    "corners'); use a smaller l, longer sides or wider corners"
)


def _dart():
    from equimesh.testing.shapes import sharp_dart

    return as_polygon(6.0 * sharp_dart(30, (30, 30), 3.5), 6.0)


@pytest.mark.parametrize("corner", [0, 1])
def test_a_pair_is_refused_together_from_either_of_its_corners(corner):
    """The offending pairs may lie at either corner of the pair: both ask for the pair (with the corner before)."""
    from equimesh.planar.boundary.separation import _unplaceable_chain

    error = _unplaceable_chain(as_polygon(_PAIR_TRIANGLE, 6.0), 6.0, [(0, corner)])
    assert (
        str(error)
        == "the corners at vertex 0 at (0, 0) (29.4 degrees) and vertex 1 at (25.5, 0) (23.0697 degrees) "
        + _REFUSED_TOGETHER.format(sides="12.6, 25.5, 15.785056381722754", middle="one", at="both corners")
    )


@pytest.mark.parametrize("corner", [0, 1, 3])
def test_a_run_of_three_is_refused_after_its_pairs(corner):
    """The dart sharp_dart(30, (30, 30), 3.5): each pair is placeable (so decided and passed over; the pair through the
    notch is not sharp, passed over too), the run of three through any of its corners refused, named in ring order."""
    from equimesh.planar.boundary.separation import _unplaceable_chain

    names = (
        "vertex 3 at (20.28444235, 5.435199947) (30 degrees), vertex 0 at (0, 0) (30 degrees) and vertex 1 at "
        "(20.28444235, -5.435199947) (30 degrees) "
    )
    assert str(_unplaceable_chain(_dart(), 6.0, [(0, corner)])) == "the corners at " + names + _REFUSED_TOGETHER.format(
        sides="7.686533479473213, 21.0, 21.0, 7.686533479473213", middle="ones", at="every corner"
    )


def test_a_lone_sharp_corner_or_one_at_exactly_the_sharp_threshold_is_not_decided_jointly(monkeypatch):
    """A sharp corner whose neighbours are not sharp is no run (nothing decided jointly); a pair whose wider corner is
    exactly SHARP_CORNER is not sharp (strict), with the threshold moved onto the pair triangle's 29.4 degrees."""

    assert separation._unplaceable_chain(as_polygon([[0.0, 0.0], [5.0, 0.0], [4.0, 3.0]]), 1.0, [(0, 0)]) is None
    poly = as_polygon(_PAIR_TRIANGLE, 6.0)
    monkeypatch.setattr(equimesh.planar.boundary.sides, "SHARP_CORNER", poly.rings[0].inner_angle(0))
    monkeypatch.setattr(separation, "SHARP_CORNER", poly.rings[0].inner_angle(0))
    assert separation._unplaceable_chain(poly, 6.0, [(0, 0)]) is None


def test_the_joint_refusal_reads_each_corners_visible_radii_in_side_order(monkeypatch):
    """Each corner of the run gets the radii seen in P grown by REL_TOL l for its sides (leaving, arriving), passed to
    the proof per corner as (T_j, T_(j+1)); stand-ins record them and refute nothing."""
    from equimesh.planar.boundary import chain as _coupled

    poly, seen, decided = _dart(), [], []
    lp = poly.local_length(6.0)

    def radii(grown, ring, c, sides):
        assert grown.equals(poly.region.buffer(REL_TOL * lp))
        seen.append((c, tuple(sides)))
        return 10.0 * c + 1.0, 10.0 * c + 2.0

    monkeypatch.setattr(equimesh.planar.boundary.separation, "_visible_radii", radii)
    monkeypatch.setattr(_coupled, "chain_unplaceable", lambda *args: decided.append(args) and False)
    assert separation._unplaceable_chain(poly, 6.0, [(0, 0)]) is None
    edges = tuple(poly.rings[0].local_edge_lengths[[2, 3, 0, 1]])  # T_0 .. T_3 of the run 3, 0, 1
    assert seen[-3:] == [(3, (edges[1], edges[0])), (0, (edges[2], edges[1])), (1, (edges[3], edges[2]))]
    assert decided[-1][1:] == (edges, lp, (32.0, 31.0, 2.0, 1.0, 12.0, 11.0))


def test_a_pair_placed_jointly_takes_the_shared_sides_points_and_completes_the_others():
    """The triangle of 29.4 and 23.07 degrees on a base of 5.25 l (placeable together): the base takes place_chain's
    points of T_1, the other two sides are completed; every part in [l, 2l], both corners' sides l apart.  A run with
    a corner that is not sharp is not placed."""
    from equimesh.planar.boundary import chain as _coupled
    from equimesh.planar.boundary.sides import _corner_gap, _grid_chain, side_positions

    apex = 5.25 * math.sin(math.radians(23.069711979788835)) / math.sin(math.radians(180.0 - 29.4 - 23.069711979788835))
    ring = as_polygon([[0.0, 0.0], [5.25, 0.0], _at(29.4, apex)], 1.0).rings[0]
    lengths, angles = ring.local_edge_lengths, [ring.inner_angle(i) for i in range(3)]
    found = _coupled.place_chain(tuple(math.radians(a) for a in angles[:2]), tuple(lengths[[2, 0, 1]]), 1.0)
    sides = side_positions(lengths, angles, 1.0)
    trial = _grid_chain(sides, lengths, angles, 1.0, 2.0, [0, 1])
    assert trial[0][1] == lengths[0] and np.array_equal(trial[0][0], np.concatenate([[0.0], found[1][:-1]]))
    for (num, den), length in zip(trial, lengths):
        parts = np.diff(np.append(num / den * length, length))
        assert np.all(parts >= (1.0 - REL_TOL)) and np.all(parts <= 2.0 * (1.0 + REL_TOL))
    assert min(_corner_gap(trial, lengths, angles, 1.0, c) for c in (0, 1)) >= 1.0 - REL_TOL
    assert _grid_chain(sides, lengths, angles, 1.0, 2.0, [1, 2]) is None


@pytest.mark.parametrize(
    "angles, lengths, run",
    [
        ([29.4, 23.07, 150.0, 157.53], [5.25, 10.0, 6.0, 2.6], [0, 1]),
        ([30.0, 30.0, 30.0, 150.0, 120.0], [3.5, 3.5, 10.0, 6.0, 3.5], [0, 1, 2]),
    ],
)
def test_a_long_last_side_placed_jointly_keeps_its_points_beyond_the_cut(angles, lengths, run):
    """The side leaving the run's last corner is 10 l long with uneven points (parts 1, 1.5, 2, 2, 2, 1.5 l from that
    corner): place_chain cuts it past K l, its own points at least l beyond the cut are kept, read from that corner
    (the middle is split again), for a pair and for a run of three."""
    from equimesh.planar.boundary.sides import _grid_chain

    far = run[-1]
    sides = [(np.arange(math.ceil(x / 2.0)) * (x / math.ceil(x / 2.0)), x) for x in lengths]
    sides[far] = np.array([0.0, 1.0, 2.5, 4.5, 6.5, 8.5]), 10.0
    num, den = _grid_chain(sides, np.array(lengths), angles, 1.0, 2.0, run)[far]
    assert den == 10.0 and num[0] == 0.0 and set(num[-3:]) == {4.5, 6.5, 8.5}
    assert np.all(np.diff(np.append(num, den)) >= 1.0 - REL_TOL) and np.all(
        np.diff(np.append(num, den)) <= 2.0 + REL_TOL
    )
