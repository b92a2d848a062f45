"""Step 2's corner rules (``planar/polygon.py``) exactly at their thresholds.

What must hold: a corner is refused as unmeshable or unseparable only when
the distance it is decided by is *below* ``(1 - REL_TOL) l`` (a distance of
exactly that is accepted, like every edge check); a segment between two
boundary points that leaves P by less than ``REL_TOL l`` (in units of l, not
``REL_TOL / l``) counts as inside P, both for the separation check and for
the corner triangle of ``_unseparable_corner``; a short side tries the
candidates with the fewest multiples of l from a corner that is not sharp
first.  The floats are built so that the distance is exactly the threshold
(asserted), at l far from 1 so that l and 1 / l differ.

The sharp-corner code after the short-side search, by hand: which corners a
pair of boundary points lies at, a side measured from either corner, a side
cut by the grid and completed, the message naming a corner; the refusals
decided on a grid of cells in full at l = 3 (local length 1.5), the order in
which they go through the corners, each side checked within its own
visibility radius (a dent below ``REL_TOL l`` leaves it seen whole); the grid
placement of one corner's or two corners' sides, and the trials of the grid
search in their order (stubbed placements).
"""

import math

import numpy as np
import pytest
import shapely

import equimesh
from equimesh.errors import InvalidPolygonError
from equimesh.planar.boundary import corner as _corner
from equimesh.planar.boundary import resample, separation
from equimesh.planar.boundary import sides as boundary_sides
from equimesh.planar.boundary.resample import Boundary
from equimesh.planar.boundary.separation import check_boundary_separation
from equimesh.planar.boundary.sides import side_positions
from equimesh.planar.polygon import as_polygon
from equimesh.testing.shapes import sharp_dart
from equimesh.tolerance import REL_TOL, at_least


def first_corner(vertices, l):
    """The polygon and its first corner ``(ring, i, theta, leaving, arriving)`` (local lengths)."""
    poly = as_polygon(np.array(vertices), l)
    return poly, next(separation._corners(poly))


def chord(a, b, theta):
    """Law of cosines: points ``a`` and ``b`` from a corner of ``theta`` radians, on its two sides."""
    return math.sqrt(max(a * a + b * b - 2.0 * a * b * math.cos(theta), 0.0))


@pytest.mark.parametrize("beta, refused", [(1.2981954331865397, False), (1.2982, True), (1.2981, False)])
def test_unmeshable_corner_exactly_at_the_threshold(beta, refused):
    """A 25-degree corner with a side of beta ~ 1.278 l (l = 1.015625): the sector's far point (radius 2l, widened by
    REL_TOL) is exactly (1 - REL_TOL) l from the side's end at beta = 1.2981954331865397 (one float lower it is
    farther): not refused; at 1.2982 it is closer, refused; at 1.2981 farther."""
    l, a = 1.015625, math.radians(25.0)
    poly, (_, _, theta, leaving, _) = first_corner(
        [(0.0, 0.0), (beta, 0.0), (10 * l * math.cos(a), 10 * l * math.sin(a))], l
    )
    lp = poly.local_length(l)
    far = max(chord(r, leaving, theta) for r in ((1.0 - REL_TOL) * lp, 2.0 * lp * (1.0 + REL_TOL)))
    assert (far == (1.0 - REL_TOL) * lp) == (beta == 1.2981954331865397)
    error = separation._unmeshable_corner(poly, l)
    assert (error is not None) == refused
    if refused:
        assert str(error).startswith(
            "no mesh with every edge in [l, 2l] exists for l = 1.015625: at the corner at vertex 0 at (0, 0)"
        )


@pytest.mark.parametrize("a, refused", [(2.250271104332659, False), (2.2502, True), (2.2503, False)])
def test_unseparable_corner_exactly_at_the_threshold(a, refused):
    """A 38.94-degree corner between sides a ~ 2.25 and 2.25 (single parts at l = 1.5): the first points of its two
    sides are its neighbours, exactly (1 - REL_TOL) l apart at a = 2.250271104332659: not refused; closer at
    a = 2.2502, refused; farther at 2.2503."""
    l, t = 1.5, math.radians(38.94)
    poly, (_, _, theta, leaving, arriving) = first_corner(
        [(0.0, 0.0), (a, 0.0), (2.25 * math.cos(t), 2.25 * math.sin(t))], l
    )
    assert (chord(leaving, arriving, theta) == (1.0 - REL_TOL) * poly.local_length(l)) == (a == 2.250271104332659)
    error = separation._unseparable_corner(poly, l)
    assert (error is not None) == refused
    if refused:
        assert str(error).startswith(
            "the corner at vertex 0 at (0, 0) (38.94 degrees) cannot meet Lemma 3 (1) for l = 1.5"
        )


