"""The exact predicates of the fast engine (``planar/insertion/predicates.py``) against rational arithmetic.

What must hold: ``orient2d`` and ``incircle`` have the sign of the exact determinant, also on collinear and
cocircular points, and their value is the determinant up to its floating-point error bound; the expansion
arithmetic below them is exact (two_sum, two_product with Dekker's split, Grow-Expansion: nonoverlapping
components in increasing magnitude, zeros eliminated).
"""

import math
from fractions import Fraction

import numpy as np
from conditions import exercised
from hypothesis import given
from hypothesis import strategies as st
from insertion_cases import exact_incircle, exact_orient, quadruples, sign

from equimesh.planar.insertion import predicates as pr
from equimesh.planar.insertion.predicates import incircle, orient2d

EPS = 2.0**-53


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
    x, y = pr.two_sum(a, b)
    assert x == a + b and Fraction(x) + Fraction(y) == Fraction(a) + Fraction(b)
    x, y = pr.two_product(a, b)
    assert x == a * b and Fraction(x) + Fraction(y) == Fraction(a) * Fraction(b)
    x, y = pr.difference(a, b)
    assert_expansion(x, y, Fraction(a) - Fraction(b))


@given(doubles)
def test_split_halves_have_26_bits(a):
    hi, lo = pr.split(a)
    assert Fraction(hi) + Fraction(lo) == Fraction(a)
    assert _significant_bits(hi) <= 26 and _significant_bits(lo) <= 26


def test_split_by_hand():
    """2^53 - 1 (53 ones) splits into 2^53 and -1: the splitter is 2^27 + 1."""
    assert pr.split(2.0**53 - 1.0) == (2.0**53, -1.0)
    assert pr.split(1.0 + 2.0**-52) == (1.0, 2.0**-52)


@given(st.lists(doubles, min_size=1, max_size=8))
def test_grow_keeps_an_exact_nonoverlapping_expansion(terms):
    h = np.empty(len(terms) + 1)
    n = 0
    for i, b in enumerate(terms):
        n = pr.grow(h, n, b)
        assert_expansion(h, n, sum(map(Fraction, terms[: i + 1]), Fraction(0)))


def test_grow_eliminates_zeros_by_hand():
    """1 + 2^-60 is two components; adding -1 leaves one; adding -2^-60 leaves the single zero."""
    h = np.empty(4)
    n = pr.grow(h, 0, 1.0)
    n = pr.grow(h, n, 2.0**-60)
    assert (n, list(h[:n])) == (2, [2.0**-60, 1.0])
    n = pr.grow(h, n, -1.0)
    assert (n, list(h[:n])) == (1, [2.0**-60])
    n = pr.grow(h, n, -(2.0**-60))
    assert (n, list(h[:n])) == (1, [0.0])


@given(
    st.lists(doubles, min_size=1, max_size=3), st.lists(doubles, min_size=1, max_size=3), st.sampled_from([1.0, -1.0])
)
def test_add_product_is_exact(e_terms, f_terms, sign):
    def expansion(terms):
        h = np.empty(len(terms) + 1)
        n = 0
        for b in terms:
            n = pr.grow(h, n, b)
        return h, n, sum(map(Fraction, terms), Fraction(0))

    (e, ne, ev), (f, nf, fv) = expansion(e_terms), expansion(f_terms)
    h = np.empty(2 * ne * nf + 2)
    n = pr.grow(h, 0, 3.0)
    n = pr.add_product(h, n, e, ne, f, nf, sign)
    assert_expansion(h, n, 3 + int(sign) * ev * fv)
    cross, nc = pr.cross_exact(e, ne, f, nf, f, nf, e, ne)
    assert_expansion(cross, nc, Fraction(0))
    lift, nl = pr.lift_exact(e, ne, f, nf)
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
        assert sign(value) == sign(det)
        assert _close(value, det, permanent, 4 * EPS)
        exact = pr.orient_exact(*p, *q, *r)
        assert _top_component(exact, det)
    if exercised("abc is counter-clockwise", exact_orient(a, b, c)[0] > 0):
        det, permanent = exact_incircle(a, b, c, d)
        value = incircle(*a, *b, *c, *d)
        assert sign(value) == sign(det)
        assert _close(value, det, permanent, 16 * EPS)
        exact = pr.incircle_exact(*a, *b, *c, *d)
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
    assert sign(orient2d(*a, *b, *c)) == -1
    for a, b, c, d in ROUNDED_COCIRCULAR:
        assert exact_orient(a, b, c)[0] > 0
        assert sign(incircle(*a, *b, *c, *d)) == sign(exact_incircle(a, b, c, d)[0])


def test_cross_exact_fills_its_buffer():
    """Two products with rounding errors at exponents far apart: four nonoverlapping components, the most possible."""
    one = np.array([1.0 + 2.0**-30])
    tiny = np.array([2.0**-100 * (1.0 + 2.0**-30)])
    h, n = pr.cross_exact(one, 1, one, 1, tiny, 1, tiny, 1)
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
    assert _top_component(pr.incircle_exact(*a, *b, *c, *d), exact_incircle(a, b, c, d)[0])


def test_predicates_by_hand():
    """Values far from degenerate are the plain determinants: orient = twice the signed area."""
    assert orient2d(0.0, 0.0, 2.0, 0.0, 0.0, 3.0) == 6.0
    assert orient2d(0.0, 0.0, 0.0, 3.0, 2.0, 0.0) == -6.0
    # d at the centre of the unit circle through a, b, c: the determinant is |abc| * 2 * r^2 = 2 * 1 * 1.
    assert incircle(1.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, 0.0) == 2.0
    assert incircle(1.0, 0.0, 0.0, 1.0, -1.0, 0.0, 0.0, -2.0) < 0.0
