"""Exact orientation and in-circle predicates, compiled (numba).

The fast engine decides every combinatorial question (which side of a line,
inside a circumcircle) with these two predicates.  Lattices and regular
polygons make both determinants exactly zero all the time, so an answer that
depends on rounding could corrupt the triangulation or differ between
platforms.  Each predicate evaluates the determinant in floating point and
returns it when Shewchuk's a-priori error bound proves its sign ("Adaptive
Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates",
1997, ``ccwerrboundA`` and ``iccerrboundA``); otherwise it recomputes the
determinant exactly as a floating-point expansion (two_sum, two_product with
Dekker's split, Grow-Expansion with zero elimination) and returns the
expansion's largest component, whose sign is the sign of the exact value.
The fallback is exact for the given doubles as long as no product overflows
or underflows (coordinates are moderate: the caller works in a frame where
``l`` is about 1).

Compiled without fast-math, so no fused multiply-add can change a rounding,
and with numba's runtime (``nrt=True``, the exact fallback allocates its
expansions) even when called from the engine's helpers compiled without it.
"""

import numpy as np

from ..._jit import compiled

#: Half an ulp of 1.0 (Shewchuk's ``epsilon``).
_EPS = 2.0**-53
#: Dekker's splitter for doubles, 2^27 + 1.
_SPLITTER = 134217729.0
#: Shewchuk's error bounds for the floating-point determinants.
_CCW_BOUND = (3.0 + 16.0 * _EPS) * _EPS
_ICC_BOUND = (10.0 + 96.0 * _EPS) * _EPS


def two_sum(a, b):
    """``a + b = x + y`` exactly, ``x`` the rounded sum (Knuth)."""
    x = a + b
    bv = x - a
    av = x - bv
    return x, (a - av) + (b - bv)


two_sum = compiled(two_sum, nrt=True)


def split(a):
    """``a = hi + lo`` with both halves of at most 26 significant bits (Dekker)."""
    c = _SPLITTER * a
    hi = c - (c - a)
    return hi, a - hi


split = compiled(split, nrt=True)


def two_product(a, b):
    """``a * b = x + y`` exactly, ``x`` the rounded product (Dekker)."""
    x = a * b
    ahi, alo = split(a)
    bhi, blo = split(b)
    err = x - ahi * bhi
    err -= alo * bhi
    err -= ahi * blo
    return x, alo * blo - err


two_product = compiled(two_product, nrt=True)


def grow(h, n, b):
    """Add ``b`` to the expansion ``h[:n]`` in place (Grow-Expansion, zero elimination); the new length.

    ``h`` needs room for ``n + 1`` components.  Components stay
    nonoverlapping and in increasing order of magnitude.
    """
    q = b
    k = 0
    for i in range(n):
        q, e = two_sum(q, h[i])
        if e != 0.0:
            h[k] = e
            k += 1
    if q != 0.0 or k == 0:
        h[k] = q
        k += 1
    return k


grow = compiled(grow, nrt=True)


def add_product(h, n, e, ne, f, nf, sign):
    """``h[:n] += sign * (e[:ne] * f[:nf])`` exactly; the new length (room for ``n + 2 ne nf``)."""
    for i in range(ne):
        for j in range(nf):
            x, y = two_product(e[i], f[j])
            n = grow(h, n, sign * y)
            n = grow(h, n, sign * x)
    return n


add_product = compiled(add_product, nrt=True)


def difference(a, b):
    """``a - b`` as an expansion of one or two components."""
    h = np.empty(2)
    h[0] = a
    return h, grow(h, 1, -b)


difference = compiled(difference, nrt=True)


def orient_exact(ax, ay, bx, by, cx, cy):
    h = np.empty(13)
    n = 0
    for p, q, s in ((ax, by, 1.0), (ax, cy, -1.0), (cx, by, -1.0), (ay, bx, -1.0), (ay, cx, 1.0), (cy, bx, 1.0)):
        x, y = two_product(p, q)
        n = grow(h, n, s * y)
        n = grow(h, n, s * x)
    return h[n - 1]


