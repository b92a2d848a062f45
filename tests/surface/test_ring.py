"""The ring resampler (``surface/ring.py``, Step 2 on a closed polyline with corners), tested directly by hand.

What must hold: each side between corners is split into Step 2's count of
equal parts along its arc (fewer where a chord would be shorter than l),
starting at its corner, in the polyline's order; with one corner the side
runs once around the loop; next to a corner sharper than SHARP_CORNER the
side keeps one straight edge from the corner to the point ``stagger_reach
+ l`` away, the reach computed from the angle of those straight edges; the
points and the parameters are interpolated where the vertices lie, the
ends of a side bit for bit; a side no split leaves with chords of at least
l is refused with the caller's exception.  Each test runs in milliseconds,
so that the mutants of ``ring.py`` (``make mutation``) are cheap to kill;
the property test with Problem 2 on the result is in ``tests/surface/test_outline.py``.
"""

import math

import numpy as np
import pytest

from equimesh._geometry import Polyline, inner_angle
from equimesh.errors import SurfaceTooSmallError
from equimesh.planar.boundary.sides import stagger_reach
from equimesh.surface import ring
from equimesh.surface.ring import resample_ring

AFFINE = np.array([[2.0, -1.0], [0.5, 3.0]])


def densified(corners, per_side):
    """The closed polyline through ``corners`` with ``per_side`` segments on each side, and the corners' indices."""
    corners = np.asarray(corners, dtype=float)
    t = np.arange(per_side)[:, None] / per_side
    xy = np.vstack([a + t * (b - a) for a, b in zip(corners, np.roll(corners, -1, axis=0))])
    return xy, np.arange(len(corners)) * per_side


def along(a, b, fractions):
    """Points at ``fractions`` of the segment ``ab``."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    return a + np.asarray(fractions, float)[:, None] * (b - a)


def resampled(xy, corners, l, spacing):
    """resample_ring with parameters ``xy @ AFFINE + 7``; checks they follow the points."""
    params = xy @ AFFINE + 7.0
    r = resample_ring(xy, params, corners, l, spacing)
    np.testing.assert_allclose(r.params, r.points @ AFFINE + 7.0, atol=1e-12)
    return r


SQUARE = [(0.0, 0.0), (10.0, 0.0), (10.0, 10.0), (0.0, 10.0)]


def square_at(s):
    """Points of SQUARE's boundary at arc lengths ``s`` (mod 40) from (0, 0), counter-clockwise."""
    s = np.asarray(s, float) % 40.0
    side, t = np.floor(s / 10.0).astype(int), (s % 10.0) / 10.0
    a, b = np.array(SQUARE)[side], np.array(SQUARE)[(side + 1) % 4]
    return a + t[:, None] * (b - a)


@pytest.mark.parametrize("spacing, parts", [(2.0, 5), (1.5, 7)])
def test_square_sides_split_into_step2_parts(spacing, parts):
    """Sides 10 long at l = 1: k = ceil(10 / spacing) equal parts, from each corner in order, whatever the polyline's
    own points (every 2.5)."""
    xy, corners = densified(SQUARE, 4)
    r = resampled(xy, corners, 1.0, spacing)
    f = np.arange(parts) / parts
    expected = np.vstack([along(a, b, f) for a, b in zip(SQUARE, np.roll(SQUARE, -1, axis=0))])
    np.testing.assert_allclose(r.points, expected, atol=1e-12)
    assert r.side.tolist() == np.repeat(np.arange(4), parts).tolist()
    assert r.side.dtype.kind == "i"
    for i, c in enumerate(corners):
        assert np.array_equal(r.points[i * parts], xy[c])


def test_one_corner_runs_once_around_the_loop():
    """Corner 5, (10, 2.5): one side 40 long, 20 parts of 2 from it, around the loop."""
    xy, _ = densified(SQUARE, 4)
    r = resampled(xy, [5], 1.0, 2.0)
    assert len(r.points) == 20 and r.side.tolist() == [0] * 20
    np.testing.assert_allclose(r.points, square_at(12.5 + 2.0 * np.arange(20)), atol=1e-12)
    assert np.array_equal(r.points[0], xy[5])


