"""The fast engine (``planar/insertion/fast.py``): its kernels against the reference's geometry and the engine against
the reference.

What must hold:

* the circumcircle and the distance to a segment are the reference's (``equimesh._geometry``) bit for bit;
* the engine's arrays keep their rows when they grow, one cache line per triangle;
* each triangle's candidates are the reference's, also exactly at the
  thresholds of the rules, and the whole engine inserts the reference's
  points, its triangles in a fixed (slot) order.

Small inputs, so that the file runs in seconds with the kernels run as
Python (``NUMBA_DISABLE_JIT=1``, as mutation testing runs them:
``tools/mutation``).
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from insertion_cases import (
    NEAR_CONSTRAINT,
    assert_same_insertion,
    at_exactly,
    circle_triangle,
    contains,
    coordinates,
    exact_orient,
    problem1_runs,
    problem2_runs,
    square_ring,
    square_rings,
)
from invariants import assert_problem1_invariants

import equimesh
import equimesh.planar.increment
import equimesh.planar.strip
from equimesh import EquimeshError
from equimesh._geometry import circumcenters, point_segment_distance
from equimesh.errors import InternalError
from equimesh.planar.insertion import Region, arrays, candidates, fast, insert, reference
from equimesh.planar.insertion.buckets import empty_queue
from equimesh.planar.insertion.cdt import adjacency, cavity, locate, walk
from equimesh.planar.insertion.heap import MAX_SLOTS
from equimesh.planar.insertion.region import constrained_delaunay
from equimesh.planar.limits import node_estimate
from equimesh.testing.generators import rectangle, regular_polygon
from equimesh.tolerance import REL_TOL, SLIVER_GAP

# --------------------------------------------------------------------------- geometry as the reference's

finite = coordinates


triangles = st.lists(st.tuples(finite, finite), min_size=3, max_size=3).filter(lambda t: exact_orient(*t)[0] != 0)


@given(triangles, st.permutations([0, 1, 2]))
def test_circumcircle_is_the_reference_bit_for_bit(triangle, order):
    """Centre and radius are :func:`circumcenters` of the vertices in index order; g is their centroid."""
    P = np.array(triangle)
    cx, cy, r, gx, gy = candidates.circumcircle(P, *order)
    centre, radius = circumcenters(P[0], P[1], P[2])
    assert [cx, cy, r] == [*centre, radius]
    assert (gx, gy) == tuple((P[0] + P[1] + P[2]) / 3.0)


def _edge_distance(x, a, b, bound=np.inf):
    return candidates.edge_distance_within(np.array([a, b], dtype=float), 0, 1, *x, bound)


@given(st.tuples(finite, finite), st.tuples(finite, finite), st.tuples(finite, finite), st.floats(0, 1e6))
def test_edge_distance_within_a_bound_is_the_reference_bit_for_bit(x, a, b, bound):
    """At most the bound, the distance is the reference's bit for bit; above it, a number above the bound (so every
    comparison with the bound decides as the reference's distance)."""
    expected = point_segment_distance(np.array(x), np.array(a), np.array(b))
    assert _edge_distance(x, a, b) == expected
    got = _edge_distance(x, a, b, bound)
    assert got == expected if expected <= bound else got > bound


def test_edge_distance_by_hand():
    """Beyond either end the distance is to the end; over the segment, to the line; a point segment is a point."""
    assert _edge_distance((5.0, 4.0), (0.0, 0.0), (2.0, 0.0)) == 5.0
    assert _edge_distance((-3.0, 4.0), (0.0, 0.0), (2.0, 0.0)) == 5.0
    assert _edge_distance((1.5, -2.0), (0.0, 0.0), (2.0, 0.0)) == 2.0
    assert _edge_distance((4.0, 5.0), (1.0, 1.0), (1.0, 1.0)) == 5.0
    assert _edge_distance((0.25, 1.0), (0.0, 0.0), (0.5, 0.0)) == 1.0  # a segment shorter than 1


# --------------------------------------------------------------------------- the arrays


