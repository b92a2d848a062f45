"""Fast engine: Steps 3-4 of Algorithm INCREMENT with an incremental CDT and a heap, compiled.

Same candidates, values, rules and tie-breaking as :mod:`.reference` (read
its docstring first); only the bookkeeping differs.

* The constrained Delaunay triangulation (CDT) is built once (Triangle, one
  call) and then updated point by point by constrained Bowyer-Watson
  (:mod:`._cdt`): the cavity starts at the triangle that contains the new
  point (found by the visibility walk, no global point location) and never
  crosses a constraint.  A constraint midpoint splits its segment in two.
* Every candidate belongs to one triangle: its circumcentre (value the
  circumradius) and the midpoints of its constraint edges (value
  ``min(|ab|/2, |m - apex|)`` with that triangle's apex).  Inserting a point
  changes exactly the triangles of its cavity, so only their candidates die
  and only the fan's are new; a surviving triangle keeps its vertices, hence
  the same circumcentre bits and the same apex.  Candidates go into a
  max-heap keyed by ``(value, -x, -y)``, stored as a min-heap on
  ``(-value, x, y)``, with the triangle slot's version: an entry whose
  triangle died (or whose segment was split) is skipped when it surfaces
  (lazy deletion).

Why the heap top is the farthest point of Step 3.  The live entries are the
candidates of the current triangles, and those are exactly the candidates
the reference engine lists after re-triangulating from scratch (the CDT is
unique without four cocircular points, and circumcentres are computed by the
same float operations from the vertices in increasing index order, so they
have the same bits).  The heap's order is the reference's lexsort order:
largest value, then smallest x, then smallest y.  So the top live entry is
the reference's choice, and Step 4 stops when the heap holds no live entry:
only candidates of value at least ``(1 - REL_TOL) l`` are pushed.  A
circumcentre's visibility and its distance to the constraints (the
REL_TOL and SLIVER_GAP rules) are decided when it is pushed and decided
again when it surfaces, because a split constraint moves a little.  (One
difference remains: a circumcentre hidden behind a constraint that a later
split bends out of the way is not listed again unless its triangle changes.)

Visibility (:func:`._cdt.walk`) decides the reference's test "the closed
segment from the centroid to the circumcentre touches no constraint" by
walking through the triangles it crosses; the distance of a circumcentre
to the constraints is the minimum over the constraint edges of the
triangles within ``2 SLIVER_GAP l`` of it, ``_REACH`` (the segment from the
circumcentre to its nearest constraint point crosses only such triangles,
or meets a nearer constraint first).  Degenerate walks (through a vertex)
fall back to the reference's brute-force test against every constraint.

With four or more cocircular points the CDT is not unique: Triangle and
Bowyer-Watson may pick different diagonals, and the two engines may insert
different points.  Both satisfy the same guarantees; the fast engine is
deterministic (exact predicates, fixed slot order).

The engine requires every constraint to bound the region (a triangle on one
side only), as in Problems 1 and 2.

Compilation.  The helpers that take arrays only index them, never allocate,
and are compiled without numba's reference counting (``nrt=False``, :mod:`equimesh._jit`):
with it, every call increments and decrements the count of each array
argument atomically, which dominated the calls of these helpers (docs/decisions.md,
"Kernels compiled by a call").  numba hands that flag down to the functions they
call, so the predicates, whose exact fallback allocates, ask for the
runtime explicitly (``nrt=True`` in :mod:`._predicates`).  The heap's
sift loops call no helper that takes an array for the same reason.

numba's on-disk cache (``cache=True``) is keyed by the source file of each
compiled function, not by the functions it calls: after an edit of
:mod:`._cdt` or :mod:`._predicates` alone, the cached :func:`insert_all`
still holds the old code.  Edit this file too (or delete ``__pycache__/*.nb*``)
whenever one of them changes.
"""

import math

import numpy as np