def test_a_side_through_the_end_of_the_polyline():
    """Corners 5 and 13: the second side wraps from (0, 7.5) through the polyline's first point (0, 0) to (10, 2.5),
    20 long: 10 parts of 2."""
    xy, _ = densified(SQUARE, 4)
    r = resampled(xy, [5, 13], 1.0, 2.0)
    assert r.side.tolist() == [0] * 10 + [1] * 10
    np.testing.assert_allclose(r.points, square_at(12.5 + 2.0 * np.arange(20)), atol=1e-12)
    assert np.array_equal(r.points[10], xy[13])


@pytest.mark.parametrize("l", [1.0, 0.25])
def test_a_sharp_corner_keeps_a_straight_edge_of_reach_plus_l(l):
    """A 30-degree corner between sides 20 l long (K = ceil(1 / sin 30) = 2): each side keeps the straight edge from
    the corner to 3 l from it, the rest of side 0 (17 l) and of side 2 (17 l) in 9 parts; the base, 2 * 20 l sin 15
    = 10.35 l, in 6 (its corners are 75 degrees: not sharp).  At l = 0.25 the reach K l is below 1."""
    a = math.radians(30.0)
    wedge = [(0.0, 0.0), (20.0 * l, 0.0), (20.0 * l * math.cos(a), 20.0 * l * math.sin(a))]
    xy, corners = densified(wedge, 4)
    assert stagger_reach(inner_angle(xy, 0), l) == 2.0 * l
    r = resampled(xy, corners, l, 2.0)
    assert r.side.tolist() == [0] * 10 + [1] * 6 + [2] * 10
    np.testing.assert_allclose(
        r.points[:10], along(wedge[0], wedge[1], np.r_[0.0, (3.0 + 17.0 * np.arange(9) / 9) / 20.0]), atol=1e-12 * l
    )
    np.testing.assert_allclose(r.points[10:16], along(wedge[1], wedge[2], np.arange(6) / 6), atol=1e-12 * l)
    np.testing.assert_allclose(
        r.points[16:], along(wedge[2], wedge[0], np.r_[17.0 * np.arange(9) / 9, 17.0] / 20.0), atol=1e-12 * l
    )


def bent_wedge(bend):
    """A 40-degree corner at the origin whose leaving side bends toward the other after 1.5 (by ``bend`` degrees),
    closed by a far base: the straight edges from the corner meet at a sharper angle than the polyline's sides."""
    a, b = math.radians(40.0), math.radians(bend)
    return np.array(
        [
            (0.0, 0.0),
            (1.5, 0.0),
            (1.5 + 30.0 * math.cos(b), 30.0 * math.sin(b)),
            (30.0 * math.cos(a), 30.0 * math.sin(a)),
        ]
    )


@pytest.mark.parametrize("mirrored", [False, True])
@pytest.mark.parametrize("bend", [0.0, 15.0, 25.0, 30.0])
def test_straight_edges_at_a_sharp_corner_match_their_own_angle(bend, mirrored):
    """The straight edges from the corner end at stagger_reach(angle between them) + l from it: the reach is
    recomputed from the straight edges' angle (K = 2 down to 30 degrees; bent by 25 or 30 degrees the edges to 3 l
    meet at 24 or 21 degrees, K = 3, and the edges to 4 l settle it)."""
    xy, corners = bent_wedge(bend), [0, 2, 3]
    if mirrored:  # the arriving side bends (reflected in the x axis, order reversed to keep the region on the left)
        xy, corners = np.vstack([xy[:1], xy[:0:-1]]) * [1.0, -1.0], [0, 1, 2]
    r = resampled(xy, corners, 1.0, 2.0)
    corner, p, q = r.points[0], r.points[1], r.points[-1]
    assert np.array_equal(corner, xy[0])
    angle = inner_angle(np.array([q, corner, p]), 1)
    reach = stagger_reach(angle, 1.0) + 1.0
    np.testing.assert_allclose([np.linalg.norm(p), np.linalg.norm(q)], [reach, reach], rtol=1e-12)
    assert reach == (3.0 if bend < 20.0 else 4.0)