def test_grown_pads_with_zeros():
    a = np.array([[1, 2], [3, 4]], dtype=np.int64)
    g = arrays.grown(a, 5)
    assert g.dtype == a.dtype and g.tolist() == [[1, 2], [3, 4], [0, 0], [0, 0], [0, 0]]
    assert arrays.grown(np.array([1.5]), 3).tolist() == [1.5, 0.0, 0.0]


def test_extended_keeps_the_rows():
    a = np.array([[1, 2], [3, 4]], dtype=np.int64)
    g = arrays.extended(a, 5)
    assert g.dtype == a.dtype and g.shape == (5, 2) and g[:2].tolist() == [[1, 2], [3, 4]]


def test_the_triangle_store_is_one_cache_line_per_triangle():
    T = arrays.triangle_store(5)
    assert T.shape == (5, arrays.ROW) and T.dtype == np.int32 and T.ctypes.data % 64 == 0 and T.strides == (64, 4)
    V, N, S, mark, ver, alive = arrays.store_views(T)
    V[2], N[2], S[2], mark[2], ver[2], alive[2] = (1, 2, 3), (4, 5, 6), (7, 8, 9), 10, 11, 12
    assert T[2, :12].tolist() == list(range(1, 13))
    T[:3] = 7
    grown = arrays.grown_store(T, 9, 3)
    assert grown.shape == (9, arrays.ROW) and grown.ctypes.data % 64 == 0 and (grown[:3] == 7).all()


# --------------------------------------------------------------------------- the engine's candidates


def _assert_candidates(P, V, SA, SB, l):
    """Per triangle: the visible circumcentre and the constraint midpoints of value at least (1 - REL_TOL) l the
    reference lists, same bits, same values; the same circumcentres when the distance search gives up at once (a
    buffer of one triangle) and measures every constraint."""
    N, S, _ = adjacency(V, SA, SB, len(P))
    segments = np.column_stack([SA, SB])
    salive, alive = np.ones(len(SA), dtype=np.bool_), np.ones(len(V), dtype=np.bool_)
    lim, seen = candidates.limits(l), np.empty(candidates.NEAR_TRIANGLES, dtype=np.int64)
    centres, radii = reference.circle_candidates(P, V, segments, l)
    listed = {(x, y): r for (x, y), r in zip(centres.tolist(), radii.tolist())}
    queue = empty_queue(4 * len(V) + 1, 1, lim[0])
    H, q = queue[0], queue[4]
    q[0] = 0  # the lowest bucket the current one: every candidate goes into the heap
    nh = 0
    for t in range(len(V)):
        r, cx, cy, where = candidates.visible_circumcentre(
            P, V, N, S, SA, SB, salive, len(SA), alive, len(V), t, lim, seen
        )
        assert (r >= 0.0) == ((cx, cy) in listed)
        if r >= 0.0:
            assert r == listed[(cx, cy)] and contains(P, V, where, cx, cy)
        assert (
            candidates.visible_circumcentre(P, V, N, S, SA, SB, salive, len(SA), alive, len(V), t, lim, seen[:1])[0]
            == r
        )
        nh = candidates.push_candidates(
            P, V, N, S, SA, SB, salive, len(SA), alive, np.arange(len(V)), len(V), t, lim, seen, queue, nh
        )
    mids, values, split = reference.midpoint_candidates(P, V, segments, l)
    expected = sorted(
        [(-r, x, y, -1) for (x, y), r in zip(centres.tolist(), radii.tolist())]
        + [(-v, x, y, s) for (x, y), v, s in zip(mids.tolist(), values.tolist(), split.tolist()) if v >= lim[0]]
    )
    tags = [(int(H[i]["tag"]) >> 2, (int(H[i]["tag"]) & 3) - 1) for i in range(nh)]
    pushed = sorted((H[i]["key"], H[i]["x"], H[i]["y"], S[t, e] if e >= 0 else -1) for i, (t, e) in enumerate(tags))
    assert pushed == expected
    assert all(H[i]["version"] == t for i, (t, _) in enumerate(tags))  # each entry carries its triangle's version


