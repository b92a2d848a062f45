"""The fast engine's constrained Delaunay kernels (``planar/insertion/cdt.py``), each against a brute-force definition.

What must hold: the adjacency links twin half-edges and marks the constraints; a walk decides visibility as
the brute-force segment test does, or says it cannot (-1), at any scale; ``locate`` gives the lowest live slot
containing a point, from any start; Bowyer-Watson insertion keeps the triangulation constrained Delaunay, a
cavity never crosses a constraint and ``fill`` refuses a fan that is not counter-clockwise; the touch test is
the reference's.  Small inputs, so that the kernels also run as Python (``NUMBA_DISABLE_JIT=1``, as mutation
testing runs them).
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from insertion_cases import contains, exact_incircle, square_ring, square_rings

from equimesh._geometry import segments_intersect
from equimesh.planar.insertion.cdt import adjacency, cavity, cavity_boundary, fill, locate, segments_touch, walk
from equimesh.planar.insertion.predicates import orient2d
from equimesh.planar.insertion.region import constrained_delaunay


def test_cavity_boundary_fills_its_buffer_exactly():
    """A cavity of k triangles has k + 2 boundary edges: a buffer of exactly that length suffices.

    Regression: an interior edge visited after the last boundary edge was
    refused as "buffer full", and a cavity of 64 triangles (the initial
    buffer) broke the run (random convex polygons of ~6,800 l^2).
    """
    V = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int64)
    N = np.array([[-1, -1, 1], [0, -1, -1]], dtype=np.int64)
    S = np.full((2, 3), -1, dtype=np.int64)
    mark = np.ones(2, dtype=np.int64)
    edges = np.empty((4, 4), dtype=np.int64)
    # Triangle 1 first, so the last edge visited (2, 0) of triangle 0 is interior.
    assert cavity_boundary(V, N, S, np.array([1, 0]), 2, -1, mark, 1, edges) == 4
    assert {tuple(e[:2]) for e in edges.tolist()} == {(2, 3), (3, 0), (0, 1), (1, 2)}


@given(st.integers(3, 7), st.integers(3, 7), st.data())
def test_local_locate_gives_the_lowest_slot_like_the_scan(nx, ny, data):
    """The local walk of :func:`_cdt.locate` answers what scanning every slot answers.

    On a lattice (cocircular everywhere) and for query points at vertices,
    edge midpoints and inside triangles; ``max_steps=0`` forces the scan.
    """
    xy = np.array([[x, y] for y in range(ny) for x in range(nx)], dtype=float)
    ring = [i for i in range(nx)] + [i * nx + nx - 1 for i in range(1, ny)]
    ring += [(ny - 1) * nx + i for i in range(nx - 2, -1, -1)] + [i * nx for i in range(ny - 2, 0, -1)]
    segments = np.array([[ring[i], ring[(i + 1) % len(ring)]] for i in range(len(ring))], dtype=np.int64)
    V = constrained_delaunay(xy, segments, np.empty((0, 2)))
    N, _, _ = adjacency(V, segments[:, 0].copy(), segments[:, 1].copy(), len(xy))
    alive = np.ones(len(V), dtype=np.bool_)
    t = data.draw(st.integers(0, len(V) - 1))
    weights = np.array(data.draw(st.sampled_from([(1, 0, 0), (1, 1, 0), (0, 1, 1), (1, 1, 1), (2, 1, 1)])), dtype=float)
    x, y = (weights @ xy[V[data.draw(st.integers(0, len(V) - 1))]]) / weights.sum()
    scan = locate(xy, V, N, alive, len(V), t, x, y, 0)
    assert scan >= 0
    assert locate(xy, V, N, alive, len(V), t, x, y, len(V) + 1) == scan


small_grid = st.tuples(st.integers(-3, 3), st.integers(-3, 3)).map(lambda p: (p[0] / 2.0, p[1] / 2.0))


@given(st.lists(small_grid, min_size=4, max_size=4))
def test_segments_touch_is_the_reference(quad):
    """On grid points (collinear, overlapping, touching at an end, disjoint): the answer of segments_intersect."""
    p, q, a, b = (np.array(v) for v in quad)
    assert segments_touch(*p, *q, *a, *b) == bool(segments_intersect(p, q, a, b))


@pytest.mark.parametrize("end", range(4))
def test_segments_touch_where_one_end_lies_on_the_other_segment(end):
    """A T: one end inside the other segment, the other three ends off both lines; each of the four ends in turn."""

    def ends(stem, bar):
        return [stem + bar, stem[::-1] + bar, bar + stem, bar + stem[::-1]][end]

    bar = [(0.0, 0.0), (3.0, 0.0)]
    assert segments_touch(*(c for point in ends([(1.0, 0.0), (1.0, 2.0)], bar) for c in point))  # (1, 0) on the bar
    assert not segments_touch(*(c for point in ends([(1.0, 0.5), (1.0, 2.0)], bar) for c in point))


def _half_edges(V):
    return {(int(V[t, e]), int(V[t, (e + 1) % 3])): (t, e) for t in range(len(V)) for e in range(3)}


@given(square_rings())
def test_adjacency_links_twin_edges_and_constraints(ring):
    P, V, SA, SB = ring
    N, S, count = adjacency(V, SA, SB, len(P))
    half = _half_edges(V)
    seg = {(int(a), int(b)): s for s, (a, b) in enumerate(zip(SA, SB))}
    for (u, v), (t, e) in half.items():
        assert N[t, e] == half.get((v, u), (-1,))[0]
        assert S[t, e] == seg.get((u, v), seg.get((v, u), -1))
    assert count.tolist() == [1] * len(SA)  # each constraint bounds the region
    # A pair that is no edge is counted 0 times; an edge inside the region, twice.
    t = next(t for t in range(len(V)) if all(N[t] >= 0))
    _, _, inner = adjacency(
        V,
        np.array([V[t, 0], 0]),
        np.array([V[t, 1], len(P) - 1 if (0, len(P) - 1) not in half and (len(P) - 1, 0) not in half else 0]),
        len(P),
    )
    assert inner[0] == 2


def _touches_a_constraint(g, c, P, SA, SB):
    return any(bool(segments_intersect(np.array(g), np.array(c), P[a], P[b])) for a, b in zip(SA, SB))


@given(square_rings(), st.data())
def test_walk_decides_visibility_like_the_brute_force_test(ring, data):
    """Status 1: gc touches no constraint and c is in the triangle returned; 0: it touches one; -1 only when
    degenerate."""
    P, V, SA, SB = ring
    N, S, _ = adjacency(V, SA, SB, len(P))
    t = data.draw(st.integers(0, len(V) - 1))
    g = tuple(P[V[t]].sum(axis=0) / 3.0)
    c = data.draw(
        st.one_of(
            st.tuples(st.floats(-1.0, 7.0), st.floats(-1.0, 7.0)),
            st.tuples(st.integers(-2, 14), st.integers(-2, 14)).map(lambda p: (p[0] / 2.0, p[1] / 2.0)),
        )
    )
    status, where = walk(P, V, N, S, t, *g, *c, len(V) + 1)
    degenerate = any(orient2d(*g, *c, *p) == 0.0 for p in P)
    assert status >= 0 or degenerate
    if status >= 0:
        assert status == (0 if _touches_a_constraint(g, c, P, SA, SB) else 1)
    if status == 1:
        assert contains(P, V, where, *c)
    # A start point on an edge of t is degenerate.
    assert walk(P, V, N, S, t, *P[V[t, 0]], *c, len(V) + 1) == (-1, -1)


def test_walk_through_a_vertex_is_degenerate_and_a_constraint_end_is_touching():
    """On an 18 x 18 ring of points 3 apart (every centroid g an integer point): c on a vertex of g's triangle,
    or past it, or opposite it on the line through g and the vertex, is degenerate (-1); c inside a constraint
    edge of g's triangle touches it (0), constraint 0 included."""
    P, V, SA, SB = square_ring(18.0, 3.0, hole=True)
    N, S, _ = adjacency(V, SA, SB, len(P))
    for t in range(len(V)):
        g = P[V[t]].sum(axis=0) / 3.0
        for e in range(3):
            v = P[V[t, e]]
            for c in (v, 2.0 * v - g, 2.0 * g - v, 4.0 * g - 3.0 * v):
                if not (contains(P, V, t, *c) and tuple(c) != tuple(v)):
                    assert walk(P, V, N, S, t, *g, *c, len(V) + 1) == (-1, -1)
            if S[t, e] >= 0:
                middle = (v + P[V[t, (e + 1) % 3]]) / 2.0
                assert walk(P, V, N, S, t, *g, *middle, len(V) + 1) == (0, t)
    assert 0 in S


