"""The fast engine's compiled kernels, each against its definition (exact arithmetic, the reference's geometry).

What must hold:

* the exact predicates: ``orient2d`` and ``incircle`` have the sign of the
  exact determinant, also on collinear and cocircular points, and their value
  is the determinant up to its floating-point error bound; the expansion
  arithmetic below them is exact (two_sum, two_product with Dekker's split,
  Grow-Expansion: nonoverlapping components in increasing magnitude, zeros
  eliminated);
* the circumcircle, the distance to a segment and the touch test are the
  reference's (``equimesh._geometry``) bit for bit;
* the heap pops its entries in the reference's order (largest value, then
  smallest x, then smallest y), compaction keeps exactly the live entries,
  and ``_room`` leaves room for the pushes to come;
* the CDT operations: a walk decides visibility as the brute-force test does,
  or says it cannot (-1), at any scale; Bowyer-Watson keeps the triangulation
  constrained Delaunay;
* each triangle's candidates are the reference's, also exactly at the
  thresholds of the rules, and the whole engine inserts the reference's
  points, its triangles in a fixed (slot) order.

Small inputs, so that the file runs in seconds with the kernels run as
Python (``NUMBA_DISABLE_JIT=1``, as mutation testing runs them:
``tools/mutation``).
"""

import math
from fractions import Fraction

import numpy as np
import pytest
import strategies
from hypothesis import given
from hypothesis import strategies as st
from invariants import assert_problem1_invariants
from test_engines import assert_same_insertion, problem1_runs, problem2_runs
from test_reference_engine import NEAR_CONSTRAINT, at_exactly, circle_triangle

import equimesh
from equimesh import EquimeshError
from equimesh._geometry import circumcenters, point_segment_distance, segments_intersect
from equimesh.errors import InternalError
from equimesh.planar.insertion import Region, fast, insert, reference
from equimesh.planar.insertion import predicates as pr
from equimesh.planar.insertion.cdt import adjacency, cavity, cavity_boundary, fill, locate, segments_touch, walk
from equimesh.planar.insertion.predicates import incircle, orient2d
from equimesh.planar.insertion.region import constrained_delaunay
from equimesh.testing.generators import rectangle, regular_polygon
from equimesh.tolerance import REL_TOL, SLIVER_GAP

EPS = 2.0**-53


def _sign(x):
    return int(x > 0) - int(x < 0)


def exact_orient(a, b, c):
    """``orient(a, b, c)`` in rational arithmetic and its permanent ``|ax - cx||by - cy| + |ay - cy||bx - cx|``."""
    (ax, ay), (bx, by), (cx, cy) = ((Fraction(x), Fraction(y)) for x, y in (a, b, c))
    left, right = (ax - cx) * (by - cy), (ay - cy) * (bx - cx)
    return left - right, abs(left) + abs(right)


def exact_incircle(a, b, c, d):
    """The in-circle determinant of ``abcd`` in rational arithmetic and its permanent."""
    dx, dy = Fraction(d[0]), Fraction(d[1])
    (ax, ay), (bx, by), (cx, cy) = rows = [(Fraction(p[0]) - dx, Fraction(p[1]) - dy) for p in (a, b, c)]
    la, lb, lc = (x * x + y * y for x, y in rows)
    det = la * (bx * cy - by * cx) + lb * (cx * ay - cy * ax) + lc * (ax * by - ay * bx)
    permanent = (
        la * (abs(bx * cy) + abs(by * cx)) + lb * (abs(cx * ay) + abs(cy * ax)) + lc * (abs(ax * by) + abs(ay * bx))
    )
    return det, permanent


coordinates = strategies.frame_coordinates
points = st.tuples(coordinates, coordinates)


@st.composite
def lattice_quadruples(draw):
    """Four points of a scaled, shifted integer or triangular lattice (many collinear and cocircular)."""
    h = draw(st.sampled_from([1.0, 0.1, 1.7, 2.0**-10]))
    shift = np.array([draw(coordinates), draw(coordinates)])
    ij = np.array(draw(st.lists(st.tuples(st.integers(-3, 3), st.integers(-3, 3)), min_size=4, max_size=4)), float)
    if draw(st.booleans()):
        ij = np.column_stack([ij[:, 0] + 0.5 * ij[:, 1], ij[:, 1] * math.sqrt(3.0) / 2.0])
    return [tuple(map(float, p)) for p in ij * h + shift]


@st.composite
def cocircular_quadruples(draw):
    """Four vertices of a regular k-gon (cocircular up to rounding), in ccw order."""
    k = draw(st.integers(4, 12))
    v = regular_polygon(k, draw(st.floats(0.1, 10.0)), center=(draw(coordinates), draw(coordinates)))
    idx = sorted(draw(st.lists(st.integers(0, k - 1), min_size=4, max_size=4, unique=True)))
    return [tuple(map(float, v[i])) for i in idx]