@given(square_rings(), st.floats(0.3, 2.0), st.data())
def test_candidates_are_the_reference_candidates(ring, l, data):
    """:func:`_assert_candidates`; and ``constraint_gap`` is the distance to the nearest constraint whenever it is at
    most
    half the search reach, also when the search gives up (a buffer of one triangle) and measures every constraint.
    """
    P, V, SA, SB = ring
    _assert_candidates(P, V, SA, SB, l)
    N, S, _ = adjacency(V, SA, SB, len(P))
    salive, lim, seen = (
        np.ones(len(SA), dtype=np.bool_),
        candidates.limits(l),
        np.empty(candidates.NEAR_TRIANGLES, dtype=np.int64),
    )
    x, y = data.draw(st.tuples(st.floats(0.0, 6.0), st.floats(0.0, 6.0)))
    t = locate(P, V, N, np.ones(len(V), dtype=np.bool_), len(V), 0, x, y, len(V) + 1)
    if t >= 0:
        nearest = min(_edge_distance((x, y), P[a], P[b]) for a, b in zip(SA, SB))
        for reach, buffer in ((lim[4], seen), (lim[4], seen[:1]), (0.0, seen)):
            gap = candidates.constraint_gap(P, V, N, S, SA, SB, salive, len(SA), t, x, y, reach, buffer)
            assert gap == nearest if nearest <= reach / 2.0 else gap > reach / 2.0


def test_a_circumcentre_the_walks_cannot_reach_is_found_by_the_scan():
    """A hexagon with a reflex corner at (-1, -2), triangulated by hand (not Delaunay; the rules do not need it):
    the circumcentre (0, -4) of the first triangle is seen from its centroid along x = 0, through its apex (0, 1),
    a degenerate walk; locate's walk towards it steps over the boundary edge (-3, 0)-(-1, -2) of the second
    triangle, out of the region, and the scan finds it, when it is listed and when it surfaces (the first point)."""
    P = np.array([(0.0, 1.0), (-3.0, 0.0), (-1.0, -2.0), (-1.0, -6.0), (3.0, -6.0), (3.0, 0.0)])
    V = np.array([[1, 5, 0], [5, 1, 2], [5, 2, 3], [5, 3, 4]], dtype=np.int64)
    SA = np.arange(6, dtype=np.int64)
    SB = (SA + 1) % 6
    N, S, _ = adjacency(V, SA, SB, len(P))
    assert walk(P, V, N, S, 0, 0.0, 1.0 / 3.0, 0.0, -4.0, len(V) + 1) == (-1, -1)
    _assert_candidates(P, V, SA, SB, 4.0)
    status, points, _, _, values = fast.insert_all(P, V, np.column_stack([SA, SB]), candidates.limits(4.0))
    assert status == fast.OK and points[len(P)].tolist() == [0.0, -4.0] and values[0] == 5.0


def test_candidates_after_a_short_constraint():
    """A triangle whose first edge is a constraint too short for a candidate and whose other two are long: their
    midpoints are candidates all the same."""
    P = np.array([(0.0, 0.0), (1.0, 0.0), (0.0, 6.0)])
    _assert_candidates(P, np.array([[0, 1, 2]]), np.array([0, 1, 2]), np.array([1, 2, 0]), 1.0)


@pytest.mark.parametrize("hole", [False, True])
def test_candidates_where_every_boundary_midpoint_counts(hole):
    """l = 0.45 on a ring of points 1 apart: the midpoint of every constraint edge is a candidate, whichever edge
    of its triangle it is."""
    _assert_candidates(*square_ring(6.0, 1.0, hole, [(0.5, 4.3), (5.2, 1.1), (3.1, 5.4), (2.5, 0.6)]), 0.45)


