"""The reference engine's candidate rules (Steps 3-4 of Algorithm INCREMENT), tested directly.

:mod:`equimesh.planar.insertion.reference` lists two kinds of candidates for
the farthest point: visible circumcentres (candidate 1, with the
near-constraint and ``SLIVER_GAP`` exclusions) and midpoints of long
constraint segments (candidate 2, with the apex rule).  Each rule is checked
on a hand-built triangle whose circumcentre and circumradius are known, with
thresholds approached from both sides; then the choice among candidates
(largest value, ties by smallest x, then y) and the order of the inserted
values along a run.
"""

import numpy as np
import pytest
from hypothesis import given
from insertion_cases import NEAR_CONSTRAINT, at_exactly, circle_triangle
from invariants import assert_values_non_increasing
from strategies import problems

from equimesh import REL_TOL
from equimesh.planar.boundary.resample import resample_boundary
from equimesh.planar.increment import validate_problem1
from equimesh.planar.insertion import reference
from equimesh.planar.insertion.region import Region
from equimesh.tolerance import SLIVER_GAP

ONE = np.array([[0, 1, 2]])


#: Points 2 to 4 of the midpoint tests: a triangle away from the constraint [0, 1].
FAR_POINTS, FAR = [[0.0, 5.0], [1.0, 5.0], [0.0, 6.0]], np.array([[2, 3, 4]])


def test_circumcentre_listed_with_its_radius():
    """Candidate 1: a visible circumcentre far from every constraint, with value its circumradius."""
    points, segments = circle_triangle(0.5, 1.5)
    centers, radii = reference.circle_candidates(points, ONE, segments, 1.0)
    np.testing.assert_allclose(centers, [[0.0, 0.5]], atol=1e-15)
    np.testing.assert_allclose(radii, [1.5], rtol=1e-15)


@pytest.mark.parametrize("factor, listed", [(1.0 - 0.5 * REL_TOL, True), (1.0 - 2.0 * REL_TOL, False)])
def test_circumradius_threshold_is_l_up_to_rel_tol(factor, listed):
    """Only circumradii of at least (1 - REL_TOL) l are candidates."""
    points, segments = circle_triangle(0.5, 1.5)
    centers, _ = reference.circle_candidates(points, ONE, segments, 1.5 / factor)
    assert len(centers) == listed


@pytest.mark.parametrize("gap, radius, listed", NEAR_CONSTRAINT)
def test_near_constraint_and_sliver_gap_rules(gap, radius, listed):
    """A circumcentre near a constraint is left out below REL_TOL l, and below SLIVER_GAP l when its value is l."""
    points, segments = circle_triangle(gap, radius)
    centers, _ = reference.circle_candidates(points, ONE, segments, 1.0)
    assert len(centers) == listed


@pytest.mark.parametrize("tol, radius", [(REL_TOL, 3.0), (SLIVER_GAP, 1.0)])
def test_near_rules_are_inclusive_at_any_l(tol, radius):
    """A gap of exactly REL_TOL l (any value), or exactly SLIVER_GAP l with value l, is left out, at l far from 1.

    The triangle has gap 1/2 and circumradius ``radius / (2 tol)``; l is the float for which ``tol * l`` is the
    computed gap exactly.
    """
    points, segments, l = at_exactly(tol, radius)
    centers, radii = reference.circle_candidates(points, ONE, segments, l)
    assert len(centers) == 0
    centers, _ = reference.circle_candidates(points, ONE, segments, np.nextafter(l, 0.0) * (1.0 - 4.0 * REL_TOL))
    assert len(centers) == 1  # a hair farther than tol l: listed


def test_circumcentre_behind_a_constraint_is_hidden():
    """An obtuse triangle on a constraint: its circumcentre lies behind the constraint and is not visible."""
    points = np.array([[-1.0, 0.0], [1.0, 0.0], [0.0, 0.2], [10.0, 10.0], [12.0, 10.0]])
    centers, radii = reference.circle_candidates(points, ONE, np.array([[3, 4]]), 1.0)
    np.testing.assert_allclose(radii, [2.6], rtol=1e-14)  # seen when the constraint is elsewhere
    centers, radii = reference.circle_candidates(points, ONE, np.array([[0, 1], [3, 4]]), 1.0)
    assert len(centers) == 0


@pytest.mark.parametrize("half, listed", [(1.0 - 0.5 * REL_TOL, True), (1.0 - 2.0 * REL_TOL, False)])
def test_midpoint_threshold_is_2l_up_to_rel_tol(half, listed):
    """Candidate 2: only constraints of length at least 2 (1 - REL_TOL) l have their midpoint listed."""
    points = np.array([[0.0, 0.0], [2.0 * half, 0.0], *FAR_POINTS])
    mids, values, index = reference.midpoint_candidates(points, FAR, np.array([[0, 1]]), 1.0)
    assert len(mids) == len(values) == len(index) == listed and index.dtype == np.int64
    if listed:
        np.testing.assert_array_equal(mids, [[half, 0.0]])
        assert values.tolist() == [half] and index.tolist() == [0]


@pytest.mark.parametrize("apex_y, value", [(0.5, 0.5), (3.0, 1.25), (None, 1.25)])
def test_midpoint_value_is_capped_by_the_apex(apex_y, value):
    """The midpoint's value is min(|ab| / 2, |m - apex|); without a triangle on ab it is |ab| / 2."""
    points = np.array([[0.0, 0.0], [2.5, 0.0], *FAR_POINTS, [1.25, apex_y or 1.0]])
    triangles = np.vstack([FAR, [[0, 1, 5]]]) if apex_y is not None else FAR
    _, values, _ = reference.midpoint_candidates(points, triangles, np.array([[0, 1]]), 1.0)
    assert values.tolist() == [value]