def test_walk_is_the_same_at_any_scale():
    """Scaled by 2^-20 (exactly: every orientation by 2^-40, far below 1), every walk from every triangle to the
    points of a grid gives the same answer (the signs decide, never a magnitude)."""
    P, V, SA, SB = square_ring(6.0, 1.0, True, [(0.5, 4.3), (5.2, 1.1), (3.1, 5.4)])
    N, S, _ = adjacency(V, SA, SB, len(P))
    scale = 2.0**-20
    for t in range(len(V)):
        g = tuple(P[V[t]].sum(axis=0) / 3.0)
        for c in [(x + 0.3, y + 0.1) for x in range(-1, 7, 3) for y in range(-1, 7, 3)]:
            expected = walk(P, V, N, S, t, *g, *c, len(V) + 1)
            assert walk(P * scale, V, N, S, t, *(np.array(g) * scale), *(np.array(c) * scale), len(V) + 1) == expected


@given(square_rings(), st.data())
def test_locate_gives_the_lowest_live_slot_containing_the_point(ring, data):
    P, V, SA, SB = ring
    N, _, _ = adjacency(V, SA, SB, len(P))
    alive = np.ones(len(V), dtype=np.bool_)
    x, y = data.draw(
        st.one_of(st.sampled_from([tuple(p) for p in P]), st.tuples(st.floats(0.0, 6.0), st.floats(0.0, 6.0)))
    )
    containing = [t for t in range(len(V)) if contains(P, V, t, x, y)]
    start = data.draw(st.integers(0, len(V) - 1))
    for steps in (0, len(V) + 1):
        assert locate(P, V, N, alive, len(V), start, x, y, steps) == (containing[0] if containing else -1)
    alive[containing[:1]] = False
    assert locate(P, V, N, alive, len(V), start, x, y, 0) == (containing[1] if len(containing) > 1 else -1)