@pytest.mark.parametrize("hole", [False, True])
def test_gap_is_the_nearest_constraint_within_half_its_reach(hole):
    """From the triangle containing each point of a grid, for reaches from a fraction of a triangle to most of the
    region: the distance to the nearest constraint, exact whenever it is at most half the reach, else a number above
    half the reach."""
    P, V, SA, SB = square_ring(6.0, 1.0, hole, [(0.5, 4.3), (5.2, 1.1), (3.1, 5.4), (2.5, 0.6)])
    N, S, _ = adjacency(V, SA, SB, len(P))
    salive, seen = np.ones(len(SA), dtype=np.bool_), np.empty(len(V), dtype=np.int64)
    for x, y in [(0.25 + 0.7 * i, 0.15 + 0.7 * j) for i in range(9) for j in range(9)]:
        t = locate(P, V, N, np.ones(len(V), dtype=np.bool_), len(V), 0, x, y, len(V) + 1)
        if t < 0:
            continue
        nearest = min(_edge_distance((x, y), P[a], P[b]) for a, b in zip(SA, SB))
        for reach in (0.3, 1.0, 2.0, 6.0):
            gap = candidates.constraint_gap(P, V, N, S, SA, SB, salive, len(SA), t, x, y, reach, seen)
            assert gap == nearest if nearest <= reach / 2.0 else gap > reach / 2.0


def test_a_cavity_larger_than_its_buffer():
    """A regular 70-gon: its vertices are cocircular, so the first point (a circumcentre near the centre) has a
    cavity of more than ``CAVITY`` (64) triangles: the buffer must grow, and the mesh is Problem 1's."""
    vertices = regular_polygon(70, 1.5)
    ring = np.array([(i, (i + 1) % 70) for i in range(70)], dtype=np.int64)
    V = np.ascontiguousarray(constrained_delaunay(vertices, ring, np.empty((0, 2))), dtype=np.int64)
    N, S, _ = adjacency(V, ring[:, 0].copy(), ring[:, 1].copy(), 70)
    point, _, _ = reference.best_candidate(vertices, V, ring, 1.0)
    start = locate(vertices, V, N, np.ones(len(V), dtype=np.bool_), len(V), 0, *point, len(V) + 1)
    mark = np.zeros(len(V), dtype=np.int64)
    assert cavity(vertices, V, N, S, start, *point, mark, 1, np.empty(fast.CAVITY, dtype=np.int64)) == -1
    assert cavity(vertices, V, N, S, start, *point, mark, 2, np.empty(len(V), dtype=np.int64)) > fast.CAVITY
    assert_problem1_invariants(equimesh.increment(vertices, 1.0, engine="fast"), vertices, 1.0)


@pytest.mark.parametrize(
    "runs, args",
    [
        (problem1_runs, ([(0.0, 0.0), (10.6, 0.8), (12.2, 7.4), (4.4, 11.8), (-1.6, 6.2)], 0.7)),
        (problem2_runs, ([(0.0, 0.0), (14.2, 0.6), (14.8, 6.4), (6.6, 7.2), (6.2, 14.6), (-0.4, 14.0)], 0.7, 17.0)),
    ],
    ids=["problem1", "problem2"],
)
def test_the_engine_is_the_reference_on_two_fixed_polygons(runs, args):
    """The whole engine on a convex pentagon (Problem 1) and an L (Problem 2, lattice at 17 degrees), no four
    cocircular points: the reference's points, values and triangles bit for bit (``tests/planar/test_engines.py`` does
    this on generated polygons, compiled)."""
    assert_same_insertion(runs(np.array(args[0]), *args[1:]))


def test_integer_points_and_float_indices_are_converted():
    """A region given by integer coordinates and float segment indices: the same insertion as from floats and ints."""
    corners = [[0, 0], [20, 1], [19, 4], [0, 3]]
    loose = Region(corners, [[0.0, 1.0], [1.0, 2.0], [2.0, 3.0], [3.0, 0.0]], np.empty((0, 2)))
    exact = Region(np.array(corners, dtype=float), np.array([[0, 1], [1, 2], [2, 3], [3, 0]]), np.empty((0, 2)))
    a, b = fast.run(loose, 0.6), fast.run(exact, 0.6)
    assert a.points.tobytes() == b.points.tobytes() and a.segments.tolist() == b.segments.tolist()


#: A quadrilateral of four long constraints.
_QUADRILATERAL = [(0.0, 0.0), (20.3, 0.7), (19.6, 4.1), (0.4, 3.3)]