def test_arc_at_distance_by_hand():
    """Along (0, 0), (4, 0), (4, 4): distance 3 at arc 3, 4 at the bend (arc 4), 5 at (4, 3) (arc 7); never 6."""
    pts = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 4.0]])
    arc = np.array([0.0, 4.0, 8.0])
    assert [ring.arc_at_distance(Polyline(pts, closed=False, arc=arc), d) for d in (3.0, 4.0, 5.0)] == [3.0, 4.0, 7.0]
    assert ring.arc_at_distance(Polyline(pts, closed=False, arc=arc), 6.0) is None
    # The first point at that distance: the polyline comes back to 3 from (0, 0) at arc 11 too.
    back = np.array([[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0], [0.0, 3.0]])
    assert ring.arc_at_distance(Polyline(back, closed=False, arc=np.array([0.0, 4.0, 8.0, 12.0, 13.0])), 3.0) == 3.0
    # Anywhere in the plane; and the first time, also when the polyline reaches the distance at a vertex, turns back
    # inside and crosses it again: (0, 0), (4, 0), (2, 0), (6, 0) is 4 from (0, 0) at arc 4 and 8.
    assert ring.arc_at_distance(Polyline(pts + [5.0, -3.0], closed=False, arc=arc), 5.0) == 7.0
    assert (
        ring.arc_at_distance(Polyline(np.array([[0.0, 0.0], [4.0, 0.0], [2.0, 0.0], [6.0, 0.0]]), closed=False), 4.0)
        == 4.0
    )
    # A segment that starts off the start point: (1, 0) to (1, 5) reaches 2 at (1, sqrt(3)).
    assert ring.arc_at_distance(
        Polyline(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 5.0]]), closed=False), 2.0
    ) == pytest.approx(1.0 + math.sqrt(3.0), rel=1e-15)


def test_points_at_arc_positions_keep_the_ends_bit_for_bit():
    """(0, 0), (3, 0), (3, 4) at arc 0, 1.5, 3, 5, 7 (values carried alike); the last segment ends at
    x = 0.7 + (0.1 - 0.7), which is not 0.1 in floating point: the end is the polyline's own point."""
    xy = np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 4.0]])
    line = Polyline(xy, closed=False, values=xy * 2.0)
    s = np.array([0.0, 1.5, 3.0, 5.0, 7.0])
    pts, prm = line.at(s), line.values_at(s)
    np.testing.assert_allclose(pts, [[0, 0], [1.5, 0], [3, 0], [3, 2], [3, 4]], atol=1e-15)
    np.testing.assert_allclose(prm, 2.0 * pts, atol=1e-15)
    xy = np.array([[0.3, 0.0], [0.7, 0.0], [0.1, 0.0]])
    assert 0.7 + (0.1 - 0.7) != 0.1
    line = Polyline(xy, closed=False, values=xy[::-1].copy(), arc=np.array([0.0, 0.4, 1.0]))
    s = np.array([0.0, 0.4, 1.0])
    pts, prm = line.at(s), line.values_at(s)
    assert np.array_equal(pts[[0, -1]], xy[[0, -1]]) and np.array_equal(prm[[0, -1]], xy[[-1, 0]])
    # A point of the polyline asked for (arc 1.0 is (0.1, 0)) is that point: the segment it starts, at t = 0.
    xy = np.array([[0.3, 0.0], [0.7, 0.0], [0.1, 0.0], [0.1, 1.0]])
    pts = Polyline(xy, closed=False, arc=np.array([0.0, 0.4, 1.0, 2.0])).at(np.array([0.0, 1.0, 2.0]))
    assert np.array_equal(pts, xy[[0, 2, 3]])