def dented(dent):
    """A 30-degree corner at (0, 0) between sides 2 long whose far ends p, q are 1.035 apart, with a fourth vertex
    ``dent`` inside the triangle, from the middle of pq towards the corner: the segment pq leaves P by ``dent``."""
    p, q = np.array([2.0, 0.0]), 2.0 * np.array([math.cos(math.radians(30.0)), math.sin(math.radians(30.0))])
    m = (p + q) / 2.0
    return np.array([(0.0, 0.0), p, m - dent * m / np.linalg.norm(m), q])


@pytest.mark.parametrize("dent, inside", [(1.1e-9, True), (2e-9, False)])
def test_a_segment_leaving_p_by_less_than_rel_tol_l_is_inside(dent, inside):
    """At l = 1.5 a segment leaving P by 1.1e-9 is inside P grown by REL_TOL l = 1.5e-9 (and not REL_TOL / l = 6.7e-10);
    2e-9 is outside.  So the boundary points p and q, 1.035 < l apart, see each other across the dent (the separation
    check refuses them), and the corner triangle (0, 0), p, q lies in P (the corner is unseparable)."""
    l = 1.5
    vertices = dented(dent)
    poly = as_polygon(vertices, l)
    assert np.array_equal(poly.rings[0].local, vertices)  # the local frame is the caller's at l = 1.5
    pq = Boundary(vertices[[1, 3]], np.array([True, True]), np.array([1, 3]), np.array([0, 0]))
    if inside:
        with pytest.raises(
            InvalidPolygonError, match=r"^the corner at vertex 0 at \(0, 0\) \(30 degrees\) cannot meet"
        ):
            check_boundary_separation(poly, pq, l)
        assert separation._unseparable_corner(poly, l) is not None
    else:
        assert check_boundary_separation(poly, pq, l) is None
        assert separation._unseparable_corner(poly, l) is None


def test_a_short_side_takes_the_fewest_multiples_from_a_corner_that_is_not_sharp():
    """The triangle (0, 0), (2.42, 0), (4.64, 2.35) at l = 1, spacing 1.5: corners of 26.9 (sharp), 133.4 (not) and
    19.8 degrees (sharp).  Side 1 (3.23 long, from the 133-degree corner to the 19.8-degree one) is separated with
    one multiple of l from its first corner and one staggered point from its last: points at 0, 1 and length - 1;
    the candidate with two multiples (0, 1, 2) is tried after it."""
    poly = as_polygon(np.array([(0.0, 0.0), (2.42, 0.0), (4.64, 2.35)]), 1.0)
    ring = poly.rings[0]
    angles = [ring.inner_angle(i) for i in range(3)]
    np.testing.assert_allclose(angles, [26.861, 133.371, 19.769], atol=1e-3)
    lengths = ring.local_edge_lengths
    numerators, denominator = side_positions(lengths, angles, 1.0, 1.5)[1]
    assert denominator == lengths[1]
    np.testing.assert_allclose(numerators, [0.0, 1.0, lengths[1] - 1.0], atol=1e-12)


# --------------------------------------------------------------------------- the grid placement's helpers, by hand


def ring_polygon():
    """A pentagon (ring 0) with a square hole (ring 1), at l = 1."""
    pentagon = [(10.0 * math.cos(2 * math.pi * k / 5), 10.0 * math.sin(2 * math.pi * k / 5)) for k in range(5)]
    return as_polygon(np.array(pentagon), 1.0, holes=[np.array([(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)])])


#: Boundary points by (ring, edge, is a vertex): 0 inside edge 4, 1 inside edge 0, 2 the vertex 1 (on edges 0 and 1),
#: 3 inside edge 2, 4 inside edge 0 of the hole.
RING_POINTS = Boundary(
    np.zeros((5, 2)), np.array([False, False, True, False, False]), np.array([4, 0, 1, 2, 0]), np.array([0, 0, 0, 0, 1])
)