#: A notched heptagon (found by a search): the walk of a circumcentre from its triangle's centroid runs through a
#: vertex both when it is pushed and when it surfaces, so both times the brute-force test decides.
_THROUGH_A_VERTEX = [(0.0, 1.0), (-3.0, 0.0), (-5.2, -4.2), (-4.5, -11.3), (-0.3, -3.8), (3.2, -3.8), (3.0, 0.0)]


@pytest.mark.parametrize(
    "corners, l",
    [(_QUADRILATERAL, 0.6), (_QUADRILATERAL, 30.0), (_THROUGH_A_VERTEX, 2.0)],
    ids=["quadrilateral", "quadrilateral-nothing", "walk-through-a-vertex"],
)
def test_the_corners_alone_give_the_reference_insertion(corners, l):
    """Only the corners: every point comes from splitting the long constraints or from circumcentres, and the heap
    is compacted while midpoints are in it; with l = 30 nothing is inserted in the quadrilateral (two triangles).
    The reference's insertion bit for bit."""
    region = Region(
        np.array(corners), np.array([[i, (i + 1) % len(corners)] for i in range(len(corners))]), np.empty((0, 2))
    )
    a, b = fast.run(region, l), reference.run(region, l)
    assert a.points.tobytes() == b.points.tobytes() and a.values.tobytes() == b.values.tobytes()
    assert a.segments.dtype == b.segments.dtype == np.int64 and a.segments.tolist() == b.segments.tolist()
    assert sorted(map(sorted, a.triangles.tolist())) == sorted(map(sorted, b.triangles.tolist()))


def test_the_triangles_come_out_in_slot_order_the_cavitys_slots_first():
    """A 2 x 2 square (triangles 3 0 1 and 1 2 3) with l = 1.4: only its centre is inserted, on the diagonal, and its
    cavity is both triangles.  Its fan of four takes their slots 1 and 0 (the last freed first) and then new
    slots 2 and 3, and the triangles come out in slot order: fixed, so the same input gives the same arrays."""
    square = np.array([(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)])
    region = Region(square, np.array([[0, 1], [1, 2], [2, 3], [3, 0]]), np.empty((0, 2)))
    assert constrained_delaunay(square, region.segments, region.holes).tolist() == [[3, 0, 1], [1, 2, 3]]
    assert fast.run(region, 1.4).triangles.tolist() == [[0, 1, 4], [3, 0, 4], [1, 2, 4], [2, 3, 4]]


def test_a_broken_cavity_is_an_internal_error(monkeypatch):
    """When the compiled loop reports a cavity it could not re-triangulate (a bug), run raises InternalError, never
    returns the mesh."""
    monkeypatch.setattr(fast, "insert_all", lambda P0, T0, SEG0, *_: (fast.BROKEN, P0, T0, SEG0, np.empty(0)))
    with pytest.raises(InternalError) as caught:
        fast.run(Region(rectangle(2.0, 2.0), np.array([[0, 1], [1, 2], [2, 3], [3, 0]]), np.empty((0, 2))), 1.0)
    assert str(caught.value) == "fast engine: a Bowyer-Watson cavity did not re-triangulate (broken triangulation)"


def test_fast_engine_refuses_an_interior_constraint():
    """A constraint with triangles on both sides is outside the fast engine's contract: a clear error."""
    square = rectangle(2.0, 2.0)
    region = Region(square, np.array([[0, 1], [1, 2], [2, 3], [3, 0], [0, 2]]), np.empty((0, 2)))
    with pytest.raises(EquimeshError, match="segment 4 is an edge of zero or two triangles"):
        insert(region, 1.0, engine="fast")


def _l_at(value, factor):
    """The l for which ``factor * l`` is ``value`` exactly."""
    l = value / factor
    for _ in range(64):
        if factor * l == value:
            return float(l)
        l = np.nextafter(l, np.inf if factor * l < value else -np.inf)
    raise AssertionError(f"no l with {factor!r} * l == {value!r}")


