"""Small vectorised planar primitives shared by validation and insertion.

All functions broadcast over leading axes and take coordinates as ``(..., 2)``
arrays.  They are floating-point predicates: callers that need robustness near
degeneracy keep a margin of :data:`equimesh.tolerance.REL_TOL` times ``l``.
"""

import numpy as np


def cross(u, v):
    """z-component of the cross product of 2-vectors ``u`` and ``v``."""
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def orient(a, b, c):
    """Twice the signed area of triangle ``abc`` (> 0 counter-clockwise)."""
    return cross(b - a, c - a)


def signed_area(ring):
    """Signed area of a closed polygon given as an ``(n, 2)`` vertex ring."""
    return 0.5 * float(np.sum(cross(ring, np.roll(ring, -1, axis=0))))


def segments_intersect(p, q, a, b):
    """Whether closed segments ``pq`` and ``ab`` share a point (vectorised).

    Collinear overlapping segments and touching endpoints count as
    intersecting.
    """
    d1 = orient(a, b, p)
    d2 = orient(a, b, q)
    d3 = orient(p, q, a)
    d4 = orient(p, q, b)
    proper = (d1 * d2 < 0) & (d3 * d4 < 0)

    def on_segment(s, t, r, d):
        lo = np.minimum(s, t)
        hi = np.maximum(s, t)
        inside = np.all((r >= lo) & (r <= hi), axis=-1)
        return (d == 0) & inside

    touching = (
        on_segment(a, b, p, d1)
        | on_segment(a, b, q, d2)
        | on_segment(p, q, a, d3)
        | on_segment(p, q, b, d4)
    )
    return proper | touching


def point_segment_distance(x, a, b):
    """Euclidean distance from points ``x`` to segments ``ab`` (vectorised)."""
    ab = b - a
    denom = np.sum(ab * ab, axis=-1)
    t = np.clip(np.sum((x - a) * ab, axis=-1) / np.where(denom > 0, denom, 1.0), 0.0, 1.0)
    foot = a + t[..., None] * ab
    return np.hypot(*np.moveaxis(x - foot, -1, 0))


def circumcenters(a, b, c):
    """Circumcentres and circumradii of triangles ``abc`` (vectorised).

    Computed relative to ``a`` so that the result is exact under scaling by a
    power of two and independent of translation up to one rounding.
    """
    bb = b - a
    cc = c - a
    d = 2.0 * cross(bb, cc)
    b2 = np.sum(bb * bb, axis=-1)
    c2 = np.sum(cc * cc, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (cc[..., 1] * b2 - bb[..., 1] * c2) / d
        uy = (bb[..., 0] * c2 - cc[..., 0] * b2) / d
    u = np.stack([ux, uy], axis=-1)
    return a + u, np.hypot(ux, uy)