@pytest.mark.parametrize(
    "pairs, corners",
    [
        ([(0, 1)], [(0, 0)]),  # edges 4 and 0 meet at corner 0 (the ring wraps)
        ([(1, 0)], [(0, 0)]),  # either order
        ([(2, 0)], [(0, 0)]),  # the vertex 1 lies on edge 0 too
        ([(2, 3)], [(0, 2)]),  # and on edge 1, which meets edge 2 at corner 2
        ([(1, 3)], []),  # edges 0 and 2 share no corner
        ([(0, 1), (1, 3), (1, 2)], [(0, 0), (0, 1)]),  # every pair adds its corners
        ([(4, 1), (3, 2)], [(0, 2)]),  # a pair on two rings has no corner, and the next pair still counts
    ],
)
def test_corners_of_a_pair_are_where_their_edges_meet(pairs, corners):
    """``_corners_of``: the corners at which two boundary points lie on the two sides, a vertex on both its edges."""
    assert separation._corners_of(ring_polygon(), RING_POINTS, np.array(pairs)) == corners


def test_from_corner_measures_a_side_from_either_end():
    """Side 1 (5 long, points at 0, 1 and 3 of it) measured from corner 1, which it leaves, and from corner 2, where it
    arrives; the far end is included."""
    sides, lengths = [None, (np.array([0.0, 1.0, 3.0]), 5.0), None], [4.0, 5.0, 6.0]
    np.testing.assert_array_equal(boundary_sides._from_corner(sides, lengths, 1, 1), [1.0, 3.0, 5.0])
    np.testing.assert_array_equal(boundary_sides._from_corner(sides, lengths, 2, 1), [2.0, 4.0, 5.0])


@pytest.mark.parametrize(
    "leaving, expected", [(True, [0.0, 1.0, 2.5, 3.5, 5.0, 7.0]), (False, [0.0, 2.0, 4.0, 5.5, 6.5, 8.0])]
)
def test_grid_side_keeps_the_points_at_least_l_past_the_cut(leaving, expected):
    """A side 9 long (l = 1) that the grid cut at 2.5 (points 1 and 2.5 from the corner): of its current points 1.5,
    2.5, 3.5, 5 and 7, those at least l past the cut are kept, 3.5 (exactly l past it) included, and the middle
    between, exactly l, is one part.  Positions are from the side's first corner: the corner itself if it leaves
    it, the far end if it arrives."""
    numerators, length = boundary_sides._grid_side(
        9.0, np.array([1.0, 2.5]), np.array([1.5, 2.5, 3.5, 5.0, 7.0, 9.0]), leaving, 1.0, 1.5
    )
    assert length == 9.0
    np.testing.assert_array_equal(numerators, expected)


def test_grid_side_drops_the_points_within_l_of_the_cut():
    """A side 10 long cut at 6: its current point 5.5, before the cut but less than l from it, is not kept (else the
    middle would be too short and the grid's own last point dropped); 7.5 is."""
    numerators, _ = boundary_sides._grid_side(
        10.0, np.array([1.5, 3.0, 4.5, 6.0]), np.array([1.0, 2.5, 4.0, 5.5, 7.5, 10.0]), True, 1.0, 1.5
    )
    np.testing.assert_array_equal(numerators, [0.0, 1.5, 3.0, 4.5, 6.0, 7.5])


def test_grid_side_ending_at_the_far_end_is_the_grid_points():
    """Points ending at the side's far end are the side (from its first corner either way)."""
    for leaving, expected in ((True, [0.0, 1.5, 3.0]), (False, [0.0, 1.0, 2.5])):
        numerators, length = boundary_sides._grid_side(
            4.0, np.array([1.5, 3.0, 4.0]), np.array([4.0]), leaving, 1.0, 1.5
        )
        np.testing.assert_array_equal(numerators, expected)


def pentagon_point(k):
    return 10.0 * np.array([math.cos(2 * math.pi * k / 5), math.sin(2 * math.pi * k / 5)])