def _thresholds():
    """(points, l) of the reference engine's threshold tests (``tests/planar/insertion/test_reference.py``), and a
    radius
    at (1 - REL_TOL) l and at (1 + REL_TOL) l (this one within SLIVER_GAP l of a constraint) and a constraint of
    half-length (1 - REL_TOL) l, each exactly."""
    cases = [(circle_triangle(gap, radius)[0], 1.0) for gap, radius, _ in NEAR_CONSTRAINT]
    cases += [(circle_triangle(0.5, 1.5)[0], 1.5 / factor) for factor in (1.0 - 0.5 * REL_TOL, 1.0 - 2.0 * REL_TOL)]
    for tol, radius in [(REL_TOL, 3.0), (SLIVER_GAP, 1.0)]:
        points, _, l = at_exactly(tol, radius)
        cases += [(points, l), (points, np.nextafter(l, 0.0) * (1.0 - 4.0 * REL_TOL))]
    for gap, radius, factor in [(0.5, 1.5, 1.0 - REL_TOL), (0.5 * SLIVER_GAP, 1.0, 1.0 + REL_TOL)]:
        points = circle_triangle(gap, radius)[0]
        cases.append((points, _l_at(candidates.circumcircle(points, 0, 1, 2)[2], factor)))
    cases.append((np.array([[-1.0, 0.0], [1.0, 0.0], [0.0, 5.0]]), _l_at(1.0, 1.0 - REL_TOL)))
    return cases


def test_every_limit_is_a_multiple_of_l():
    """Scaling l by a power of two scales every threshold and the search reach by it exactly, the squared floor of
    the circumradii by its square."""
    for k in (-7, 1, 30):
        scaled = candidates.limits(math.ldexp(1.3, k)).tolist()
        assert scaled == [math.ldexp(x, k) for x in candidates.limits(1.3)[:5]] + [
            math.ldexp(candidates.limits(1.3)[5], 2 * k)
        ]


@pytest.mark.parametrize("points, l", _thresholds())
def test_candidates_at_the_thresholds_of_the_rules(points, l):
    """One triangle bounded by its three constraints at each threshold of the rules: the reference's candidates
    (:func:`_assert_candidates`)."""
    _assert_candidates(points, np.array([[0, 1, 2]]), np.array([0, 1, 2]), np.array([1, 2, 0]), l)


@pytest.mark.parametrize("points, l", _thresholds())
def test_the_candidate_rules_at_their_thresholds_are_the_reference(points, l):
    """One triangle bounded by its three constraints, its circumcentre placed at each threshold of the rules
    (radius (1 - REL_TOL) l, gap REL_TOL l and SLIVER_GAP l, value l up to REL_TOL), l far from 1 included:
    the fast engine inserts what the reference engine inserts, bit for bit."""
    region = Region(points, np.array([[0, 1], [1, 2], [2, 0]]), np.empty((0, 2)))
    a, b = fast.run(region, l), reference.run(region, l)
    assert a.points.tobytes() == b.points.tobytes() and a.values.tobytes() == b.values.tobytes()


def test_a_circumcentre_refused_when_it_surfaces_is_skipped_and_the_insertion_goes_on():
    """A circumcentre accepted when pushed and refused when it surfaces: its triangle is passed over, the rest is
    inserted.  A pentagon a, b, e, x, w, in a frame along ab (6 long, turned by 0.7 rad and moved by (0.1, 0)):
    the circle of t = (a, x, w) has radius 1 about the point 1 along ab and 7e-10 off it, and l (0.7 up to 1e-7)
    is the float just below the one for which REL_TOL l is the centre's gap to ab.  Pushed, the centre is accepted (gap
    over
    REL_TOL l, radius over l); ab's midpoint (2 from it, outside the circle: t stays) is inserted before it
    surfaces, and rounded it moves the constraint's half (a, p) 8.5e-17 nearer the centre, now within REL_TOL l:
    refused, and five more points follow (the reference's insertion, 13 points)."""
    turn = np.array([[math.cos(0.7), -math.sin(0.7)], [math.sin(0.7), math.cos(0.7)]])
    centre, radius = np.array([1.0, 7e-10]), math.hypot(1.0, 7e-10)
    frame = [
        (0.0, 0.0),
        (6.0, 0.0),
        (6.0, 1.5),
        tuple(centre + radius * np.array([0.8, 0.6])),
        tuple(centre + radius * np.array([-0.6, 0.8])),
    ]
    points = np.array([turn @ np.array(p) + (0.1, 0.0) for p in frame])
    cx, cy, _, _, _ = candidates.circumcircle(points, 0, 3, 4)
    a, b = points[0], points[1]
    p = 0.5 * (a + b)
    before = _edge_distance((cx, cy), a, b)
    after = min(_edge_distance((cx, cy), a, p), _edge_distance((cx, cy), p, b))
    l = np.nextafter(_l_at(before, REL_TOL), 0.0)
    assert after <= REL_TOL * l < before and abs(l - 0.7) < 1e-6
    region = Region(points, np.array([[i, (i + 1) % 5] for i in range(5)]), np.empty((0, 2)))
    assert [0, 3, 4] in map(sorted, constrained_delaunay(points, region.segments, region.holes).tolist())
    got, expected = fast.run(region, l), reference.run(region, l)
    assert got.points.tobytes() == expected.points.tobytes() and got.values.tobytes() == expected.values.tobytes()
    assert len(got.points) == 13 and [cx, cy] not in got.points.tolist()