def test_each_midpoint_is_capped_by_its_own_apex():
    """Two constraints, each with its triangle: values min(1.25, 0.5) and min(1.25, 3); the first apex is point 0."""
    points = np.array([[1.25, 0.5], [0.0, 0.0], [2.5, 0.0], [10.0, 0.0], [12.5, 0.0], [11.25, 3.0]])
    triangles, segments = np.array([[1, 2, 0], [3, 4, 5]]), np.array([[1, 2], [3, 4]])
    _, values, index = reference.midpoint_candidates(points, triangles, segments, 1.0)
    assert values.tolist() == [0.5, 1.25] and index.tolist() == [0, 1]


def test_apex_is_the_third_vertex_of_the_triangle_on_each_pair():
    """Either direction of the pair; -1 for a pair on no triangle, and for every pair when there is no triangle."""
    tri = np.array([[0, 1, 2], [2, 1, 3]])
    assert reference.apexes(tri, np.array([[1, 0], [0, 2], [3, 1], [3, 2], [0, 3], [4, 5]])).tolist() == [
        2,
        1,
        2,
        1,
        -1,
        -1,
    ]
    assert reference.apexes(np.empty((0, 3), dtype=np.int64), np.array([[0, 1]])).tolist() == [-1]
    assert reference.apexes(tri, np.empty((0, 2), dtype=np.int64)).tolist() == []


def test_points_and_segments_have_the_engines_dtypes_whatever_the_callers():
    """Integer coordinates and int32 segments in, float points and int64 segments out (as from the fast engine),
    even when nothing is inserted (a unit square)."""
    segments = np.array([[0, 1], [1, 2], [2, 3], [3, 0]], dtype=np.int32)
    result = reference.run(Region(np.array([[0, 0], [1, 0], [1, 1], [0, 1]]), segments, np.empty((0, 2))), 1.0)
    assert len(result.points) == 4 and result.points.dtype == float and result.segments.dtype == np.int64


def test_best_candidate_prefers_the_largest_value_and_reports_the_split():
    """A right triangle on its hypotenuse: the circumcentre is on the constraint, so the midpoint wins and splits it."""
    points = np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]])
    segments = np.array([[0, 1], [1, 2], [2, 0]])
    point, value, split = reference.best_candidate(points, ONE, segments, 1.0)
    assert point.tolist() == [1.0, 1.0] and value == pytest.approx(np.sqrt(2.0), rel=1e-15) and split == 1
    point, value, split = reference.best_candidate(points, ONE, segments, 2.0)
    assert point is None and value == 0.0 and split is None


def _tied_squares(order):
    """Four unit squares of side 2 in a 2 x 2 block, triangulated; ``order`` permutes the triangles."""
    g = np.array([[x, y] for y in (0.0, 2.0, 4.0) for x in (0.0, 2.0, 4.0)])
    cells = [(i, j) for j in range(2) for i in range(2)]
    tri = []
    for i, j in cells:
        a, b, c, d = 3 * j + i, 3 * j + i + 1, 3 * (j + 1) + i + 1, 3 * (j + 1) + i
        tri += [[a, b, c], [a, c, d]]
    ring = [0, 1, 2, 5, 8, 7, 6, 3]
    segments = np.column_stack([ring, np.roll(ring, -1)])
    return g, np.array(tri)[order], segments


@pytest.mark.parametrize("order", [list(range(8)), list(range(7, -1, -1)), [4, 5, 2, 3, 6, 7, 0, 1]])
def test_ties_are_broken_by_smallest_x_then_y(order):
    """Four circumcentres of value sqrt(2) l exactly: the one at (1, 1) wins, whatever the triangle order."""
    points, triangles, segments = _tied_squares(order)
    centers, radii = reference.circle_candidates(points, triangles, segments, 1.0)
    assert len(set(radii.tolist())) == 1 and len({tuple(c) for c in centers.tolist()}) == 4  # a real tie
    point, value, split = reference.best_candidate(points, triangles, segments, 1.0)
    assert point.tolist() == [1.0, 1.0] and value == radii[0] and split is None


def test_ties_in_x_are_broken_by_smallest_y():
    """The left column only (x = 1): the circumcentre (1, 1) wins over (1, 3)."""
    points, triangles, segments = _tied_squares(list(range(8)))
    left = triangles[[0, 1, 4, 5]]
    ring = [0, 1, 4, 7, 6, 3]
    point, _, _ = reference.best_candidate(points, left, np.column_stack([ring, np.roll(ring, -1)]), 1.0)
    assert point.tolist() == [1.0, 1.0]


@given(problems)
def test_inserted_values_never_increase(problem):
    """Farthest-point insertion: inserting a point only shrinks distances, so the inserted values do not increase.

    Every family of inputs, cocircular ones included (tests/planar/test_engines.py checks the tie-free ones
    against the fast engine); every value reaches (1 - REL_TOL) l.
    """
    vertices, l = problem
    poly, l = validate_problem1(vertices, l)
    boundary = resample_boundary(poly, l)
    result = reference.run(Region(boundary.points, boundary.segments, np.empty((0, 2))), poly.local_length(l))
    assert_values_non_increasing(result)
    assert np.all(result.values >= (1.0 - REL_TOL) * poly.local_length(l))