@pytest.mark.parametrize(
    "edges, start",
    [
        (
            (4, 0),
            "the corner at vertex 0 at (10, 0) (108 degrees) is not handled for l = 1.0: boundary points on edge "
            "(4, 0) and edge (0, 1) are ",
        ),
        ((0, 1), "the corner at vertex 1 at "),
        ((1, 0), "the corner at vertex 1 at "),
        ((0, 2), "polygon is too narrow for l = 1.0: boundary points on edge (0, 1) and edge (2, 3) are "),
    ],
)
def test_separation_error_names_the_corner_of_two_adjacent_sides(edges, start):
    """``_separation_error``: two points on the sides of one corner (edges 4 and 0 meet at corner 0, the ring wrapping)
    name that corner; on sides apart, the neck."""
    poly = ring_polygon()
    points = np.array([(pentagon_point(e) + pentagon_point(e + 1)) / 2.0 for e in edges])
    error = separation._separation_error(
        poly, Boundary(points, np.zeros(2, bool), np.array(edges), np.zeros(2, int)), 1.0, 0, 1
    )
    assert str(error).startswith(start)


# --------------------------------------------------------------------------- refusals decided on a grid of cells


def at(angle, r):
    """The point ``r`` from the origin at ``angle`` degrees."""
    return np.array([r * math.cos(math.radians(angle)), r * math.sin(math.radians(angle))])


def refusal(vertices, l):
    """The message of :func:`check_boundary_separation` on the Step 2 points of Problem 2 (spacing 1.5)."""
    poly = as_polygon(np.array(vertices) * l, l)
    with pytest.raises(InvalidPolygonError) as error:
        check_boundary_separation(poly, resample.resample_boundary(poly, l, 1.5), l)
    return str(error.value)


HANDLED = (
    "no Step 2 separates them (a limit of the paper's method, not a proof that no mesh exists; docs/proofs.md, "
    "'Sharp corners'); sides of at least 12.0 are handled; use a smaller l, longer sides or a wider corner"
)


@pytest.mark.parametrize(
    "vertices, message",
    [
        # 20 degrees, sides 3.45 l and 3.3 l: refused by the relaxation of the corner alone
        (
            [(0.0, 0.0), (3.45, 0.0), at(20.0, 3.3)],
            "the corner at vertex 0 at (0, 0) (20 degrees) cannot meet Lemma 3 (1) for l = 3.0: no split of its sides of "
            "10.350000000000001 and 9.9 into parts of [l, 2l] keeps every two points of different sides l apart "
            "(decided on a grid of cells), so " + HANDLED,
        ),
        # 21 degrees, sides 3.48 l and 3.25 l: refused only on the finer cells of the joint decision with no second corner
        (
            [(0.0, 0.0), (3.48, 0.0), at(21.0, 3.25)],
            "the corner at vertex 0 at (0, 0) (21 degrees) cannot meet Lemma 3 (1) for l = 3.0: no split of its sides of "
            "10.44 and 9.75 into parts of [l, 2l] keeps every two points of different sides l apart "
            "(decided on a grid of cells), so " + HANDLED,
        ),
        # 29.4 and 23.07 degrees sharing a side of 4.25 l: each corner alone can be separated, not both
        (
            [(0.0, 0.0), (4.25, 0.0), at(29.4, 2.1)],
            "the corners at vertex 0 at (0, 0) (29.4 degrees) and vertex 1 at (12.75, 0) (23.0697 degrees) cannot meet "
            "Lemma 3 (1) together for l = 3.0: no split of their sides of 6.300000000000001, 12.75, 7.892528190861376 (the "
            "middle one shared) into parts of [l, 2l] keeps every two points of different sides l apart at both corners "
            "(decided on a grid of cells), so no Step 2 separates them (a limit of the paper's method, not a proof that no "
            "mesh exists; docs/proofs.md, 'Sharp corners'); use a smaller l, longer sides or wider corners",
        ),
    ],
)
def test_a_corner_refused_on_a_grid_says_so_in_the_callers_lengths(vertices, message):
    """At l = 3 (local length 1.5, scale 1/2) the refusals of one corner and of two corners sharing a side, in full."""
    assert refusal(vertices, 3.0) == message