def test_locate_from_every_triangle_to_every_vertex_edge_and_centroid():
    """On a lattice (cocircular everywhere), every start, every query at a vertex, an edge midpoint or a centroid:
    the lowest slot whose closed triangle contains the query, as the scan finds it."""
    xy = np.array([[x, y] for y in range(4) for x in range(4)], dtype=float)
    ring = [0, 1, 2, 3, 7, 11, 15, 14, 13, 12, 8, 4]
    segments = np.array([[ring[i], ring[(i + 1) % 12]] for i in range(12)], dtype=np.int64)
    V = np.ascontiguousarray(constrained_delaunay(xy, segments, np.empty((0, 2))), dtype=np.int64)
    N, _, _ = adjacency(V, segments[:, 0].copy(), segments[:, 1].copy(), len(xy))
    alive = np.ones(len(V), dtype=np.bool_)
    queries = [tuple(p) for p in xy] + [tuple(xy[V[t]].mean(axis=0)) for t in range(len(V))]
    queries += [tuple((xy[V[t, e]] + xy[V[t, (e + 1) % 3]]) / 2.0) for t in range(len(V)) for e in range(3)]
    for x, y in queries:
        lowest = next(t for t in range(len(V)) if contains(xy, V, t, x, y))
        assert all(locate(xy, V, N, alive, len(V), start, x, y, len(V) + 1) == lowest for start in range(len(V)))


def _brute_cavity(P, V, N, S, start, p):
    """Triangles reachable from ``start`` across non-constraint edges whose circumcircle strictly contains ``p``."""
    cav, todo = {start}, [start]
    while todo:
        t = todo.pop()
        for e in range(3):
            n = N[t, e]
            if S[t, e] < 0 and n >= 0 and n not in cav and exact_incircle(*P[V[n]], p)[0] > 0:
                cav.add(n)
                todo.append(n)
    return cav


@given(square_rings(), st.tuples(st.floats(0.05, 5.95), st.floats(0.05, 5.95)))
def test_insertion_by_bowyer_watson_keeps_a_delaunay_triangulation(ring, p):
    """cavity = the brute-force cavity; its boundary has k + 2 edges; the fan refills it: ccw, linked, locally
    Delaunay."""
    P, V, SA, SB = ring
    N, S, _ = adjacency(V, SA, SB, len(P))
    start = locate(P, V, N, np.ones(len(V), dtype=np.bool_), len(V), 0, *p, len(V) + 1)
    if start < 0 or min(math.dist(p, q) for q in P) < 1e-3 or _touches_a_constraint(p, p, P, SA, SB):
        return  # in the hole, on a point or on a constraint (the engine splits those: cavity_boundary's split)
    mark = np.zeros(len(V), dtype=np.int64)
    assert cavity(P, V, N, S, start, *p, mark, 1, np.empty(1, dtype=np.int64)) in (1, -1)
    cav = np.empty(len(V), dtype=np.int64)
    k = cavity(P, V, N, S, start, *p, mark, 2, cav)
    assert set(cav[:k].tolist()) == _brute_cavity(P, V, N, S, start, p) == set(np.flatnonzero(mark == 2).tolist())
    edges = np.empty((k + 2, 4), dtype=np.int64)
    m = cavity_boundary(V, N, S, cav, k, -1, mark, 2, edges)
    assert m == k + 2
    assert cavity_boundary(V, N, S, cav, k, -1, mark, 2, edges[: k + 1]) == -1
    P2 = np.vstack([P, [p]])
    V2, N2, S2 = (np.vstack([a, np.zeros((2, 3), dtype=np.int64)]) for a in (V, N, S))
    slots = np.concatenate([cav[:k], [len(V), len(V) + 1]])
    vfan, vstamp = np.zeros(len(P2), dtype=np.int64), np.zeros(len(P2), dtype=np.int64)
    assert fill(P2, V2, N2, S2, edges, m, len(P), slots, vfan, vstamp, 1)
    half = _half_edges(V2)
    for t in range(len(V2)):
        a, b, c = P2[V2[t]]
        assert orient2d(*a, *b, *c) > 0.0
        for e in range(3):
            u, v = int(V2[t, e]), int(V2[t, (e + 1) % 3])
            assert N2[t, e] == half.get((v, u), (-1,))[0]
            if N2[t, e] >= 0 and S2[t, e] < 0:
                assert exact_incircle(a, b, c, P2[V2[N2[t, e], (half[(v, u)][1] + 2) % 3]])[0] <= 0