from ..._jit import compiled
from ...errors import EquimeshError, InternalError
from ...tolerance import REL_TOL, SLIVER_GAP
from .cdt import adjacency, cavity, cavity_boundary, fill, locate, segments_touch, walk
from .region import Insertion, constrained_delaunay

#: The distance from a circumcentre to the constraints is searched among the
#: triangles within ``_REACH * SLIVER_GAP * l`` of it (twice the largest gap
#: that matters, a margin against rounding in the edge distances) ...
_REACH = 2.0
#: ... and measured against every constraint when there are more than this
#: many such triangles (a vertex of high degree next to the circumcentre).
NEAR_TRIANGLES = 64

#: Starting length of the cavity buffers (grown on demand).
CAVITY = 64

#: Returned by the compiled loop: done; else ``-2 - s`` for the first
#: segment ``s`` that is not an edge of exactly one triangle ...
OK = -1
#: ... or a Bowyer-Watson cavity produced a non-counter-clockwise fan (a bug).
BROKEN = -2 - 2**62


def circumcircle(P, a, b, c):
    """Circumcentre and radius of the triangle ``abc`` (vertex indices), exactly as
    :func:`equimesh._geometry.circumcenters`.

    Vertices in increasing index order; the operations (relative to the
    first vertex, then ``hypot``) are the reference's, so the bits match.
    ``np.hypot`` is the C library's ``hypot`` compiled and as Python alike
    (Python's ``math.hypot`` rounds differently).
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
    return ax + ux, ay + uy, np.hypot(ux, uy), gx, gy


circumcircle = compiled(circumcircle, nrt=False)


def point_segment_distance(x, y, ax, ay, bx, by):
    """:func:`equimesh._geometry.point_segment_distance` for one point and segment, same operations."""
    abx, aby = bx - ax, by - ay
    denom = abx * abx + aby * aby
    t = ((x - ax) * abx + (y - ay) * aby) / (denom if denom > 0 else 1.0)
    t = min(max(t, 0.0), 1.0)
    return np.hypot(x - (ax + t * abx), y - (ay + t * aby))


point_segment_distance = compiled(point_segment_distance, nrt=False)


def edge_distance(P, a, b, x, y):
    return point_segment_distance(x, y, P[a, 0], P[a, 1], P[b, 0], P[b, 1])


edge_distance = compiled(edge_distance, nrt=False)


def constraint_gap(P, V, N, S, SA, SB, salive, n_segs, start, x, y, reach, seen):
    """Distance from ``(x, y)`` to the nearest constraint, exact whenever it is at most ``reach / 2``.

    Searches the triangles within ``reach`` of the point, from the triangle
    ``start`` containing it, across non-constraint edges; if there are more
    than ``len(seen)`` of them, every constraint is measured.
    """
    best = np.inf
    seen[0] = start
    k, i = 1, 0
    while i < k:
        t = seen[i]
        i += 1
        for e in range(3):
            s = S[t, e]
            if s >= 0:
                best = min(best, edge_distance(P, SA[s], SB[s], x, y))
                continue
            n = N[t, e]
            if n < 0 or edge_distance(P, V[t, e], V[t, (e + 1) % 3], x, y) > reach:
                continue
            known = False
            for j in range(k):
                known = known or seen[j] == n
            if not known:
                if k == len(seen):
                    best = np.inf
                    for s in range(n_segs):
                        if salive[s]:
                            best = min(best, edge_distance(P, SA[s], SB[s], x, y))
                    return best
                seen[k] = n
                k += 1
    return best


constraint_gap = compiled(constraint_gap, nrt=False)


def visible_circumcentre(P, V, N, S, SA, SB, salive, n_segs, alive, n_slots, t, lim, seen):
    """Candidate 1 of the reference for triangle ``t``: ``(value, x, y, triangle containing it)`` or value -1.

    ``lim`` = ``(1 - REL_TOL) l, (1 + REL_TOL) l, REL_TOL l, SLIVER_GAP l``, the search reach.
    """
    cx, cy, r, gx, gy = circumcircle(P, V[t, 0], V[t, 1], V[t, 2])
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


def before(a0, a1, a2, b0, b1, b2):
    """Heap order: key ``(a0, a1, a2)`` before ``(b0, b1, b2)``, lexicographically on ``(-value, x, y)``."""
    if a0 != b0:
        return a0 < b0
    if a1 != b1:
        return a1 < b1
    return a2 < b2


before = compiled(before, nrt=False)


def swap(HK, HI, a, b):
    for c in range(3):
        HK[a, c], HK[b, c] = HK[b, c], HK[a, c]
        HI[a, c], HI[b, c] = HI[b, c], HI[a, c]


swap = compiled(swap, nrt=False)


def _sift_down(HK, HI, n, i):
    """Move the entry at ``i`` down to its place among ``[:n]``.

    The entries it passes move up one level each and it is written once at
    the end: the same array as swapping it down level by level.
    """
    k0, k1, k2 = HK[i, 0], HK[i, 1], HK[i, 2]
    t, version, s = HI[i, 0], HI[i, 1], HI[i, 2]
    while True:
        c = 2 * i + 1
        if c >= n:
            break
        if c + 1 < n and before(HK[c + 1, 0], HK[c + 1, 1], HK[c + 1, 2], HK[c, 0], HK[c, 1], HK[c, 2]):
            c += 1
        if not before(HK[c, 0], HK[c, 1], HK[c, 2], k0, k1, k2):
            break
        for q in range(3):  # (no helper call in the loop: numba would count references to HK and HI)
            HK[i, q], HI[i, q] = HK[c, q], HI[c, q]
        i = c
    HK[i, 0], HK[i, 1], HK[i, 2] = k0, k1, k2
    HI[i, 0], HI[i, 1], HI[i, 2] = t, version, s


_sift_down = compiled(_sift_down, nrt=False)


def push(HK, HI, n, value, x, y, t, version, s):
    """Add an entry to the heap ``[:n]``, moving the entries above it down as in :func:`_sift_down`; the new size."""
    i = n
    while i > 0:
        parent = (i - 1) // 2
        if not before(-value, x, y, HK[parent, 0], HK[parent, 1], HK[parent, 2]):
            break
        for q in range(3):
            HK[i, q], HI[i, q] = HK[parent, q], HI[parent, q]
        i = parent
    HK[i, 0], HK[i, 1], HK[i, 2] = -value, x, y
    HI[i, 0], HI[i, 1], HI[i, 2] = t, version, s
    return n + 1


push = compiled(push, nrt=False)


def pop(HK, HI, n):
    """Remove the top (it is copied to row ``n - 1``); the new size."""
    swap(HK, HI, 0, n - 1)
    _sift_down(HK, HI, n - 1, 0)
    return n - 1


pop = compiled(pop, nrt=False)


def compact(HK, HI, n, ver, salive):
    """Drop the dead entries of the heap ``[:n]`` (lazy deletion's garbage) and restore the heap order; the new size."""
    k = 0
    for i in range(n):
        t, s = HI[i, 0], HI[i, 2]
        if ver[t] == HI[i, 1] and (s < 0 or salive[s]):
            HK[k], HI[k] = HK[i], HI[i]
            k += 1
    for i in range(k // 2 - 1, -1, -1):
        _sift_down(HK, HI, k, i)
    return k


compact = compiled(compact)


def grown(a, size):
    """``a`` in a zero-filled array of ``size`` rows."""
    out = np.zeros((size,) + a.shape[1:], dtype=a.dtype)
    out[: len(a)] = a
    return out


grown = compiled(grown)


def room(HK, HI, n, need, ver, salive):
    """The heap ``[:n]`` with room for ``need`` more entries: ``(HK, HI, n)``.

    When it is short of room, drops the dead entries (:func:`compact`), and
    if they still fill more than half of it, grows both arrays to twice their
    length plus ``need``.
    """
    if n + need > len(HK):
        n = compact(HK, HI, n, ver, salive)
        if 2 * (n + need) > len(HK):
            size = 2 * len(HK) + need
            HK, HI = grown(HK, size), grown(HI, size)
    return HK, HI, n


room = compiled(room)


def push_candidates(P, V, N, S, SA, SB, salive, n_segs, alive, ver, n_slots, t, lim, seen, HK, HI, nh):
    """Push the candidates of triangle ``t`` (its circumcentre, its constraint midpoints); the new heap size."""
    r, cx, cy, _ = visible_circumcentre(P, V, N, S, SA, SB, salive, n_segs, alive, n_slots, t, lim, seen)
    if r >= 0.0:
        nh = push(HK, HI, nh, r, cx, cy, t, ver[t], -1)
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
            nh = push(HK, HI, nh, value, mx, my, t, ver[t], s)
    return nh


push_candidates = compiled(push_candidates, nrt=False)


def insert_all(P0, T0, SEG0, lim):
    """Steps 3-4 on the CDT ``T0`` of ``P0`` with constraints ``SEG0``: ``(status, P, triangles, segments, values)``."""
    n = len(P0)
    SA, SB = SEG0[:, 0].copy(), SEG0[:, 1].copy()
    N, S, count = adjacency(T0, SA, SB, n)
    for s in range(len(SA)):
        if count[s] != 1:
            return -2 - s, P0, T0, SEG0, np.empty(0)
    P, V, n_slots, n_segs = P0.copy(), T0.copy(), len(T0), len(SA)
    salive = np.ones(len(SA), dtype=np.bool_)
    alive = np.ones(n_slots, dtype=np.bool_)
    ver = np.zeros(n_slots, dtype=np.int64)
    mark = np.zeros(n_slots, dtype=np.int64)
    free = np.empty(n_slots, dtype=np.int64)
    n_free = 0
    vfan = np.zeros(n, dtype=np.int64)
    vstamp = np.zeros(n, dtype=np.int64)
    values = np.zeros(n)
    cav = np.empty(CAVITY, dtype=np.int64)
    edges = np.empty((CAVITY + 2, 4), dtype=np.int64)
    slots = np.arange(n_slots)
    seen = np.empty(NEAR_TRIANGLES, dtype=np.int64)
    HK, HI = np.empty((0, 3)), np.empty((0, 3), dtype=np.int64)
    nh, m, stamp = 0, n_slots, 0
    while True:
        # Push the candidates of the new triangles slots[:m] (at first: every triangle), at most four each
        # (room only when short of room: a call at every pop made the engine 5 % slower).
        if nh + 4 * m > len(HK):
            HK, HI, nh = room(HK, HI, nh, 4 * m, ver, salive)
        for f in range(m):
            nh = push_candidates(
                P, V, N, S, SA, SB, salive, n_segs, alive, ver, n_slots, slots[f], lim, seen, HK, HI, nh
            )
        m = 0
        if nh == 0:
            break
        nh = pop(HK, HI, nh)
        t, version, s = HI[nh, 0], HI[nh, 1], HI[nh, 2]
        if ver[t] != version or (s >= 0 and not salive[s]):
            continue
        x, y = HK[nh, 1], HK[nh, 2]
        start = t
        if s < 0:
            r, _, _, start = visible_circumcentre(P, V, N, S, SA, SB, salive, n_segs, alive, n_slots, t, lim, seen)
            if r < 0.0:
                continue
        if n == len(P):
            P, values = grown(P, 2 * n), grown(values, 2 * n)
            vfan, vstamp = grown(vfan, 2 * n), grown(vstamp, 2 * n)
        if n_segs + 2 > len(SA):
            SA, SB, salive = grown(SA, 2 * len(SA) + 2), grown(SB, 2 * len(SB) + 2), grown(salive, 2 * len(SA) + 2)
        p = n
        P[p, 0], P[p, 1] = x, y
        values[p - len(P0)] = -HK[nh, 0]
        n += 1
        stamp += 1
        k = cavity(P, V, N, S, start, x, y, mark, stamp, cav)
        while k < 0:
            cav = grown(cav, 2 * len(cav))
            stamp += 1
            k = cavity(P, V, N, S, start, x, y, mark, stamp, cav)
        if k + 2 > len(edges):
            edges = grown(edges, 2 * k + 2)
        if k + 2 > len(slots):
            slots = grown(slots, 2 * k + 2)
        m = cavity_boundary(V, N, S, cav, k, s, mark, stamp, edges)
        if m < 0:
            return BROKEN, P, V, SEG0, values
        for i in range(k):
            alive[cav[i]] = False
            ver[cav[i]] += 1
            free[n_free] = cav[i]
            n_free += 1
        if m > n_free + len(V) - n_slots:
            size = 2 * len(V) + m
            V, N, S = grown(V, size), grown(N, size), grown(S, size)
            alive, ver, mark, free = grown(alive, size), grown(ver, size), grown(mark, size), grown(free, size)
        for f in range(m):
            if n_free > 0:
                n_free -= 1
                slots[f] = free[n_free]
            else:
                slots[f] = n_slots
                n_slots += 1
            alive[slots[f]] = True
        if not fill(P, V, N, S, edges, m, p, slots, vfan, vstamp, stamp):
            return BROKEN, P, V, SEG0, values
        if s >= 0:
            a, b = SA[s], SB[s]
            salive[s] = False
            SA[n_segs], SB[n_segs], salive[n_segs] = a, p, True
            SA[n_segs + 1], SB[n_segs + 1], salive[n_segs + 1] = p, b, True
            for f in range(m):
                t = slots[f]
                for e, w in ((1, V[t, 1]), (2, V[t, 0])):
                    if w == a:
                        S[t, e] = n_segs
                    elif w == b:
                        S[t, e] = n_segs + 1
            n_segs += 2
    live = np.flatnonzero(alive[:n_slots])
    segs = np.flatnonzero(salive[:n_segs])
    out_segments = np.empty((len(segs), 2), dtype=np.int64)
    out_segments[:, 0], out_segments[:, 1] = SA[segs], SB[segs]
    return OK, P[:n].copy(), V[live].copy(), out_segments, values[: n - len(P0)].copy()


insert_all = compiled(insert_all)


def limits(l):
    """The thresholds of the candidate rules for ``l`` and the reach of the distance search, the ``lim`` of
    :func:`visible_circumcentre`: ``(1 - REL_TOL) l, (1 + REL_TOL) l, REL_TOL l, SLIVER_GAP l, _REACH SLIVER_GAP l``."""
    return np.array([(1.0 - REL_TOL) * l, (1.0 + REL_TOL) * l, REL_TOL * l, SLIVER_GAP * l, _REACH * SLIVER_GAP * l])


def run(region, l):
    """Farthest-point insertion in ``region`` (Steps 3-5), fast engine; the same result as :func:`.reference.run`."""
    points = np.array(region.points, dtype=float).reshape(-1, 2)
    segments = np.array(region.segments, dtype=np.int64).reshape(-1, 2)
    triangles = constrained_delaunay(points, segments, region.holes)
    status, points, triangles, segments, values = insert_all(
        points, np.ascontiguousarray(triangles, dtype=np.int64), segments, limits(l)
    )
    if status == BROKEN:
        raise InternalError("fast engine: a Bowyer-Watson cavity did not re-triangulate (broken triangulation)")
    if status != OK:
        raise EquimeshError(
            f"the fast engine needs every constraint to bound the region, but segment {-2 - status} "
            "is an edge of zero or two triangles; use engine='reference'"
        )
    return Insertion(points, triangles, segments, len(region.points), values)