def test_unplaceable_corner_goes_past_corners_not_sharp_or_placeable():
    """A quadrilateral with a 20-degree corner that cannot be separated (vertex 0), a 160.7-degree one and a 7.5-degree
    one with long sides (placeable): asked in that order, the first two are passed over and the third refused."""
    l = 3.0
    poly = as_polygon(np.array([(0.0, 0.0), (3.45, 0.0), (12.0, 3.0), at(20.0, 3.3)]) * l, l)
    ring = poly.rings[0]
    assert [round(ring.inner_angle(i), 2) for i in range(4)] == [20.0, 160.67, 7.46, 171.88]
    assert separation._unplaceable_corner(poly, l, [(0, 2)]) is None
    assert str(separation._unplaceable_corner(poly, l, [(0, 1), (0, 2), (0, 0)])).startswith(
        "the corner at vertex 0 at"
    )


def test_unplaceable_chain_asks_each_corner_with_the_previous_and_the_next():
    """The triangle of the joint refusal with its vertices rolled, so that the two sharp corners are 1 and 2: asked at
    either of them, or at the blunt corner 0 before them, the pair (1, 2) is refused; asked at the blunt corner
    alone, it is paired with its neighbours, one blunt."""
    l = 3.0
    poly = as_polygon(np.array([at(29.4, 2.1), (0.0, 0.0), (4.25, 0.0)]) * l, l)
    for corners in ([(0, 1)], [(0, 2)], [(0, 0), (0, 2)]):
        assert str(separation._unplaceable_chain(poly, l, corners)).startswith(
            "the corners at vertex 1 at (0, 0) (29.4 degrees)"
        )
    assert separation._unplaceable_chain(poly, l, [(0, 0)]) is None


def test_unplaceable_chain_passes_over_a_pair_that_can_be_separated():
    """An arrowhead: notch 255.7 degrees, barb 45.8, tip 36.9, barb 21.7.  The tip with the first barb can be separated,
    with the second it cannot: asked at both barbs, the first pair is passed over and the second refused (pairs are
    decided before runs); asked at the first barb alone, its pairs pass and the run of all three is refused."""
    poly = as_polygon(np.array([(3.7, 0.0), (4.39, 2.27), (0.0, 0.0), (5.12, -0.86)]), 1.0)
    assert str(separation._unplaceable_chain(poly, 1.0, [(0, 1)])).startswith(
        "the corners at vertex 1 at (4.39, 2.27) (45.7498 degrees), vertex 2 at (0, 0) (36.8777 degrees) and vertex 3 at"
    )
    assert str(separation._unplaceable_chain(poly, 1.0, [(0, 1), (0, 3)])).startswith(
        "the corners at vertex 2 at (0, 0) (36.8777 degrees) and vertex 3 at (5.12, -0.86) (21.6656 degrees) cannot"
    )


@pytest.mark.parametrize(
    "vertices, l, start",
    [
        # the shared side (3.749) is longer than the other side of the 24.1-degree corner (1.872)
        (
            [(0.0, 0.0), (3.749, 0.0), (2.861, 0.669), (4.108, 1.838)],
            1.0,
            "the corners at vertex 3 at (4.108, 1.838) (19.0462",
        ),
        # the other side of the 18.96-degree corner (6.512) is longer than that of the 1.86-degree corner (1.896)
        (
            [(0.0, 0.0), (1.896, 0.0), (1.926, 0.506), (6.161, 2.117)],
            1.5,
            "the corners at vertex 3 at (6.161, 2.117) (1.8635",
        ),
    ],
)
def test_unplaceable_chain_checks_each_side_within_its_own_radius(vertices, l, start):
    """Two sharp corners at vertices 3 and 0 whose sides have different lengths, each seen whole from its corner: each
    side is checked up to its own length, and the pair is refused."""
    assert str(separation._unplaceable_chain(as_polygon(np.array(vertices), l), l, [(0, 0)])).startswith(start)


def test_a_lone_corner_checks_each_side_within_its_own_radius():
    """A 19.05-degree corner with sides 3.11 l and 1.15 l, refused only on the finer cells of the joint decision: the
    leaving side is checked up to 3.11 l, not to the arriving side's 1.15 l."""
    poly = as_polygon(np.array([(0.0, 0.0), (3.11, 0.0), at(19.05, 1.15)]), 1.0)
    lengths = poly.rings[0].local_edge_lengths
    assert not _corner.corner_unplaceable(math.radians(19.05), (lengths[0], lengths[2]), 1.0, (lengths[0], lengths[2]))
    assert str(separation._unplaceable_corner(poly, 1.0, [(0, 0)])).startswith(
        "the corner at vertex 0 at (0, 0) (19.05 degrees)"
    )


