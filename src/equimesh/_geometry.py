"""Small vectorised planar primitives shared by validation and insertion.

All functions broadcast over leading axes and take coordinates as ``(..., 2)``
arrays.  They are floating-point predicates: callers that need robustness near
degeneracy keep a margin of :data:`equimesh.tolerance.REL_TOL` times ``l``.
"""

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np


def cross(u, v):
    """z-component of the cross product of 2-vectors ``u`` and ``v``."""
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def inner_angle(xy, i):
    """Inner angle (degrees, in [0, 360)) of the closed polyline ``xy`` at vertex ``i``, the region on its left."""
    n = len(xy)
    u, w = xy[(i - 1) % n] - xy[i % n], xy[(i + 1) % n] - xy[i % n]
    return float(np.degrees(np.arctan2(cross(w, u), np.dot(w, u))) % 360.0)


def orient(a, b, c):
    """Twice the signed area of triangle ``abc`` (> 0 counter-clockwise)."""
    return cross(b - a, c - a)


#: Shewchuk's bound on the relative error of the floating-point orientation
#: determinant ("ccwerrboundA", Adaptive Precision Floating-Point Arithmetic and
#: Fast Robust Geometric Predicates, 1997).
_ORIENT_ERRBOUND = (3.0 + 16.0 * np.finfo(float).eps) * np.finfo(float).eps


def orient_sign(a, b, c):
    """Exact sign (-1, 0, 1) of ``orient(a, b, c)`` (vectorised).

    Floating-point first; where the result is within Shewchuk's error bound
    of zero, it is recomputed exactly in rational arithmetic from the same
    floats.  Used where a wrong sign would be a wrong answer (collinear
    polygon edges, lattice points exactly on a line).
    """
    shape = np.broadcast_shapes(*(np.shape(x)[:-1] for x in (a, b, c)))
    a, b, c = np.broadcast_arrays(*(np.atleast_2d(np.asarray(x, dtype=float)) for x in (a, b, c)))
    left = (a[..., 0] - c[..., 0]) * (b[..., 1] - c[..., 1])
    right = (a[..., 1] - c[..., 1]) * (b[..., 0] - c[..., 0])
    det = left - right
    sign = np.sign(det)
    unsure = np.abs(det) <= _ORIENT_ERRBOUND * (np.abs(left) + np.abs(right))
    for idx in zip(*np.nonzero(unsure)):
        (ax, ay), (bx, by), (cx, cy) = (map(Fraction, p[idx]) for p in (a, b, c))
        exact = (ax - cx) * (by - cy) - (ay - cy) * (bx - cx)
        sign[idx] = (exact > 0) - (exact < 0)
    return sign.reshape(shape)


def signed_area(ring):
    """Signed area of a closed polygon given as an ``(n, 2)`` vertex ring."""
    return 0.5 * float(np.sum(cross(ring, np.roll(ring, -1, axis=0))))


def segments_intersect(p, q, a, b):
    """Whether closed segments ``pq`` and ``ab`` share a point (vectorised, exact).

    Collinear overlapping segments and touching endpoints count as
    intersecting.  Orientation signs are exact (:func:`orient_sign`), so the
    answer is right for the given floating-point coordinates.
    """
    d1 = orient_sign(a, b, p)
    d2 = orient_sign(a, b, q)
    d3 = orient_sign(p, q, a)
    d4 = orient_sign(p, q, b)
    proper = (d1 * d2 < 0) & (d3 * d4 < 0)

    def on_segment(s, t, r, d):
        lo = np.minimum(s, t)
        hi = np.maximum(s, t)
        inside = np.all((r >= lo) & (r <= hi), axis=-1)
        return (d == 0) & inside

    touching = on_segment(a, b, p, d1) | on_segment(a, b, q, d2) | on_segment(p, q, a, d3) | on_segment(p, q, b, d4)
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


def power_of_two_scale(length):
    """The power of two ``s`` with ``length * s`` in ``[1, 2)`` (``length`` positive, finite, normal)."""
    _, exponent = math.frexp(length)
    return math.ldexp(1.0, 1 - exponent)


@dataclass(frozen=True)
class Frame:
    """Local coordinates ``local = (caller - origin) * scale``, ``scale`` a power of two.

    Validation, lattice, insertion and triangulation run in the local frame,
    where the target length is in ``[1, 2)`` and coordinates are moderate:
    every comparison with ``l`` is then free of the caller's offset.  Scaling
    by a power of two is exact, so local lengths divided by ``scale`` are the
    caller's lengths exactly; mapping points back costs one rounding of about
    ``ulp(|origin|)``.
    """

    origin: np.ndarray
    scale: float

    def to_local(self, x):
        return (np.asarray(x, dtype=float) - self.origin) * self.scale

    def to_caller(self, x):
        return np.asarray(x, dtype=float) / self.scale + self.origin