@pytest.mark.parametrize(
    "module, call",
    [
        (equimesh.planar.increment, lambda: equimesh.increment(regular_polygon(7, 6.0), 0.8)),
        (
            equimesh.planar.strip,
            lambda: equimesh.uniform_triangulation(
                [(0.0, 0.0), (14.2, 0.6), (14.8, 6.4), (6.6, 7.2), (6.2, 14.6), (-0.4, 14.0)], 0.7, angle=17.0
            ),
        ),
    ],
)
def test_growing_from_no_room_changes_nothing(monkeypatch, module, call):
    """Arrays made for the expected points, or grown by doubling from the input alone (every array short of room in
    turn), also from cavity buffers of one triangle: the same points, triangles, segments and values, bit for bit,
    for Problems 1 and 2."""
    regions = []
    monkeypatch.setattr(module, "insert", lambda region, l, engine: regions.append((region, l)) or insert(region, l))
    call()
    region, l = regions[0]
    points = np.array(region.points, dtype=float).reshape(-1, 2)
    segments = np.array(region.segments, dtype=np.int64).reshape(-1, 2)
    triangles = np.ascontiguousarray(constrained_delaunay(points, segments, region.holes), dtype=np.int64)
    expected = fast.expected_points(points, segments, triangles, l)
    ahead = fast.insert_all(points, triangles, segments, candidates.limits(l), expected)
    assert ahead[0] == fast.OK and len(ahead[1]) > len(points) + 1  # the points grew
    for grown in (
        fast.insert_all(points, triangles, segments, candidates.limits(l)),
        fast.insert_all(points, triangles, segments, candidates.limits(l), 0, 1),
    ):
        assert grown[0] == fast.OK
        for a, b in zip(ahead[1:], grown[1:]):
            assert a.dtype == b.dtype and np.array_equal(a, b)


#: Regions of a few corners, so that the triangles of one cavity outnumber those of the input: a thin quadrilateral
#: of long constraints, a convex pentagon and a square (candidates of equal value by the hundred: a bucket larger
#: than the heap).
_FEW_CORNERS = [
    (_QUADRILATERAL, 0.6),
    ([(0.0, 0.0), (10.6, 0.8), (12.2, 7.4), (4.4, 11.8), (-1.6, 6.2)], 0.7),
    ([(0.0, 0.0), (6.0, 0.0), (6.0, 6.0), (0.0, 6.0)], 0.5),
]