def with_dent(vertices, side, dent):
    """``vertices`` with a vertex added in the middle of side ``side``, moved ``dent`` towards vertex 0."""
    p, q = np.asarray(vertices[side]), np.asarray(vertices[(side + 1) % len(vertices)])
    m = (p + q) / 2.0
    return np.insert(
        np.asarray(vertices), side + 1, m - dent * (m - vertices[0]) / np.linalg.norm(m - vertices[0]), axis=0
    )


def seen_region(monkeypatch, refusal, poly, l):
    """``refusal(poly, l, [(0, 0)])`` and the grown region it passed to :func:`separation._visible_radii` (the first)."""
    grown, visible = [], separation._visible_radii
    monkeypatch.setattr(
        equimesh.planar.boundary.separation,
        "_visible_radii",
        lambda region, *args: grown.append(region) or visible(region, *args),
    )
    return refusal(poly, l, [(0, 0)]), grown[0]


@pytest.mark.parametrize("dent, covered", [(1.1e-9, True), (2e-9, False)])
def test_a_corner_triangle_dented_by_less_than_rel_tol_l_is_seen_whole(dent, covered, monkeypatch):
    """At l = 1.5 (the local frame the caller's) a dent of 1.1e-9 in the side opposite a sharp corner (20 degrees,
    3.45 l and 3.3 l) is inside P grown by REL_TOL l = 1.5e-9 (not REL_TOL / l = 6.7e-10), so the corner's triangle is
    seen whole (the side's undented midpoint is in the region the sides are checked against) and refused as
    without the dent; a dent of 2e-9 is not."""
    l, vertices = 1.5, np.array([(0.0, 0.0), (3.45, 0.0), at(20.0, 3.3)])
    error, grown = seen_region(
        monkeypatch, separation._unplaceable_corner, as_polygon(with_dent(vertices * l, 1, dent), l), l
    )
    assert grown.covers(shapely.Point((vertices[1] + vertices[2]) * l / 2.0)) == covered
    assert error is not None or not covered


@pytest.mark.parametrize("dent, covered", [(1.1e-9, True), (2e-9, False)])
def test_a_pair_whose_triangle_is_dented_by_less_than_rel_tol_l_is_seen_whole(dent, covered, monkeypatch):
    """The same for two corners (40.3 and 35.4 degrees) sharing a side of 4.03 l at l = 1.5, dented in the middle of the
    side after them: the region the joint refusal checks against covers the undented side with the dent of 1.1e-9
    (and the pair is refused), not with 2e-9."""
    l, side = 1.5, 4.03 * math.sin(math.radians(35.4)) / math.sin(math.radians(75.7))
    vertices = np.array([(0.0, 0.0), (4.03, 0.0), at(40.3, side)])
    error, grown = seen_region(
        monkeypatch, separation._unplaceable_chain, as_polygon(with_dent(vertices * l, 1, dent), l), l
    )
    assert grown.covers(shapely.Point((vertices[1] + vertices[2]) * l / 2.0)) == covered
    assert error is not None or not covered


# --------------------------------------------------------------------------- the grid search of a ring's sharp corners

#: A ring of sides 5.25, 9, 7 and 9 l with corners of 29.4, 23.07, 100 and 207.5 degrees (side_positions reads lengths
#: and angles only): corners 0 and 1 share the side 5.25 l, their other sides are long (cut past K l = 3 l).
GRID_LENGTHS, GRID_ANGLES = np.array([5.25, 9.0, 7.0, 9.0]), [29.4, 23.069711979788835, 100.0, 207.5]


def positions(sides):
    return [np.round(num, 9).tolist() for num, _ in sides]