orient_exact = compiled(orient_exact, nrt=True)


def orient2d(ax, ay, bx, by, cx, cy):
    """A value whose sign is the exact sign of ``orient(a, b, c)`` (> 0: counter-clockwise)."""
    left = (ax - cx) * (by - cy)
    right = (ay - cy) * (bx - cx)
    det = left - right
    if abs(det) > _CCW_BOUND * (abs(left) + abs(right)):
        return det
    return orient_exact(ax, ay, bx, by, cx, cy)


orient2d = compiled(orient2d, nrt=True)


def cross_exact(ux, nux, vy, nvy, uy, nuy, vx, nvx):
    """``u x v = ux vy - uy vx`` for expansions, as an expansion ``(h, n)``."""
    h = np.empty(2 * (nux * nvy + nuy * nvx) + 1)
    n = add_product(h, 0, ux, nux, vy, nvy, 1.0)
    return h, add_product(h, n, uy, nuy, vx, nvx, -1.0)


cross_exact = compiled(cross_exact, nrt=True)


def lift_exact(ux, nux, uy, nuy):
    """``ux^2 + uy^2`` for expansions, as an expansion ``(h, n)``."""
    h = np.empty(2 * (nux * nux + nuy * nuy) + 1)
    n = add_product(h, 0, ux, nux, ux, nux, 1.0)
    return h, add_product(h, n, uy, nuy, uy, nuy, 1.0)


lift_exact = compiled(lift_exact, nrt=True)


def incircle_exact(ax, ay, bx, by, cx, cy, dx, dy):
    adx, nadx = difference(ax, dx)
    ady, nady = difference(ay, dy)
    bdx, nbdx = difference(bx, dx)
    bdy, nbdy = difference(by, dy)
    cdx, ncdx = difference(cx, dx)
    cdy, ncdy = difference(cy, dy)
    alift, na = lift_exact(adx, nadx, ady, nady)
    blift, nb = lift_exact(bdx, nbdx, bdy, nbdy)
    clift, nc = lift_exact(cdx, ncdx, cdy, ncdy)
    bc, nbc = cross_exact(bdx, nbdx, cdy, ncdy, bdy, nbdy, cdx, ncdx)
    ca, nca = cross_exact(cdx, ncdx, ady, nady, cdy, ncdy, adx, nadx)
    ab, nab = cross_exact(adx, nadx, bdy, nbdy, ady, nady, bdx, nbdx)
    h = np.empty(2 * (na * nbc + nb * nca + nc * nab) + 1)
    n = add_product(h, 0, alift, na, bc, nbc, 1.0)
    n = add_product(h, n, blift, nb, ca, nca, 1.0)
    n = add_product(h, n, clift, nc, ab, nab, 1.0)
    return h[n - 1]


incircle_exact = compiled(incircle_exact, nrt=True)


def incircle(ax, ay, bx, by, cx, cy, dx, dy):
    """A value whose sign is the exact sign of the in-circle determinant.

    Positive when ``d`` lies strictly inside the circle through the
    counter-clockwise triangle ``abc``, zero when the four points are
    cocircular.
    """
    adx, ady = ax - dx, ay - dy
    bdx, bdy = bx - dx, by - dy
    cdx, cdy = cx - dx, cy - dy
    bdxcdy, cdxbdy = bdx * cdy, cdx * bdy
    cdxady, adxcdy = cdx * ady, adx * cdy
    adxbdy, bdxady = adx * bdy, bdx * ady
    alift = adx * adx + ady * ady
    blift = bdx * bdx + bdy * bdy
    clift = cdx * cdx + cdy * cdy
    det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady)
    permanent = (
        (abs(bdxcdy) + abs(cdxbdy)) * alift + (abs(cdxady) + abs(adxcdy)) * blift + (abs(adxbdy) + abs(bdxady)) * clift
    )
    if abs(det) > _ICC_BOUND * permanent:
        return det
    return incircle_exact(ax, ay, bx, by, cx, cy, dx, dy)


incircle = compiled(incircle, nrt=True)