@pytest.mark.parametrize("corners, l", _FEW_CORNERS, ids=["quadrilateral", "pentagon", "square"])
def test_growing_every_array_from_one_triangle_changes_nothing(corners, l):
    """From no expected points and cavity buffers (and heap room beyond the input's candidates) of 1, 2 or 3
    triangles the arrays grow, the points, segments, triangles and the buckets' chunks several times each, the heap
    after compaction (and in the square when a bucket comes in), the cavity buffer and, but in the square, the fan's:
    the insertion of arrays made at once for all, bit for bit, and the reference's points and values."""
    points = np.array(corners)
    segments = np.array([[i, (i + 1) % len(corners)] for i in range(len(corners))])
    triangles = np.ascontiguousarray(constrained_delaunay(points, segments, np.empty((0, 2))), dtype=np.int64)
    lim = candidates.limits(l)
    ahead = fast.insert_all(points, triangles, segments, lim, 4 * fast.expected_points(points, segments, triangles, l))
    assert ahead[0] == fast.OK
    for room in (1, 2, 3):
        grown = fast.insert_all(points, triangles, segments, lim, 0, room)
        assert grown[0] == fast.OK
        for a, b in zip(ahead[1:], grown[1:]):
            assert a.dtype == b.dtype and np.array_equal(a, b)
    expected = reference.run(Region(points, segments, np.empty((0, 2))), l)
    assert ahead[1].tobytes() == expected.points.tobytes() and ahead[4].tobytes() == expected.values.tobytes()


def test_values_in_the_octave_below_l_come_last():
    """l = 1, so the values pushed, from (1 - REL_TOL) l on, start in the octave below 1: an equilateral triangle of
    circumradius 1 - 5e-10 (its circumcentre such a value) beside a long one with larger candidates.  The
    reference's insertion bit for bit, that circumcentre among its points."""
    r = 1.0 - 5e-10
    a, b, c = [(r * math.cos(t), r * math.sin(t)) for t in (math.pi / 2, 7 * math.pi / 6, 11 * math.pi / 6)]
    region = Region(np.array([b, c, (4.0, 0.3), a]), np.array([[0, 1], [1, 2], [2, 3], [3, 0]]), np.empty((0, 2)))
    assert candidates.limits(1.0)[0] < 1.0 <= candidates.limits(1.0)[1]
    got, expected = fast.run(region, 1.0), reference.run(region, 1.0)
    assert got.points.tobytes() == expected.points.tobytes() and got.values.tobytes() == expected.values.tobytes()
    assert min(got.values) < 1.0


def test_a_clockwise_triangle_is_a_broken_cavity():
    """A 2 x 2 square whose first triangle is listed clockwise: the fan over the cavity of the centre is not
    counter-clockwise, and insert_all reports BROKEN with the input arrays."""
    square = np.array([(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)])
    segments = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])
    triangles = np.array([[3, 1, 0], [1, 2, 3]])
    status, points, out, out_segments, _ = fast.insert_all(square, triangles, segments, candidates.limits(1.4))
    assert status == fast.BROKEN and points is square and out is triangles and out_segments is segments


def test_the_arrays_are_made_for_olers_bound():
    """expected_points is node_estimate of the region's area (the triangles' areas, an L of area 3 whichever way
    its triangles turn) and perimeter (8), and at most half the slots the tags can name."""
    corners = np.array([(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0), (1.0, 2.0), (0.0, 2.0)])
    segments = np.array([[i, (i + 1) % 6] for i in range(6)])
    triangles = np.array([[0, 1, 2], [0, 3, 2], [0, 3, 4], [0, 4, 5]])
    for l in (0.3, 1.0):
        assert fast.expected_points(corners, segments, triangles, l) == int(node_estimate(3.0, 8.0, l))
    assert fast.expected_points(corners, segments, triangles, 1e-4) == MAX_SLOTS // 2


def test_a_region_beyond_the_tags_is_refused(monkeypatch):
    """When the triangulation would outgrow the heap's tags, run raises MeshTooLargeError naming the limits."""
    monkeypatch.setattr(fast, "insert_all", lambda P0, T0, SEG0, *_: (fast.TOO_LARGE, P0, T0, SEG0, np.empty(0)))
    with pytest.raises(equimesh.errors.MeshTooLargeError) as caught:
        fast.run(Region(rectangle(2.0, 2.0), np.array([[0, 1], [1, 2], [2, 3], [3, 0]]), np.empty((0, 2))), 1.0)
    assert str(caught.value) == (
        "the fast engine holds at most 268435456 points and 536870912 triangles, and this region needs more; "
        "use a larger l"
    )