def test_a_hairpin_side_falls_back_to_fewer_parts():
    """A side up 2, across 0.5, down 2 (arc 4.5): 3 parts put two points 0.5 apart; 2 parts, via (0.25, 2), do not."""
    xy = np.array([[0.0, 0.0], [0.0, 2.0], [0.5, 2.0], [0.5, 0.0]])
    arc = np.array([0.0, 2.0, 2.5, 4.5])
    pts, prm = ring.split_side(Polyline(xy, closed=False, values=xy, arc=arc), (0.0, 4.5), 1.0, 2.0)
    np.testing.assert_allclose(pts, [[0, 0], [0.25, 2], [0.5, 0]], atol=1e-15)
    np.testing.assert_allclose(prm, pts, atol=1e-15)
    assert ring.split_side(Polyline(xy, closed=False, values=xy, arc=arc), None, 1.0, 2.0) == (
        None,
        None,
    )  # one straight edge: its ends are 0.5 apart
    # Up 0.5, across 1.2, down 0.5 (arc 2.2, k = 2): the middle (0.6, 0.5) is 0.78 from the ends; one part, the chord.
    xy = np.array([[0.0, 0.0], [0.0, 0.5], [1.2, 0.5], [1.2, 0.0]])
    pts, _ = ring.split_side(Polyline(xy, closed=False, values=xy), (0.0, 2.2), 1.0, 2.0)
    assert np.array_equal(pts, xy[[0, -1]])


def test_a_side_with_no_split_is_refused_with_its_numbers():
    """A 30 x 0.5 rectangle split at its corners: the short sides (0.5) are refused, side 1 first; the default
    message, or the caller's exception from (side, arc, chord)."""
    xy, corners = densified([(0.0, 0.0), (30.0, 0.0), (30.0, 0.5), (0.0, 0.5)], 2)
    with pytest.raises(SurfaceTooSmallError) as err:
        resample_ring(xy, xy, corners, 1.0, 2.0)
    assert str(err.value) == (
        "side 1 of the boundary polyline is 0.5 long (its ends 0.5 apart), too short to split into parts of at least l"
    )
    seen = []
    with pytest.raises(KeyError):
        resample_ring(xy, xy, corners, 1.0, 2.0, too_short=lambda *args: seen.append(args) or KeyError(args[0]))
    assert seen == [(1, 0.5, 0.5)]
    # A hairpin side: arc 1.7, ends 0.5 apart.
    xy = np.array([[0.0, 0.0], [0.0, 0.6], [0.5, 0.6], [0.5, 0.0], [0.5, -5.0], [0.0, -5.0]])
    with pytest.raises(
        SurfaceTooSmallError, match=r"^side 0 of the boundary polyline is 1\.7 long \(its ends 0\.5 apart\)"
    ):
        resample_ring(xy, xy, [0, 3], 1.0, 2.0)


def test_a_side_too_short_for_the_straight_edge_is_one_edge():
    """A 30-degree corner whose arriving side is 2.5 long, short of the 3 l the straight edges need: both its sides
    are one straight edge each, (0, 0) to (20, 0) and back from (2.17, 1.25)."""
    a = math.radians(30.0)
    quad = [(0.0, 0.0), (20.0, 0.0), (20.0, 10.0), (2.5 * math.cos(a), 2.5 * math.sin(a))]
    xy, corners = densified(quad, 4)
    r = resampled(xy, corners, 1.0, 2.0)
    assert r.side.tolist() == [0] + [1] * 5 + [2] * 10 + [3]
    assert np.array_equal(r.points[[0, 1, 6, 16]], np.array(quad)[[0, 1, 2, 3]])