def nearest_segment(x, a, b, chunk=4096):
    """Nearest segment index, parameter t in [0, 1] and distance for each point (vectorised, chunked)."""
    ab = b - a
    denom = np.maximum(np.sum(ab * ab, axis=1), np.finfo(float).tiny)
    index = np.empty(len(x), dtype=np.int64)
    tt = np.empty(len(x))
    dist = np.empty(len(x))
    for start in range(0, len(x), chunk):
        p = x[start : start + chunk, None, :]
        t = np.clip(np.sum((p - a) * ab, axis=2) / denom, 0.0, 1.0)
        d = np.linalg.norm(a + t[..., None] * ab - p, axis=2)
        j = np.argmin(d, axis=1)
        rows = np.arange(len(j))
        index[start : start + chunk] = j
        tt[start : start + chunk] = t[rows, j]
        dist[start : start + chunk] = d[rows, j]
    return index, tt, dist


def between(a, b, t):
    """``(1 - t) a + t b`` row by row: values at the fractions ``t`` of segments, exactly ``a`` at 0 and ``b`` at 1."""
    t = np.asarray(t, dtype=float)
    if np.ndim(a) > 1:
        t = t[:, None]
    return (1.0 - t) * a + t * b


@dataclass(frozen=True)
class Polyline:
    """A plane polyline measured by arc length, values carried along it (the one arc-position helper).

    Attributes
    ----------
    points : (n, 2) float array
        The vertices; for a ``closed`` polyline the segment from the last back
        to the first is part of it (the first is not repeated).
    closed : bool
    values : (n, k) float array, optional
        Carried along (e.g. (u, v)): at an arc position they are interpolated
        with the same fraction of the same segment as the point.
    arc : float array
        Arc position of each vertex, increasing from 0, and for a closed
        polyline its length last (``n + 1`` entries); measured from the points
        unless given (e.g. a polyline reversed, measured from its other end).

    A point at an arc position is ``a + t (b - a)`` on its segment ``(a, b)``:
    a coordinate that ``a`` and ``b`` share (a side of the parameter
    rectangle) stays that float exactly, and a position at a vertex gives the
    vertex bit for bit.  A projection (:meth:`project`) instead interpolates
    with :func:`between`, exact at both ends of its segment.
    """

    points: np.ndarray
    closed: bool = True
    values: np.ndarray | None = None
    arc: np.ndarray | None = None

    def __post_init__(self):
        if self.arc is None:
            object.__setattr__(
                self, "arc", np.concatenate([[0.0], np.cumsum(np.linalg.norm(self.ends - self.starts, axis=1))])
            )

    @property
    def length(self):
        return float(self.arc[-1])

    @property
    def starts(self):
        """The first vertex of each segment."""
        return self.points if self.closed else self.points[:-1]

    @property
    def ends(self):
        """The last vertex of each segment."""
        return np.roll(self.points, -1, axis=0) if self.closed else self.points[1:]

    def segment(self, s):
        """The segment ``k`` each arc position lies on (at a vertex: the one that begins there) and the fraction ``t``.

        On a closed polyline a position ``s >= length`` is ``s - length`` (one turn).
        """
        s = np.asarray(s, dtype=float)
        if self.closed:
            s = np.where(s >= self.arc[-1], s - self.arc[-1], s)
        arc = self.arc
        k = np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(arc) - 2)
        return k, (s - arc[k]) / (arc[k + 1] - arc[k])

    def at(self, s):
        """Points at arc positions ``s``; an open polyline's last position, its length, gives its last vertex
        exactly."""
        return self._interpolate(self.points, s)

    def values_at(self, s):
        """The carried :attr:`values` at arc positions ``s``, interpolated as :meth:`at` interpolates the points."""
        return self._interpolate(self.values, s)

    def direction(self, s):
        """``d point / d s`` at arc positions ``s``: the unit direction of the segment each lies on."""
        k, _ = self.segment(s)
        return (self.ends[k] - self.starts[k]) / (self.arc[k + 1] - self.arc[k])[:, None]

    def project(self, x):
        """The nearest point of the polyline to each of ``x``: its segment ``k``, fraction ``t`` and arc position."""
        k, t, _ = nearest_segment(np.asarray(x, dtype=float), self.starts, self.ends)
        return k, t, (1.0 - t) * self.arc[k] + t * self.arc[k + 1]

    def _interpolate(self, data, s):
        k, t = self.segment(s)
        a = data[k]
        b = np.roll(data, -1, axis=0)[k] if self.closed else data[k + 1]
        inner = np.where((t == 0.0)[:, None], a, a + t[:, None] * (b - a))
        if self.closed:
            return inner
        return np.where((np.asarray(s) >= self.arc[-1])[:, None], data[-1], inner)