@pytest.mark.parametrize("segment", [0, 7])
def test_cavity_boundary_refuses_a_constraint_inside_the_cavity_and_skips_the_split_segment(segment):
    """Two triangles sharing the constraint 2-0: both in the cavity is a broken cavity, unless 2-0 is the split
    segment (numbered 0, the first, or 7)."""
    V = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int64)
    N = np.array([[-1, -1, 1], [0, -1, -1]], dtype=np.int64)
    S = np.array([[-1, -1, segment], [segment, -1, -1]], dtype=np.int64)
    mark = np.ones(2, dtype=np.int64)
    edges = np.empty((4, 4), dtype=np.int64)
    assert cavity_boundary(V, N, S, np.array([0, 1]), 2, -1, mark, 1, edges) == -1
    assert cavity_boundary(V, N, S, np.array([0, 1]), 2, segment, mark, 1, edges) == 4
    assert sorted(map(tuple, edges.tolist())) == [(0, 1, -1, -1), (1, 2, -1, -1), (2, 3, -1, -1), (3, 0, -1, -1)]
    # Only triangle 0 in the cavity: its edges, the one across 2-0 with its neighbour and segment.
    mark = np.array([1, 0])
    assert cavity_boundary(V, N, S, np.array([0]), 1, -1, mark, 1, edges) == 3
    assert edges[:3].tolist() == [[0, 1, -1, -1], [1, 2, -1, -1], [2, 0, 1, segment]]


def test_a_point_on_a_neighbours_circumcircle_stays_out_of_the_cavity():
    """p = (0, 5) inside the triangle (-4, 3), (4, 3), (0, 10) lies on the circle of radius 5 about the origin,
    the circumcircle of its neighbour (4, 3), (-4, 3), (0, -5): not strictly inside, so the neighbour stays out;
    one ulp lower it is inside, and the neighbour joins."""
    P = np.array([[-4.0, 3.0], [4.0, 3.0], [0.0, 10.0], [0.0, -5.0]])
    V = np.array([[0, 1, 2], [1, 0, 3]], dtype=np.int64)
    N, S, _ = adjacency(V, np.array([1, 2, 0, 3]), np.array([2, 0, 3, 1]), len(P))
    mark, cav = np.zeros(2, dtype=np.int64), np.empty(2, dtype=np.int64)
    assert cavity(P, V, N, S, 0, 0.0, 5.0, mark, 1, cav) == 1
    assert cavity(P, V, N, S, 0, 0.0, np.nextafter(5.0, 0.0), mark, 2, cav) == 2 and cav.tolist() == [0, 1]


def test_fill_refuses_a_fan_that_is_not_counter_clockwise():
    """A boundary edge seen from the wrong side (p outside the star) or a repeated boundary vertex: False."""
    P = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.3, 0.3], [2.0, 2.0]])
    edges = np.array([[0, 1, -1, -1], [1, 2, -1, -1], [2, 0, -1, -1]], dtype=np.int64)
    args = (np.zeros((3, 3), dtype=np.int64), np.zeros((3, 3), dtype=np.int64), np.zeros((3, 3), dtype=np.int64))
    stamps = (np.zeros(5, dtype=np.int64), np.zeros(5, dtype=np.int64))
    assert fill(P, *args, edges, 3, 3, np.arange(3), *stamps, 1)
    assert not fill(P, *args, edges, 3, 4, np.arange(3), *stamps, 2)
    repeated = np.array([[0, 1, -1, -1], [1, 0, -1, -1], [0, 1, -1, -1]], dtype=np.int64)
    assert not fill(P, *args, repeated, 3, 3, np.arange(3), *stamps, 3)