quadruples = st.one_of(st.lists(points, min_size=4, max_size=4), lattice_quadruples(), cocircular_quadruples())

# --------------------------------------------------------------------------- expansion arithmetic

#: Doubles of every magnitude the exact fallback meets (products of coordinates and their differences).
doubles = st.one_of(st.just(0.0), st.floats(-1e6, 1e6).filter(lambda x: x == 0.0 or abs(x) > 1e-30))


def _significant_bits(x):
    """Bits between the highest and the lowest set bit of the double ``x`` (0 for 0)."""
    if x == 0.0:
        return 0
    m = int(math.ldexp(math.frexp(abs(x))[0], 53))
    return (m // (m & -m)).bit_length()


def _lowest_bit(x):
    m, e = math.frexp(abs(x))
    m = int(math.ldexp(m, 53))
    return e - 53 + ((m & -m).bit_length() - 1)


def assert_expansion(h, n, value):
    """``h[:n]`` is a nonoverlapping expansion of ``value``: increasing magnitude, no zero unless alone."""
    comps = [float(c) for c in h[:n]]
    assert n >= 1 and sum(map(Fraction, comps), Fraction(0)) == value
    assert n == 1 or 0.0 not in comps, comps
    for small, big in zip(comps, comps[1:]):
        assert math.frexp(small)[1] <= _lowest_bit(big), comps  # every bit of small is below big's lowest


@given(doubles, doubles)
def test_two_sum_and_two_product_are_exact(a, b):
    x, y = pr._two_sum(a, b)
    assert x == a + b and Fraction(x) + Fraction(y) == Fraction(a) + Fraction(b)
    x, y = pr._two_product(a, b)
    assert x == a * b and Fraction(x) + Fraction(y) == Fraction(a) * Fraction(b)
    x, y = pr._difference(a, b)
    assert_expansion(x, y, Fraction(a) - Fraction(b))


@given(doubles)
def test_split_halves_have_26_bits(a):
    hi, lo = pr._split(a)
    assert Fraction(hi) + Fraction(lo) == Fraction(a)
    assert _significant_bits(hi) <= 26 and _significant_bits(lo) <= 26


def test_split_by_hand():
    """2^53 - 1 (53 ones) splits into 2^53 and -1: the splitter is 2^27 + 1."""
    assert pr._split(2.0**53 - 1.0) == (2.0**53, -1.0)
    assert pr._split(1.0 + 2.0**-52) == (1.0, 2.0**-52)


@given(st.lists(doubles, min_size=1, max_size=8))
def test_grow_keeps_an_exact_nonoverlapping_expansion(terms):
    h = np.empty(len(terms) + 1)
    n = 0
    for i, b in enumerate(terms):
        n = pr._grow(h, n, b)
        assert_expansion(h, n, sum(map(Fraction, terms[: i + 1]), Fraction(0)))


def test_grow_eliminates_zeros_by_hand():
    """1 + 2^-60 is two components; adding -1 leaves one; adding -2^-60 leaves the single zero."""
    h = np.empty(4)
    n = pr._grow(h, 0, 1.0)
    n = pr._grow(h, n, 2.0**-60)
    assert (n, list(h[:n])) == (2, [2.0**-60, 1.0])
    n = pr._grow(h, n, -1.0)
    assert (n, list(h[:n])) == (1, [2.0**-60])
    n = pr._grow(h, n, -(2.0**-60))
    assert (n, list(h[:n])) == (1, [0.0])


@given(
    st.lists(doubles, min_size=1, max_size=3), st.lists(doubles, min_size=1, max_size=3), st.sampled_from([1.0, -1.0])
)
def test_add_product_is_exact(e_terms, f_terms, sign):
    def expansion(terms):
        h = np.empty(len(terms) + 1)
        n = 0
        for b in terms:
            n = pr._grow(h, n, b)
        return h, n, sum(map(Fraction, terms), Fraction(0))

    (e, ne, ev), (f, nf, fv) = expansion(e_terms), expansion(f_terms)
    h = np.empty(2 * ne * nf + 2)
    n = pr._grow(h, 0, 3.0)
    n = pr._add_product(h, n, e, ne, f, nf, sign)
    assert_expansion(h, n, 3 + int(sign) * ev * fv)
    cross, nc = pr._cross_exact(e, ne, f, nf, f, nf, e, ne)
    assert_expansion(cross, nc, Fraction(0))
    lift, nl = pr._lift_exact(e, ne, f, nf)
    assert_expansion(lift, nl, ev * ev + fv * fv)


# --------------------------------------------------------------------------- the predicates


def _close(value, exact, permanent, bound):
    return abs(Fraction(float(value)) - exact) <= bound * permanent


def _top_component(top, exact):
    """``top`` is the largest component of a nonoverlapping expansion of ``exact``: the rest is below its lowest bit."""
    return exact == 0 if top == 0.0 else abs(exact - Fraction(float(top))) < Fraction(2) ** _lowest_bit(top)


@given(quadruples)
def test_predicates_give_the_exact_sign(quad):
    """orient2d and incircle agree in sign with rational arithmetic, and in value up to their error bounds."""
    a, b, c, d = quad
    for p, q, r in ((a, b, c), (a, b, d)):
        det, permanent = exact_orient(p, q, r)
        value = orient2d(*p, *q, *r)
        assert _sign(value) == _sign(det)
        assert _close(value, det, permanent, 4 * EPS)
        exact = pr._orient_exact(*p, *q, *r)
        assert _top_component(exact, det)
    if exact_orient(a, b, c)[0] > 0:
        det, permanent = exact_incircle(a, b, c, d)
        value = incircle(*a, *b, *c, *d)
        assert _sign(value) == _sign(det)
        assert _close(value, det, permanent, 16 * EPS)
        exact = pr._incircle_exact(*a, *b, *c, *d)
        assert _top_component(exact, det)


def test_predicates_on_exact_degeneracies():
    """Exactly collinear and cocircular points give 0; a point one ulp off the line gives the right side."""
    assert orient2d(0.0, 0.0, 1.0, 1.0, 3.0, 3.0) == 0.0
    assert orient2d(0.1, 0.1, 0.3, 0.3, 0.7, 0.7) == 0.0
    assert orient2d(0.0, 0.0, 1.0, 1.0, 3.0, np.nextafter(3.0, 4.0)) > 0.0
    assert orient2d(0.0, 0.0, 1.0, 1.0, 3.0, np.nextafter(3.0, 2.0)) < 0.0
    assert incircle(0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0) == 0.0
    assert incircle(0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, np.nextafter(1.0, 0.0)) > 0.0
    assert incircle(0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, np.nextafter(1.0, 2.0)) < 0.0


#: Points whose determinant rounds to a few ulps of the wrong sign (found by a search over lattice points
#: and regular polygons shifted by a float): the floating-point filter must send them to the exact path.
#: Orientation: three collinear lattice points moved off the line by the rounding of their shift.
ROUNDED_COLLINEAR = [
    (17.411734702368754, 63.40775260450107),
    (-8.988265297631244, 30.40775260450107),
    (-74.98826529763124, -52.09224739549893),
]
#: In-circle: near-cocircular quadruples where each one of the three terms of the permanent decides.
ROUNDED_COCIRCULAR = [
    [
        (15.92126927774595, 32.613187074599026),
        (19.321269277745948, 30.913187074599026),
        (19.321269277745948, 32.613187074599026),
        (15.92126927774595, 30.913187074599026),
    ],
    [
        (20.926165246765393, 3.685615981610309),
        (20.926165246765393, 1.9856159816103087),
        (24.32616524676539, 1.9856159816103087),
        (24.32616524676539, 3.685615981610309),
    ],
    [
        (-27.64288931395287, 21.926510684504446),
        (-29.12288931395287, 21.926510684504446),
        (-28.012889313952872, 21.556510684504445),
        (-28.75288931395287, 21.556510684504445),
    ],
    # a far from d, b and c near it: the first term's lift is large.
    [
        (-69.39856049678312, -45.80618297899076),
        (-22.62861706679063, -9.09126415966715),
        (-23.847830536049322, -7.241910777572148),
        (-23.22111730167882, -8.155309756583527),
    ],
]


def test_predicates_where_rounding_gives_the_wrong_sign():
    a, b, c = ROUNDED_COLLINEAR
    det = exact_orient(a, b, c)[0]
    left, right = (a[0] - c[0]) * (b[1] - c[1]), (a[1] - c[1]) * (b[0] - c[0])
    assert det < 0 < left - right  # the premise: rounding flips the sign
    assert _sign(orient2d(*a, *b, *c)) == -1
    for a, b, c, d in ROUNDED_COCIRCULAR:
        assert exact_orient(a, b, c)[0] > 0
        assert _sign(incircle(*a, *b, *c, *d)) == _sign(exact_incircle(a, b, c, d)[0])


def test_cross_exact_fills_its_buffer():
    """Two products with rounding errors at exponents far apart: four nonoverlapping components, the most possible."""
    one = np.array([1.0 + 2.0**-30])
    tiny = np.array([2.0**-100 * (1.0 + 2.0**-30)])
    h, n = pr._cross_exact(one, 1, one, 1, tiny, 1, tiny, 1)
    assert n == 4
    assert_expansion(h, n, Fraction(one[0]) ** 2 - Fraction(tiny[0]) ** 2)


def test_incircle_exact_fills_its_buffer():
    """d at the origin, a, b, c of odd 16-bit integers scaled by 1, 2^-150, 2^-300: every difference, lift and cross
    product is one component, and the three terms lift * cross, 2^150 apart, are inexact products of two 31-bit
    numbers: six nonoverlapping components, the most its buffer (2 * 3 + 1) has room for."""
    a = (41547.0, 43305.0)
    b = (math.ldexp(54385.0, -150), math.ldexp(63279.0, -150))
    c = (math.ldexp(21587.0, -300), math.ldexp(-26565.0, -300))
    d = (0.0, 0.0)
    assert _top_component(pr._incircle_exact(*a, *b, *c, *d), exact_incircle(a, b, c, d)[0])


def test_predicates_by_hand():
    """Values far from degenerate are the plain determinants: orient = twice the signed area."""
    assert orient2d(0.0, 0.0, 2.0, 0.0, 0.0, 3.0) == 6.0
    assert orient2d(0.0, 0.0, 0.0, 3.0, 2.0, 0.0) == -6.0
    # d at the centre of the unit circle through a, b, c: the determinant is |abc| * 2 * r^2 = 2 * 1 * 1.
    assert incircle(1.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, 0.0) == 2.0
    assert incircle(1.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, -2.0) < 0.0


# --------------------------------------------------------------------------- geometry as the reference's

finite = coordinates


triangles = st.lists(st.tuples(finite, finite), min_size=3, max_size=3).filter(lambda t: exact_orient(*t)[0] != 0)


@given(triangles, st.permutations([0, 1, 2]))
def test_circumcircle_is_the_reference_bit_for_bit(triangle, order):
    """Centre and radius are :func:`circumcenters` of the vertices in index order; g is their centroid."""
    P = np.array(triangle)
    cx, cy, r, gx, gy = fast._circumcircle(P, *order)
    centre, radius = circumcenters(P[0], P[1], P[2])
    assert [cx, cy, r] == [*centre, radius]
    assert (gx, gy) == tuple((P[0] + P[1] + P[2]) / 3.0)


@given(st.tuples(finite, finite), st.tuples(finite, finite), st.tuples(finite, finite))
def test_point_segment_distance_is_the_reference_bit_for_bit(x, a, b):
    expected = point_segment_distance(np.array(x), np.array(a), np.array(b))
    assert fast._point_segment_distance(*x, *a, *b) == expected
    P = np.array([a, b])
    assert fast._edge_distance(P, 0, 1, *x) == expected


def test_point_segment_distance_by_hand():
    """Beyond either end the distance is to the end; over the segment, to the line; a point segment is a point."""
    assert fast._point_segment_distance(5.0, 4.0, 0.0, 0.0, 2.0, 0.0) == 5.0
    assert fast._point_segment_distance(-3.0, 4.0, 0.0, 0.0, 2.0, 0.0) == 5.0
    assert fast._point_segment_distance(1.5, -2.0, 0.0, 0.0, 2.0, 0.0) == 2.0
    assert fast._point_segment_distance(4.0, 5.0, 1.0, 1.0, 1.0, 1.0) == 5.0
    assert fast._point_segment_distance(0.25, 1.0, 0.0, 0.0, 0.5, 0.0) == 1.0  # a segment shorter than 1


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


# --------------------------------------------------------------------------- the heap

#: Keys with many ties in value, then in x.
heap_keys = st.lists(
    st.tuples(st.sampled_from([1.0, 1.5, 2.0]), st.sampled_from([0.0, 1.0]), st.sampled_from([0.0, 1.0])),
    min_size=1,
    max_size=12,
)


def _heap(keys):
    HK, HI = np.empty((len(keys) + 1, 3)), np.empty((len(keys) + 1, 3), dtype=np.int64)
    n = 0
    for i, (value, x, y) in enumerate(keys):
        n = fast._push(HK, HI, n, value, x, y, i, 10 + i, i % 3 - 1)
    return HK, HI, n


def _pop_all(HK, HI, n):
    out = []
    while n:
        n = fast._pop(HK, HI, n)
        out.append((-HK[n, 0], HK[n, 1], HK[n, 2], *HI[n]))
    return out


@given(heap_keys)
def test_heap_pops_the_largest_value_then_smallest_x_then_y(keys):
    HK, HI, n = _heap(keys)
    assert n == len(keys)
    expected = sorted(((*k, i, 10 + i, i % 3 - 1) for i, k in enumerate(keys)), key=lambda e: (-e[0], e[1], e[2], e[3]))
    popped = _pop_all(HK, HI, n)
    assert [e[:3] for e in popped] == [e[:3] for e in expected]
    assert all(keys[e[3]] == e[:3] and e[4] == 10 + e[3] and e[5] == e[3] % 3 - 1 for e in popped)


def test_before_is_lexicographic():
    assert fast._before(-2.0, 5.0, 5.0, -1.0, 0.0, 0.0)
    assert not fast._before(-1.0, 0.0, 0.0, -2.0, 5.0, 5.0)
    assert fast._before(-1.0, 0.0, 5.0, -1.0, 1.0, 0.0) and not fast._before(-1.0, 1.0, 0.0, -1.0, 0.0, 5.0)
    assert fast._before(-1.0, 1.0, 0.0, -1.0, 1.0, 1.0) and not fast._before(-1.0, 1.0, 1.0, -1.0, 1.0, 0.0)
    assert not fast._before(-1.0, 1.0, 1.0, -1.0, 1.0, 1.0)


@given(heap_keys, st.data())
def test_compact_keeps_exactly_the_live_entries_in_heap_order(keys, data):
    """An entry lives when its slot's version is current and its segment (if any) is alive."""
    HK, HI, n = _heap(keys)
    ver = np.array([10 + i + data.draw(st.sampled_from([0, 0, 1])) for i in range(len(keys))], dtype=np.int64)
    salive = np.array([data.draw(st.booleans()), data.draw(st.booleans())])
    live = [i for i in range(len(keys)) if ver[i] == 10 + i and (i % 3 - 1 < 0 or salive[i % 3 - 1])]
    k = fast._compact(HK, HI, n, ver, salive)
    assert k == len(live)
    assert sorted(e[3] for e in _pop_all(HK, HI, k)) == live
    HK, HI, n = _heap(keys)
    k = fast._compact(HK, HI, n, ver, salive)
    popped = _pop_all(HK, HI, k)
    assert [e[:3] for e in popped] == sorted((keys[i] for i in live), key=lambda e: (-e[0], e[1], e[2]))


@given(heap_keys, st.integers(0, 40), st.data())
def test_room_makes_room_and_keeps_the_live_entries_in_heap_order(keys, need, data):
    """Both arrays, of one length, have room for need more entries; all entries are kept while there is room
    already, else exactly the live ones."""
    HK, HI, n = _heap(keys)
    ver = np.array([10 + i + data.draw(st.sampled_from([0, 0, 1])) for i in range(len(keys))], dtype=np.int64)
    salive = np.array([data.draw(st.booleans()), data.draw(st.booleans())])
    live = [i for i in range(len(keys)) if ver[i] == 10 + i and (i % 3 - 1 < 0 or salive[i % 3 - 1])]
    room = n + need <= len(HK)
    HK, HI, k = fast._room(HK, HI, n, need, ver, salive)
    assert len(HK) == len(HI) >= k + need
    popped = _pop_all(HK, HI, k)
    assert sorted(e[3] for e in popped) == (list(range(n)) if room else live)
    assert [e[:3] for e in popped] == sorted((e[:3] for e in popped), key=lambda e: (-e[0], e[1], e[2]))


def test_grown_pads_with_zeros():
    a = np.array([[1, 2], [3, 4]], dtype=np.int64)
    g = fast._grown(a, 5)
    assert g.dtype == a.dtype and g.tolist() == [[1, 2], [3, 4], [0, 0], [0, 0], [0, 0]]
    assert fast._grown(np.array([1.5]), 3).tolist() == [1.5, 0.0, 0.0]


@pytest.mark.parametrize("i, j", [(0, 1), (1, 0), (2, 2)])
def test_swap_exchanges_two_rows(i, j):
    HK = np.arange(9.0).reshape(3, 3)
    HI = np.arange(9).reshape(3, 3)
    fast._swap(HK, HI, i, j)
    order = list(range(3))
    order[i], order[j] = order[j], order[i]
    assert HK.tolist() == np.arange(9.0).reshape(3, 3)[order].tolist()
    assert HI.tolist() == np.arange(9).reshape(3, 3)[order].tolist()


# --------------------------------------------------------------------------- the CDT operations


def _ring(corners, step):
    """Points every ``step`` along the closed polygon ``corners`` (side lengths multiples of ``step``)."""
    out = []
    for a, b in zip(corners, corners[1:] + corners[:1]):
        k = round(math.dist(a, b) / step)
        out += [(a[0] + (b[0] - a[0]) * i / k, a[1] + (b[1] - a[1]) * i / k) for i in range(k)]
    return out


def _square_ring(size, step, hole, inner=()):
    """A ``size`` square with (or without) a square hole of a third of its size in the middle, boundary points
    ``step`` apart, and the points ``inner``: ``(P, V, SA, SB)``, points, the CDT's triangles, the constraint
    segments' ends."""
    a, b = size / 3.0, 2.0 * size / 3.0
    rings = [_ring([(0.0, 0.0), (size, 0.0), (size, size), (0.0, size)], step)]
    rings += [_ring([(a, a), (a, b), (b, b), (b, a)], step)] if hole else []
    P = np.array([p for ring in rings for p in ring] + list(inner))
    segments, start = [], 0
    for ring in rings:
        segments += [(start + i, start + (i + 1) % len(ring)) for i in range(len(ring))]
        start += len(ring)
    segments = np.array(segments, dtype=np.int64)
    holes = np.array([[size / 2.0, size / 2.0]]) if hole else np.empty((0, 2))
    V = np.ascontiguousarray(constrained_delaunay(P, segments, holes), dtype=np.int64)
    return P, V, segments[:, 0].copy(), segments[:, 1].copy()


@st.composite
def square_rings(draw):
    """A 6 x 6 square with (or without) a 2 x 2 square hole, boundary points 1 apart, and generic interior points
    (:func:`_square_ring`)."""
    hole = draw(st.booleans())
    inner = draw(st.lists(st.tuples(st.floats(0.3, 5.7), st.floats(0.3, 5.7)), max_size=6))
    return _square_ring(6.0, 1.0, hole, [p for p in inner if not (hole and 1.7 <= p[0] <= 4.3 and 1.7 <= p[1] <= 4.3)])


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


def _contains(P, V, t, x, y):
    a, b, c = P[V[t]]
    return min(orient2d(*a, *b, x, y), orient2d(*b, *c, x, y), orient2d(*c, *a, x, y)) >= 0.0


@given(square_rings(), st.data())
def test_walk_decides_visibility_like_the_brute_force_test(ring, data):
    """Status 1: gc touches no constraint and c is in the triangle returned; 0: it touches one; -1 only when degenerate."""
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
        assert _contains(P, V, where, *c)
    # A start point on an edge of t is degenerate.
    assert walk(P, V, N, S, t, *P[V[t, 0]], *c, len(V) + 1) == (-1, -1)


def test_walk_through_a_vertex_is_degenerate_and_a_constraint_end_is_touching():
    """On an 18 x 18 ring of points 3 apart (every centroid g an integer point): c on a vertex of g's triangle,
    or past it, or opposite it on the line through g and the vertex, is degenerate (-1); c inside a constraint
    edge of g's triangle touches it (0), constraint 0 included."""
    P, V, SA, SB = _square_ring(18.0, 3.0, hole=True)
    N, S, _ = adjacency(V, SA, SB, len(P))
    for t in range(len(V)):
        g = P[V[t]].sum(axis=0) / 3.0
        for e in range(3):
            v = P[V[t, e]]
            for c in (v, 2.0 * v - g, 2.0 * g - v, 4.0 * g - 3.0 * v):
                if not (_contains(P, V, t, *c) and tuple(c) != tuple(v)):
                    assert walk(P, V, N, S, t, *g, *c, len(V) + 1) == (-1, -1)
            if S[t, e] >= 0:
                middle = (v + P[V[t, (e + 1) % 3]]) / 2.0
                assert walk(P, V, N, S, t, *g, *middle, len(V) + 1) == (0, t)
    assert 0 in S


def test_walk_is_the_same_at_any_scale():
    """Scaled by 2^-20 (exactly: every orientation by 2^-40, far below 1), every walk from every triangle to the
    points of a grid gives the same answer (the signs decide, never a magnitude)."""
    P, V, SA, SB = _square_ring(6.0, 1.0, True, [(0.5, 4.3), (5.2, 1.1), (3.1, 5.4)])
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
    containing = [t for t in range(len(V)) if _contains(P, V, t, x, y)]
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
        lowest = next(t for t in range(len(V)) if _contains(xy, V, t, x, y))
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
    """cavity = the brute-force cavity; its boundary has k + 2 edges; the fan refills it: ccw, linked, locally Delaunay."""
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


# --------------------------------------------------------------------------- the engine's candidates


def _assert_candidates(P, V, SA, SB, l):
    """Per triangle: the visible circumcentre and the constraint midpoints of value at least (1 - REL_TOL) l the
    reference lists, same bits, same values; the same circumcentres when the distance search gives up at once (a
    buffer of one triangle) and measures every constraint."""
    N, S, _ = adjacency(V, SA, SB, len(P))
    segments = np.column_stack([SA, SB])
    salive, alive = np.ones(len(SA), dtype=np.bool_), np.ones(len(V), dtype=np.bool_)
    lim, seen = fast._limits(l), np.empty(fast._NEAR_TRIANGLES, dtype=np.int64)
    centres, radii = reference.circle_candidates(P, V, segments, l)
    listed = {(x, y): r for (x, y), r in zip(centres.tolist(), radii.tolist())}
    HK, HI = np.empty((4 * len(V), 3)), np.empty((4 * len(V), 3), dtype=np.int64)
    nh = 0
    for t in range(len(V)):
        r, cx, cy, where = fast._visible_circumcentre(P, V, N, S, SA, SB, salive, len(SA), alive, len(V), t, lim, seen)
        assert (r >= 0.0) == ((cx, cy) in listed)
        if r >= 0.0:
            assert r == listed[(cx, cy)] and _contains(P, V, where, cx, cy)
        assert fast._visible_circumcentre(P, V, N, S, SA, SB, salive, len(SA), alive, len(V), t, lim, seen[:1])[0] == r
        nh = fast._push_candidates(
            P, V, N, S, SA, SB, salive, len(SA), alive, np.arange(len(V)), len(V), t, lim, seen, HK, HI, nh
        )
    mids, values, split = reference.midpoint_candidates(P, V, segments, l)
    expected = sorted(
        [(-r, x, y, -1) for (x, y), r in zip(centres.tolist(), radii.tolist())]
        + [(-v, x, y, s) for (x, y), v, s in zip(mids.tolist(), values.tolist(), split.tolist()) if v >= lim[0]]
    )
    pushed = sorted((*HK[i], HI[i, 2]) for i in range(nh))
    assert pushed == expected
    assert all(HI[i, 1] == HI[i, 0] for i in range(nh))  # each entry carries its triangle's version


@given(square_rings(), st.floats(0.3, 2.0), st.data())
def test_candidates_are_the_reference_candidates(ring, l, data):
    """:func:`_assert_candidates`; and ``_gap`` is the distance to the nearest constraint whenever it is at most
    half the search reach, also when the search gives up (a buffer of one triangle) and measures every constraint.
    """
    P, V, SA, SB = ring
    _assert_candidates(P, V, SA, SB, l)
    N, S, _ = adjacency(V, SA, SB, len(P))
    salive, lim, seen = (
        np.ones(len(SA), dtype=np.bool_),
        fast._limits(l),
        np.empty(fast._NEAR_TRIANGLES, dtype=np.int64),
    )
    x, y = data.draw(st.tuples(st.floats(0.0, 6.0), st.floats(0.0, 6.0)))
    t = locate(P, V, N, np.ones(len(V), dtype=np.bool_), len(V), 0, x, y, len(V) + 1)
    if t >= 0:
        nearest = min(fast._point_segment_distance(x, y, *P[a], *P[b]) for a, b in zip(SA, SB))
        for reach, buffer in ((lim[4], seen), (lim[4], seen[:1]), (0.0, seen)):
            gap = fast._gap(P, V, N, S, SA, SB, salive, len(SA), t, x, y, reach, buffer)
            assert gap >= nearest and (gap == nearest or nearest > reach / 2.0)


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
    status, points, _, _, values = fast._insert_all(P, V, np.column_stack([SA, SB]), fast._limits(4.0))
    assert status == fast._OK and points[len(P)].tolist() == [0.0, -4.0] and values[0] == 5.0


def test_candidates_after_a_short_constraint():
    """A triangle whose first edge is a constraint too short for a candidate and whose other two are long: their
    midpoints are candidates all the same."""
    P = np.array([(0.0, 0.0), (1.0, 0.0), (0.0, 6.0)])
    _assert_candidates(P, np.array([[0, 1, 2]]), np.array([0, 1, 2]), np.array([1, 2, 0]), 1.0)


@pytest.mark.parametrize("hole", [False, True])
def test_candidates_where_every_boundary_midpoint_counts(hole):
    """l = 0.45 on a ring of points 1 apart: the midpoint of every constraint edge is a candidate, whichever edge
    of its triangle it is."""
    _assert_candidates(*_square_ring(6.0, 1.0, hole, [(0.5, 4.3), (5.2, 1.1), (3.1, 5.4), (2.5, 0.6)]), 0.45)


@pytest.mark.parametrize("hole", [False, True])
def test_gap_is_the_nearest_constraint_within_half_its_reach(hole):
    """From the triangle containing each point of a grid, for reaches from a fraction of a triangle to most of the
    region: the distance to the nearest constraint, exact whenever it is at most half the reach."""
    P, V, SA, SB = _square_ring(6.0, 1.0, hole, [(0.5, 4.3), (5.2, 1.1), (3.1, 5.4), (2.5, 0.6)])
    N, S, _ = adjacency(V, SA, SB, len(P))
    salive, seen = np.ones(len(SA), dtype=np.bool_), np.empty(len(V), dtype=np.int64)
    for x, y in [(0.25 + 0.7 * i, 0.15 + 0.7 * j) for i in range(9) for j in range(9)]:
        t = locate(P, V, N, np.ones(len(V), dtype=np.bool_), len(V), 0, x, y, len(V) + 1)
        if t < 0:
            continue
        nearest = min(fast._point_segment_distance(x, y, *P[a], *P[b]) for a, b in zip(SA, SB))
        for reach in (0.3, 1.0, 2.0, 6.0):
            gap = fast._gap(P, V, N, S, SA, SB, salive, len(SA), t, x, y, reach, seen)
            assert gap >= nearest and (gap == nearest or nearest > reach / 2.0)


def test_a_cavity_larger_than_its_buffer():
    """A regular 70-gon: its vertices are cocircular, so the first point (a circumcentre near the centre) has a
    cavity of more than ``_CAVITY`` (64) triangles: the buffer must grow, and the mesh is Problem 1's."""
    vertices = regular_polygon(70, 1.5)
    ring = np.array([(i, (i + 1) % 70) for i in range(70)], dtype=np.int64)
    V = np.ascontiguousarray(constrained_delaunay(vertices, ring, np.empty((0, 2))), dtype=np.int64)
    N, S, _ = adjacency(V, ring[:, 0].copy(), ring[:, 1].copy(), 70)
    point, _, _ = reference.best_candidate(vertices, V, ring, 1.0)
    start = locate(vertices, V, N, np.ones(len(V), dtype=np.bool_), len(V), 0, *point, len(V) + 1)
    mark = np.zeros(len(V), dtype=np.int64)
    assert cavity(vertices, V, N, S, start, *point, mark, 1, np.empty(fast._CAVITY, dtype=np.int64)) == -1
    assert cavity(vertices, V, N, S, start, *point, mark, 2, np.empty(len(V), dtype=np.int64)) > fast._CAVITY
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
    cocircular points: the reference's points, values and triangles bit for bit (``tests/test_engines.py`` does
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
    monkeypatch.setattr(fast, "_insert_all", lambda P0, T0, SEG0, lim: (fast._BROKEN, P0, T0, SEG0, np.empty(0)))
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
    """(points, l) of the reference engine's threshold tests (``tests/test_reference_engine.py``), and a radius
    at (1 - REL_TOL) l and at (1 + REL_TOL) l (this one within SLIVER_GAP l of a constraint) and a constraint of
    half-length (1 - REL_TOL) l, each exactly."""
    cases = [(circle_triangle(gap, radius)[0], 1.0) for gap, radius, _ in NEAR_CONSTRAINT]
    cases += [(circle_triangle(0.5, 1.5)[0], 1.5 / factor) for factor in (1.0 - 0.5 * REL_TOL, 1.0 - 2.0 * REL_TOL)]
    for tol, radius in [(REL_TOL, 3.0), (SLIVER_GAP, 1.0)]:
        points, _, l = at_exactly(tol, radius)
        cases += [(points, l), (points, np.nextafter(l, 0.0) * (1.0 - 4.0 * REL_TOL))]
    for gap, radius, factor in [(0.5, 1.5, 1.0 - REL_TOL), (0.5 * SLIVER_GAP, 1.0, 1.0 + REL_TOL)]:
        points = circle_triangle(gap, radius)[0]
        cases.append((points, _l_at(fast._circumcircle(points, 0, 1, 2)[2], factor)))
    cases.append((np.array([[-1.0, 0.0], [1.0, 0.0], [0.0, 5.0]]), _l_at(1.0, 1.0 - REL_TOL)))
    return cases


def test_every_limit_is_a_multiple_of_l():
    """Scaling l by a power of two scales every threshold and the search reach by it exactly."""
    for k in (-7, 1, 30):
        assert fast._limits(math.ldexp(1.3, k)).tolist() == [math.ldexp(x, k) for x in fast._limits(1.3)]


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
    is the float just below the one for which REL_TOL l is the centre's gap to ab.  Pushed, the centre is accepted (gap over
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
    cx, cy, _, _, _ = fast._circumcircle(points, 0, 3, 4)
    a, b = points[0], points[1]
    p = 0.5 * (a + b)
    before = fast._point_segment_distance(cx, cy, *a, *b)
    after = min(fast._point_segment_distance(cx, cy, *a, *p), fast._point_segment_distance(cx, cy, *p, *b))
    l = np.nextafter(_l_at(before, REL_TOL), 0.0)
    assert after <= REL_TOL * l < before and abs(l - 0.7) < 1e-6
    region = Region(points, np.array([[i, (i + 1) % 5] for i in range(5)]), np.empty((0, 2)))
    assert [0, 3, 4] in map(sorted, constrained_delaunay(points, region.segments, region.holes).tolist())
    got, expected = fast.run(region, l), reference.run(region, l)
    assert got.points.tobytes() == expected.points.tobytes() and got.values.tobytes() == expected.values.tobytes()
    assert len(got.points) == 13 and [cx, cy] not in got.points.tolist()