@pytest.mark.parametrize(
    "last, placed",
    [
        (
            9.0,
            [
                [0.0, 1.0, 2.0, 3.25],
                [0.0, 1.0, 3.0, 4.5, 6.0, 7.5],
                [0.0, 1.0, 2.0, 3.0, 4.0],
                [0.0, 1.5, 3.0, 4.5, 6.0, 7.0625],
            ],
        ),
        (2.1, [[0.0, 1.75, 2.75, 4.0625], [0.0, 2.0, 3.0, 4.5, 6.0, 7.5], [0.0, 1.0, 2.0, 3.0, 4.0], [0.0, 1.1]]),
    ],
)
def test_grid_chain_places_the_three_sides_of_two_corners(last, placed):
    """_grid_chain at corners 0 and 1: side 3 (arriving at 0, ``last`` long), 0 (shared) and 1 (leaving 1) placed
    jointly, a long side kept past its cut from where it was; both corners then l apart, side 2 untouched; None when
    the next corner is not sharp."""
    lengths = np.append(GRID_LENGTHS[:3], last)
    sides = side_positions(lengths, GRID_ANGLES, 1.0, 1.5)
    trial = boundary_sides._grid_chain(sides, lengths, GRID_ANGLES, 1.0, 1.5, [0, 1])
    assert positions(trial) == placed
    assert trial[2] is sides[2]
    assert all(at_least(boundary_sides._corner_gap(trial, lengths, GRID_ANGLES, 1.0, c), 1.0) for c in (0, 1))
    assert boundary_sides._grid_chain(sides, lengths, GRID_ANGLES, 1.0, 1.5, [1, 2]) is None


@pytest.mark.parametrize(
    "keep, first, last",
    [
        ((False, False), [0.0, 1.25, 3.25], [0.0, 1.5, 3.0, 4.5, 6.0, 7.0625]),
        ((True, False), [0.0, 1.0, 2.0, 3.25], [0.0, 1.5, 3.0, 4.5, 6.0, 7.0625]),
        ((False, True), [0.0, 1.25, 3.25], [0.0, 1.5, 3.0, 4.5, 6.0, 7.0]),
    ],
)
def test_grid_sides_places_a_corners_two_sides_keeping_those_asked(keep, first, last):
    """_grid_sides at corner 0: its leaving side 0 and arriving side 3 placed on the grid, a side flagged in ``keep``
    passed as it is (up to the cut past K l of a long side); the other sides untouched."""
    sides = side_positions(GRID_LENGTHS, GRID_ANGLES, 1.0, 1.5)
    trial = boundary_sides._grid_sides(sides, GRID_LENGTHS, GRID_ANGLES, 1.0, 1.5, 0, keep)
    assert positions(trial) == [first, positions(sides)[1], positions(sides)[2], last]
    if keep[0]:
        assert positions(trial)[0] == positions(sides)[0]


def test_place_corners_on_a_grid_tries_the_trials_in_order(monkeypatch):
    """Every corner reported closer than l, in turn, goes through the trials of the docstring in order: itself free,
    leaving side kept, arriving side kept, the next (previous) corner first then this one keeping the shared side,
    this one first then the next (previous), jointly with the next, jointly with the previous, with its whole run of
    three or more (when it has one); a trial with a corner
    that is not sharp (corner 2, 100 degrees) is skipped, the others still tried (corner 2's own joint trial with the
    previous corner too).  (The grid placements are stubbed: each returns its input, and no trial separates anything.)"""
    calls, angles = [], [29.4, 23.0, 100.0, 20.0, 15.0]
    sides = side_positions(np.full(5, 4.0), angles, 1.0, 1.5)
    monkeypatch.setattr(_corner, "corner_unplaceable", lambda *args: False)
    monkeypatch.setattr(equimesh.planar.boundary.sides, "_corner_gap", lambda *args: 0.0)
    monkeypatch.setattr(
        equimesh.planar.boundary.sides, "_grid_sides", lambda sides, *args: calls.append((args[-2], args[-1])) or sides
    )
    monkeypatch.setattr(
        equimesh.planar.boundary.sides, "_grid_chain", lambda sides, *args: calls.append((args[-1], "chain")) or sides
    )
    boundary_sides._place_corners_on_a_grid(sides, np.full(5, 4.0), angles, 1.0, 1.5)
    free, leaving, arriving = (False, False), (True, False), (False, True)

    def trials(c, after, before):
        """Each trial as its steps ``(corner, call recorded)``."""
        run = boundary_sides.sharp_run(np.full(5, 4.0), angles, 1.0, c)
        return [
            [(c, (c, free))],
            [(c, (c, leaving))],
            [(c, (c, arriving))],
            [(after, (after, free)), (c, (c, leaving))],
            [(before, (before, free)), (c, (c, arriving))],
            [(c, (c, free)), (after, (after, arriving))],
            [(c, (c, free)), (before, (before, leaving))],
            [(c, ([c, after], "chain"))],
            [(before, ([before, c], "chain"))],
            *([[(c, (run, "chain"))]] if len(run) > 2 else []),
        ]

    expected = [
        call
        for c in range(5)
        for trial in trials(c, (c + 1) % 5, (c - 1) % 5)
        if all(corner != 2 for corner, _ in trial)
        for _, call in trial
    ]
    assert calls == expected
    assert any(keep == "chain" and len(run) > 2 for run, keep in calls)  # a run of three or more was tried


