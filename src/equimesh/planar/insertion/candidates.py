"""The fast engine's candidates of Step 3 (:mod:`.fast`): per triangle, its circumcentre and its constraint midpoints.

Every candidate belongs to one triangle: its circumcentre (value the
circumradius) and the midpoints of its constraint edges (value
``min(|ab|/2, |m - apex|)`` with that triangle's apex), the candidates 1 and 2
of :mod:`.reference`, computed by the same float operations so that they have
the same bits (:func:`circumcircle`).  Inserting a point changes exactly the
triangles of its cavity, so only their candidates die and only the fan's are
new (:func:`push_candidates` queues them, :mod:`.buckets`).

Visibility (:func:`._cdt.walk`) decides the reference's test "the closed
segment from the centroid to the circumcentre touches no constraint" by
walking through the triangles it crosses; the distance of a circumcentre
to the constraints is the minimum over the constraint edges of the
triangles within ``2 SLIVER_GAP l`` of it, ``_REACH`` (the segment from the
circumcentre to its nearest constraint point crosses only such triangles,
or meets a nearer constraint first; :func:`constraint_gap`).  Degenerate walks
(through a vertex) fall back to the reference's brute-force test against every
constraint (:func:`visible_circumcentre`).  The helpers only index their
arrays and are compiled without numba's reference counting (:mod:`.fast`,
"Compilation").
"""

import math

import numpy as np

from ..._jit import compiled
from ...tolerance import REL_TOL, SLIVER_GAP
from .buckets import offer
from .cdt import locate, segments_touch, walk

#: The distance from a circumcentre to the constraints is searched among the
#: triangles within ``_REACH * SLIVER_GAP * l`` of it (twice the largest gap
#: that matters, a margin against rounding in the edge distances) ...
_REACH = 2.0
#: ... and measured against every constraint when there are more than this
#: many such triangles (a vertex of high degree next to the circumcentre).
NEAR_TRIANGLES = 64

#: A squared circumradius or distance computed in floating point (two squares and a sum, relative error at most 3
#: ulps) below ``SQUARE_MARGIN`` times the square of a bound has a ``hypot`` (error below an ulp) below the bound, and
#: one above the square over ``SQUARE_MARGIN`` a ``hypot`` above it: a margin of 10^-6 against errors of 10^-15.
#: The circumradii of most new triangles are below l, and the edges near a circumcentre are mostly farther than
#: the constraint search's reach, so they skip ``hypot``.
SQUARE_MARGIN = 1.0 - 1e-6


def circumcircle(P, a, b, c, floor=0.0):
    """Circumcentre and radius of the triangle ``abc`` (vertex indices), exactly as
    :func:`equimesh._geometry.circumcenters`.

    Vertices in increasing index order; the operations (relative to the
    first vertex, then ``hypot``) are the reference's, so the bits match.
    ``np.hypot`` is the C library's ``hypot`` compiled and as Python alike
    (Python's ``math.hypot`` rounds differently).  The radius is -1 instead
    when the squared offset of the centre is below ``floor`` (a radius
    surely too small, without the cost of ``hypot``, :data:`SQUARE_MARGIN`).
    """
    i, j, k = min(a, b, c), max(min(a, b), min(max(a, b), c)), max(a, b, c)
    ax, ay = P[i, 0], P[i, 1]
    bbx, bby = P[j, 0] - ax, P[j, 1] - ay
    ccx, ccy = P[k, 0] - ax, P[k, 1] - ay
    d = 2.0 * (bbx * ccy - bby * ccx)
    b2 = bbx * bbx + bby * bby
    c2 = ccx * ccx + ccy * ccy
    ux = (ccy * b2 - bby * c2) / d
    uy = (bbx * c2 - ccx * b2) / d
    gx = (P[i, 0] + P[j, 0] + P[k, 0]) / 3.0
    gy = (P[i, 1] + P[j, 1] + P[k, 1]) / 3.0
    r = -1.0 if ux * ux + uy * uy < floor else np.hypot(ux, uy)
    return ax + ux, ay + uy, r, gx, gy


circumcircle = compiled(circumcircle, nrt=False)


def segment_offset(x, y, ax, ay, bx, by):
    """The offset of ``(x, y)`` from its nearest point on the segment ``ab``: the operations of
    :func:`equimesh._geometry.point_segment_distance` before its ``hypot``."""
    abx, aby = bx - ax, by - ay
    denom = abx * abx + aby * aby
    t = ((x - ax) * abx + (y - ay) * aby) / (denom if denom > 0 else 1.0)
    t = min(max(t, 0.0), 1.0)
    return x - (ax + t * abx), y - (ay + t * aby)


segment_offset = compiled(segment_offset, nrt=False)


def edge_distance_within(P, a, b, x, y, bound):
    """The distance from ``(x, y)`` to the edge ``ab`` bit for bit as
    :func:`equimesh._geometry.point_segment_distance` where it is at most ``bound``, else a number above ``bound``.

    A squared distance above ``bound^2 / SQUARE_MARGIN`` has a ``hypot`` above
    ``bound``; its square root is returned then, without the cost of ``hypot``.
    So a comparison with ``bound`` or less decides as the distance would.
    """
    dx, dy = segment_offset(x, y, P[a, 0], P[a, 1], P[b, 0], P[b, 1])
    d2 = dx * dx + dy * dy
    if SQUARE_MARGIN * d2 > bound * bound:
        return math.sqrt(d2)
    return np.hypot(dx, dy)