def test_a_stretch_shorter_than_l_between_the_straight_edges_is_one_edge():
    """A 30-degree corner whose leaving side is 3.5 long: after its straight edge (3 l) 0.5 l is left, so the side is
    one edge to (3.5, 0); the arriving side, 20 long, between two sharp corners (31 and 30 degrees, K = 2 each),
    keeps both straight edges and 14 in 7 parts."""
    a = math.radians(30.0)
    far = (20.0 * math.cos(a), 20.0 * math.sin(a))
    quad = [(0.0, 0.0), (3.5, 0.0), (14.0, 4.0), far]
    xy, corners = densified(quad, 4)
    r = resampled(xy, corners, 1.0, 2.0)
    assert r.side.tolist() == [0] + [1] * 6 + [2] * 3 + [3] * 9
    assert np.array_equal(r.points[1], [3.5, 0.0])
    np.testing.assert_allclose(r.points[10:], along(far, quad[0], np.r_[0.0, 3.0:18.0:2.0] / 20.0), atol=1e-12)


def test_single_precision_input_is_computed_in_double():
    """float32 points and parameters give the result of the same values in float64, bit for bit."""
    xy, corners = densified(SQUARE, 4)
    xy = (xy * 0.3 + 0.1).astype(np.float32)
    params = (np.arange(len(xy))[:, None] ** 3 * [1.0, 7.0] + 0.1).astype(np.float32)  # differences inexact in float32
    double = resample_ring(xy.astype(float), params.astype(float), corners, 0.35, 1.5)
    single = resample_ring(xy, params, corners, 0.35, 1.5)
    assert single.points.dtype == single.params.dtype == np.float64
    assert np.array_equal(single.points, double.points) and np.array_equal(single.params, double.params)


def test_at_distance_solves_each_segment_on_its_own():
    """Two segments at once, each with its own origin: the fraction at which each reaches distance 2 (x = 2 on the
    first, y = 2 on the second)."""
    origin = np.array([[0.0, 0.0], [0.0, 0.0]])
    a, b = np.array([[1.0, 0.0], [0.0, 1.0]]), np.array([[3.0, 0.0], [0.0, 5.0]])
    np.testing.assert_allclose(ring.at_distance(origin, a, b, 2.0), [0.5, 0.25], rtol=1e-15)


def test_reach_on_an_open_polyline_from_each_start_and_none_past_its_end():
    """Along the x axis from vertices 0, 1 and 2 of (0, 0) ... (3, 0), distance 1.5 is first reached at x = 1.5 and
    2.5; from vertex 2 only past the end (nan), although the polyline's first vertex is that far."""
    line = Polyline(np.array([[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]]), closed=False)
    found = ring.reach(line, 1.5, [0, 1, 2])
    np.testing.assert_allclose(found[:2], [1.5, 2.5], rtol=1e-15)
    assert np.isnan(found[2])


def test_reach_on_a_closed_polyline_runs_on_past_its_length():
    """Around the unit square from its last vertex (0, 1): distance 1.2 is first reached on the first side, past
    the turn's end, at arc 4 + sqrt(1.2^2 - 1); from vertex 0 on the second side, at arc 1 + sqrt(1.2^2 - 1)."""
    square = Polyline(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]))
    run = math.sqrt(1.2**2 - 1.0)
    np.testing.assert_allclose(ring.reach(square, 1.2, [3, 0]), [4.0 + run, 1.0 + run], rtol=1e-14)


def test_reach_follows_a_closed_polyline_to_its_last_segment():
    """From vertex 0 every vertex is within distance 1 but the last, (0.3, -2): the point is found on the last
    segment of the turn, exactly 1 from the start."""
    loop = Polyline(np.array([[0.0, 0.0], [0.5, 0.1], [0.6, 0.0], [0.3, -2.0]]))
    (s,) = ring.reach(loop, 1.0, [0])
    assert loop.arc[2] < s < loop.arc[3]
    assert np.linalg.norm(loop.at(np.array([s]))[0]) == pytest.approx(1.0, rel=1e-14)