def test_place_corners_on_a_grid_checks_every_corner_a_trial_touched(monkeypatch):
    """A trial is taken when the corners it touched and their neighbours are l apart: for a joint trial the two
    corners and one neighbour on each side (here the first trial that returns anything, the joint one)."""
    checked = []
    sides = side_positions(np.full(5, 4.0), [20.0] * 5, 1.0, 1.5)
    monkeypatch.setattr(_corner, "corner_unplaceable", lambda *args: False)
    monkeypatch.setattr(
        equimesh.planar.boundary.sides,
        "_corner_gap",
        lambda trial, *args: 0.0 if trial is sides else checked.append(args[-1]),
    )
    monkeypatch.setattr(equimesh.planar.boundary.sides, "_grid_sides", lambda *args: None)
    monkeypatch.setattr(equimesh.planar.boundary.sides, "_grid_chain", lambda trial, *args: list(trial))
    monkeypatch.setattr(boundary_sides, "at_least", lambda value, l: value is None)
    boundary_sides._place_corners_on_a_grid(sides, np.full(5, 4.0), [20.0] * 5, 1.0, 1.5)
    assert [set(checked[k : k + 4]) for k in range(0, 20, 4)] == [
        {4, 0, 1, 2},
        {0, 1, 2, 3},
        {1, 2, 3, 4},
        {2, 3, 4, 0},
        {3, 4, 0, 1},
    ]


def test_place_corners_on_a_grid_checks_a_lone_corner_and_its_neighbours(monkeypatch):
    """For a trial of one corner (here the first, its two sides free) the corner itself and its two neighbours are
    checked, each once."""
    checked = []
    sides = side_positions(np.full(5, 4.0), [20.0] * 5, 1.0, 1.5)
    monkeypatch.setattr(_corner, "corner_unplaceable", lambda *args: False)
    monkeypatch.setattr(
        equimesh.planar.boundary.sides,
        "_corner_gap",
        lambda trial, *args: 0.0 if trial is sides else checked.append(args[-1]),
    )
    monkeypatch.setattr(equimesh.planar.boundary.sides, "_grid_sides", lambda trial, *args: list(trial))
    monkeypatch.setattr(boundary_sides, "at_least", lambda value, l: value is None)
    boundary_sides._place_corners_on_a_grid(sides, np.full(5, 4.0), [20.0] * 5, 1.0, 1.5)
    assert sorted(checked[:3]) == [0, 1, 4] and [sorted(checked[k : k + 3]) for k in range(3, 15, 3)] == [
        [0, 1, 2],
        [1, 2, 3],
        [2, 3, 4],
        [0, 3, 4],
    ]


def test_a_dart_separated_only_by_its_run_of_three_is_meshed(monkeypatch):
    """A dart (tip 23.97 degrees, barbs 30.55 and 38.91, sides 4.42 l) whose three sharp corners no single corner or
    pair trial separates: the trial of the whole run places it (a chain of three returned), and it is meshed with
    every edge in [l, 2l] (found by a random search over darts; without the run trial it is refused)."""
    placed, chain = [], boundary_sides._grid_chain
    monkeypatch.setattr(
        equimesh.planar.boundary.sides,
        "_grid_chain",
        lambda *args: placed.append((len(args[-1]), chain(*args))) or placed[-1][1],
    )
    dart = sharp_dart(23.97192472430486, (30.54743423844858, 38.9057900966436), 4.424429730465021)
    mesh = equimesh.uniform_triangulation(dart, 1.0)
    assert any(n == 3 and found is not None for n, found in placed)
    lengths = mesh.edge_lengths()
    assert at_least(lengths.min(), 1.0) and lengths.max() <= 2.0 * (1.0 + REL_TOL)