edge_distance_within = compiled(edge_distance_within, nrt=False)


def constraint_gap(P, V, N, S, SA, SB, salive, n_segs, start, x, y, reach, seen):
    """Distance from ``(x, y)`` to the nearest constraint, exact whenever it is at most ``reach / 2`` (else a
    number above it).

    Searches the triangles within ``reach`` of the point, from the triangle
    ``start`` containing it, across non-constraint edges; if there are more
    than ``len(seen)`` of them, every constraint is measured.  Distances are
    :func:`edge_distance_within` these bounds, which decide as the exact ones.
    """
    near = 0.5 * reach
    best = np.inf
    seen[0] = start
    k, i = 1, 0
    while i < k:
        t = seen[i]
        i += 1
        for e in range(3):
            s = S[t, e]
            if s >= 0:
                best = min(best, edge_distance_within(P, SA[s], SB[s], x, y, near))
                continue
            n = N[t, e]
            if n < 0 or edge_distance_within(P, V[t, e], V[t, (e + 1) % 3], x, y, reach) > reach:
                continue
            known = False
            for j in range(k):
                known = known or seen[j] == n
            if not known:
                if k == len(seen):
                    best = np.inf
                    for s in range(n_segs):
                        if salive[s]:
                            best = min(best, edge_distance_within(P, SA[s], SB[s], x, y, near))
                    return best
                seen[k] = n
                k += 1
    return best


constraint_gap = compiled(constraint_gap, nrt=False)


def visible_circumcentre(P, V, N, S, SA, SB, salive, n_segs, alive, n_slots, t, lim, seen):
    """Candidate 1 of the reference for triangle ``t``: ``(value, x, y, triangle containing it)`` or value -1.

    ``lim``: :func:`limits`.
    """
    cx, cy, r, gx, gy = circumcircle(P, V[t, 0], V[t, 1], V[t, 2], lim[5])
    if not (math.isfinite(r) and r >= lim[0]):
        return -1.0, cx, cy, -1
    status, where = walk(P, V, N, S, t, gx, gy, cx, cy, n_slots + 1)
    if status < 0:
        for s in range(n_segs):
            if salive[s] and segments_touch(gx, gy, cx, cy, P[SA[s], 0], P[SA[s], 1], P[SB[s], 0], P[SB[s], 1]):
                return -1.0, cx, cy, -1
        where = locate(P, V, N, alive, n_slots, t, cx, cy, n_slots + 1)
    elif status == 0:
        return -1.0, cx, cy, -1
    gap = constraint_gap(P, V, N, S, SA, SB, salive, n_segs, where, cx, cy, lim[4], seen)
    if gap <= lim[2] or (gap <= lim[3] and r <= lim[1]):
        return -1.0, cx, cy, -1
    return r, cx, cy, where


visible_circumcentre = compiled(visible_circumcentre, nrt=False)


def push_candidates(P, V, N, S, SA, SB, salive, n_segs, alive, ver, n_slots, t, lim, seen, queue, nh):
    """Queue the candidates of triangle ``t`` (its circumcentre, its constraint midpoints); the new heap size.

    ``queue``: ``(H, pool, link, table, q)`` of :func:`.buckets.offer`.
    """
    H, pool, link, table, q = queue
    r, cx, cy, _ = visible_circumcentre(P, V, N, S, SA, SB, salive, n_segs, alive, n_slots, t, lim, seen)
    if r >= 0.0:
        nh = offer(H, nh, pool, link, table, q, r, cx, cy, 4 * t, ver[t])
    for e in range(3):
        s = S[t, e]
        if s < 0:
            continue
        ax, ay, bx, by = P[SA[s], 0], P[SA[s], 1], P[SB[s], 0], P[SB[s], 1]
        dx, dy = bx - ax, by - ay
        half = 0.5 * math.sqrt(dx * dx + dy * dy)
        if not half >= lim[0]:
            continue
        mx, my = 0.5 * (ax + bx), 0.5 * (ay + by)
        apex = V[t, (e + 2) % 3]
        ex, ey = mx - P[apex, 0], my - P[apex, 1]
        value = min(half, math.sqrt(ex * ex + ey * ey))
        if value >= lim[0]:
            nh = offer(H, nh, pool, link, table, q, value, mx, my, 4 * t + e + 1, ver[t])
    return nh


push_candidates = compiled(push_candidates, nrt=False)


def limits(l):
    """The thresholds of the candidate rules for ``l`` and the reach of the distance search, the ``lim`` of
    :func:`visible_circumcentre`: ``(1 - REL_TOL) l, (1 + REL_TOL) l, REL_TOL l, SLIVER_GAP l, _REACH SLIVER_GAP l``,
    and the squared circumradius below which no circumcentre is a candidate, ``SQUARE_MARGIN ((1 - REL_TOL) l)^2``."""
    low = (1.0 - REL_TOL) * l
    return np.array(
        [low, (1.0 + REL_TOL) * l, REL_TOL * l, SLIVER_GAP * l, _REACH * SLIVER_GAP * l, SQUARE_MARGIN * low * low]
    )
