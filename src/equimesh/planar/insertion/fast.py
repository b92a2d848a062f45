"""Fast engine: Steps 3-4 of Algorithm INCREMENT with an incremental CDT and a queue of candidates, compiled.

Same candidates, values, rules and tie-breaking as :mod:`.reference` (read
its docstring first); only the bookkeeping differs.

* The constrained Delaunay triangulation (CDT) is built once (Triangle, one
  call) and then updated point by point by constrained Bowyer-Watson
  (:mod:`._cdt`): the cavity starts at the triangle that contains the new
  point (found by the visibility walk, no global point location) and never
  crosses a constraint.  A constraint midpoint splits its segment in two.
* Every candidate belongs to one triangle (:mod:`.candidates`): its
  circumcentre and the midpoints of its constraint edges.  Inserting a point
  changes exactly the triangles of its cavity, so only their candidates die
  and only the fan's are new; a surviving triangle keeps its vertices, hence
  the same circumcentre bits and the same apex.  Candidates go into the
  queue of :mod:`.buckets` and :mod:`.heap`, largest value first, then
  smallest x, then smallest y, with the triangle slot's version: an entry
  whose triangle died (or whose segment was split) is skipped when it
  surfaces (lazy deletion).

Why the queue's first entry is the farthest point of Step 3.  The live entries are the
candidates of the current triangles, and those are exactly the candidates
the reference engine lists after re-triangulating from scratch (the CDT is
unique without four cocircular points, and circumcentres are computed by the
same float operations from the vertices in increasing index order, so they
have the same bits).  The queue's order is the reference's lexsort order:
largest value, then smallest x, then smallest y.  So the first live entry is
the reference's choice, and Step 4 stops when the queue holds no live entry:
only candidates of value at least ``(1 - REL_TOL) l`` are pushed.  A
circumcentre's visibility and its distance to the constraints (the
REL_TOL and SLIVER_GAP rules) are decided when it is pushed and decided
again when it surfaces, because a split constraint moves a little.  (One
difference remains: a circumcentre hidden behind a constraint that a later
split bends out of the way is not listed again unless its triangle changes.)

Visibility and the distance to the constraints are decided in
:mod:`.candidates`.

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
runtime explicitly (``nrt=True`` in :mod:`._predicates`).  The loop of
Steps 3-4 (:func:`advance`) is compiled so too: :func:`insert_all` makes
the arrays, and grows one by doubling whenever the loop stops short of room.

Memory: the arrays are made at once for Oler's bound on the points
(:func:`expected_points`), each triangle one cache line (:mod:`.arrays`).
The farthest point jumps across the region, so the next candidate's
triangle, then its points and neighbours, are prefetched while the current
point is inserted (:func:`.arrays.prefetch`; the heap's top is most likely
the next candidate).

numba's on-disk cache (``cache=True``) is keyed by the source file of each
compiled function, not by the functions it calls: after an edit of
:mod:`._cdt`, :mod:`._predicates`, :mod:`.candidates`, :mod:`.buckets`, :mod:`.heap` or
:mod:`.arrays` alone, the cached
:func:`insert_all`
still holds the old code.  Edit this file too (or delete ``__pycache__/*.nb*``)
whenever one of them changes.
"""

import numpy as np

from ..._jit import compiled
from ...errors import EquimeshError, InternalError, MeshTooLargeError
from ...mesh import triangle_orient
from .arrays import extended, grown, grown_store, prefetch, store_views, triangle_store
from .buckets import CHUNK, empty_queue, refill, spare_chunks
from .candidates import NEAR_TRIANGLES, limits, push_candidates, visible_circumcentre
from .cdt import adjacency, cavity, cavity_boundary, fill
from .heap import ENTRY, MAX_SLOTS, compact, entry_live, pop, push
from .region import Insertion, constrained_delaunay

#: Starting length of the cavity buffers (grown on demand).
CAVITY = 64

#: Returned by the compiled loop: done; else ``-2 - s`` for the first
#: segment ``s`` that is not an edge of exactly one triangle ...
OK = -1
#: ... or a Bowyer-Watson cavity produced a non-counter-clockwise fan (a bug) ...
BROKEN = -2 - 2**62
#: ... or the triangulation outgrew the heap's tags (:data:`.heap.MAX_SLOTS`).
TOO_LARGE = -3 - 2**62
#: :func:`advance` stopped short of room (never returned by :func:`insert_all`).
ROOM = -4 - 2**62

#: The scalars of :func:`advance` between its calls, one row each of an int64 array: points, triangle slots,
#: segments, free slots, heap entries, the new triangles whose candidates are still to be pushed, the cavity stamp,
#: the initial points, and after ROOM the array short of room and the rows it needs.
STATE = ("points", "slots", "segments", "free", "heap", "fan", "stamp", "initial", "short", "need")
POINTS, SLOTS, SEGMENTS, FREE, HEAP, FAN, STAMP, INITIAL, SHORT, NEED = range(len(STATE))
#: What ``state[SHORT]`` names: nothing, the heap, the points, the segments, the cavity, the fan, the triangles,
#: the buckets' chunks.
SHORT_NONE, SHORT_HEAP, SHORT_POINTS, SHORT_SEGMENTS, SHORT_CAVITY, SHORT_FAN, SHORT_TRIANGLES, SHORT_CHUNKS = range(8)


def grown_heap(H, size):
    """The heap array ``H`` in a zero-filled one of ``size`` rows."""
    out = np.zeros(size, dtype=ENTRY)
    out[: len(H)] = H
    return out


grown_heap = compiled(grown_heap)


def advance(
    P, V, N, S, SA, SB, salive, alive, ver, mark, free, vfan, vstamp, values, cav, edges, slots, seen, queue, lim, state
):
    """Steps 3-4 from ``state`` (:data:`STATE`) until no candidate is left: OK, BROKEN, or ROOM.

    ROOM: an array is too short for the next step, which is not taken (its
    candidate goes back into the heap); ``state[SHORT]`` names the array and
    ``state[NEED]`` the rows it needs, and the caller grows it and calls again.
    Compiled without reference counting, so the loop allocates nothing.
    """
    n, n_slots, n_segs, n_free = state[POINTS], state[SLOTS], state[SEGMENTS], state[FREE]
    nh, m, stamp, n0 = state[HEAP], state[FAN], state[STAMP], state[INITIAL]
    H, pool, link, table, q = queue
    status = OK
    while True:
        # Queue the candidates of the new triangles slots[:m] (at first: every triangle), at most four each.
        if nh + 4 * m >= len(H):
            nh = compact(H, nh, ver, S, salive)
            if 2 * (nh + 4 * m) >= len(H):
                status, state[SHORT], state[NEED] = ROOM, SHORT_HEAP, 2 * len(H) + 4 * m
                break
        if spare_chunks(link, q) < 4 * m:
            status, state[SHORT], state[NEED] = ROOM, SHORT_CHUNKS, 2 * len(link) + 4 * m
            break
        for f in range(m):
            nh = push_candidates(
                P, V, N, S, SA, SB, salive, n_segs, alive, ver, n_slots, slots[f], lim, seen, queue, nh
            )
        m = 0
        if nh == 0:
            nh, need = refill(H, pool, link, table, q, ver, S, salive)
            if need > 0:
                status, state[SHORT], state[NEED] = ROOM, SHORT_HEAP, max(2 * len(H), need)
                break
            if nh == 0:
                break
        nh = pop(H, nh)
        if nh > 0:  # most likely the next candidate: its triangle's row, while this one is inserted
            prefetch(V, H[0]["tag"] >> 2)
        if not entry_live(H, nh, ver, S, salive):
            continue
        tag, version, value, x, y = H[nh]["tag"], H[nh]["version"], -H[nh]["key"], H[nh]["x"], H[nh]["y"]
        t, e = tag >> 2, (tag & 3) - 1
        s = S[t, e] if e >= 0 else -1
        start = t
        if s < 0:
            r, _, _, start = visible_circumcentre(P, V, N, S, SA, SB, salive, n_segs, alive, n_slots, t, lim, seen)
            if r < 0.0:
                continue
        stamp += 1
        k = cavity(P, V, N, S, start, x, y, mark, stamp, cav) if n < len(P) and n_segs + 2 <= len(SA) else 0
        short, need = SHORT_NONE, 0
        if n == len(P):
            short, need = SHORT_POINTS, 2 * n
        elif n_segs + 2 > len(SA):
            short, need = SHORT_SEGMENTS, 2 * len(SA) + 2
        elif k < 0:
            short, need = SHORT_CAVITY, 2 * len(cav)
        elif k + 2 > len(edges) or k + 2 > len(slots):
            short, need = SHORT_FAN, 2 * k + 2
        else:
            m = cavity_boundary(V, N, S, cav, k, s, mark, stamp, edges)
            if m < 0:
                status = BROKEN
                break
            if m > n_free + k + len(V) - n_slots:
                short, need, m = SHORT_TRIANGLES, 2 * len(V) + m, 0
        if short != SHORT_NONE:
            nh = push(H, nh, value, x, y, tag, version)
            status, state[SHORT], state[NEED] = ROOM, short, need
            break
        p = n
        P[p, 0], P[p, 1] = x, y
        values[p - n0] = value
        n += 1
        for i in range(k):
            alive[cav[i]] = False
            ver[cav[i]] += 1
            free[n_free] = cav[i]
            n_free += 1
        for f in range(m):
            if n_free > 0:
                n_free -= 1
                slots[f] = free[n_free]
            else:
                slots[f] = n_slots
                mark[n_slots], ver[n_slots] = 0, 0
                n_slots += 1
            alive[slots[f]] = True
        if not fill(P, V, N, S, edges, m, p, slots, vfan, vstamp, stamp):
            status = BROKEN
            break
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
        if nh > 0:  # the next candidate's triangle has arrived by now: ask for its points and neighbours
            t = H[0]["tag"] >> 2
            for e in range(3):
                prefetch(P, V[t, e])
                if N[t, e] >= 0:
                    prefetch(V, N[t, e])
    state[POINTS], state[SLOTS], state[SEGMENTS], state[FREE] = n, n_slots, n_segs, n_free
    state[HEAP], state[FAN], state[STAMP] = nh, m, stamp
    return status


advance = compiled(advance, nrt=False)


def insert_all(P0, T0, SEG0, lim, points=0, room=CAVITY):
    """Steps 3-4 on the CDT ``T0`` of ``P0`` with constraints ``SEG0``: ``(status, P, triangles, segments, values)``.

    ``points``: the expected number of points at the end, for which the
    arrays are made at once (they grow by doubling beyond it).  ``room``
    (at least 1): the triangles a cavity may hold before its buffers grow, and in the heap
    four candidates each beyond those of ``T0``.  Rows of triangles and
    points are written in full when first used, so the arrays are not
    initialised beyond the input.
    """
    n = len(P0)
    SA0, SB0 = SEG0[:, 0].copy(), SEG0[:, 1].copy()
    N0, S0, count = adjacency(T0, SA0, SB0, n)
    for s in range(len(SA0)):
        if count[s] != 1:
            return -2 - s, P0, T0, SEG0, np.empty(0)
    points = max(points, n + 1)
    rows = len(T0) + 2 * (points - n)  # an insertion adds two triangles (one on a constraint)
    T = triangle_store(rows)
    V, N, S, mark, ver, alive = store_views(T)
    V[: len(T0)], N[: len(T0)], S[: len(T0)] = T0, N0, S0
    mark[: len(T0)], ver[: len(T0)], alive[: len(T0)] = 0, 0, 1
    P, free = extended(P0, points), np.empty(rows, dtype=np.int64)
    W, values = np.zeros((points, 2), dtype=np.int64), np.empty(points)  # per point: its fan triangle, its stamp
    SA, SB = extended(SA0, 2 * len(SA0) + 2), extended(SB0, 2 * len(SA0) + 2)
    salive = grown(np.ones(len(SA0), dtype=np.bool_), len(SA))
    cav = np.empty(room, dtype=np.int64)
    edges = np.empty((max(room, len(T0)) + 2, 4), dtype=np.int64)
    slots = extended(np.arange(len(T0)), len(edges))
    seen = np.empty(NEAR_TRIANGLES, dtype=np.int64)
    H, pool, link, table, q = empty_queue(4 * len(T0) + 4 * room + 1, (4 * len(T0) + 2 * points) // CHUNK + 1, lim[0])
    state = np.zeros(len(STATE), dtype=np.int64)
    state[POINTS], state[SLOTS], state[SEGMENTS], state[FAN], state[INITIAL] = n, len(T0), len(SA0), len(T0), n
    status = ROOM
    while status == ROOM:
        work = (P, V, N, S, SA, SB, salive, alive, ver, mark, free, W[:, 0], W[:, 1], values, cav, edges, slots)
        status = advance(*work, seen, (H, pool, link, table, q), lim, state)
        short, need = state[SHORT], state[NEED]
        if status != ROOM:
            break
        if short == SHORT_HEAP:
            H = grown_heap(H, need)
        elif short == SHORT_CHUNKS:
            pool, link = extended(pool, need * CHUNK), extended(link, need)
        elif short == SHORT_POINTS:
            if need > MAX_SLOTS // 2:
                return TOO_LARGE, P0, T0, SEG0, values
            P, W, values = extended(P, need), grown(W, need), extended(values, need)
        elif short == SHORT_SEGMENTS:
            SA, SB, salive = extended(SA, need), extended(SB, need), grown(salive, need)
        elif short == SHORT_CAVITY:
            cav = extended(cav, need)
        elif short == SHORT_FAN:
            edges, slots = extended(edges, need), extended(slots, need)
        else:
            if need > MAX_SLOTS:
                return TOO_LARGE, P0, T0, SEG0, values
            T, free = grown_store(T, need, state[SLOTS]), extended(free, need)
            V, N, S, mark, ver, alive = store_views(T)
    n, n_slots, n_segs = state[POINTS], state[SLOTS], state[SEGMENTS]
    if status == BROKEN:
        return BROKEN, P0, T0, SEG0, values
    live = np.flatnonzero(alive[:n_slots])
    segs = np.flatnonzero(salive[:n_segs])
    out_segments = np.empty((len(segs), 2), dtype=np.int64)
    out_segments[:, 0], out_segments[:, 1] = SA[segs], SB[segs]
    triangles = np.empty((len(live), 3), dtype=np.int64)
    triangles[:] = V[live]
    return OK, P[:n].copy(), triangles, out_segments, values[: n - len(P0)].copy()


insert_all = compiled(insert_all)


def expected_points(points, segments, triangles, l):
    """Oler's bound on points pairwise ``l`` apart (:func:`equimesh.planar.limits.node_estimate`) for the region
    triangulated by ``triangles``, bounded by ``segments``: the engine's arrays are made for this many points."""
    from ..limits import node_estimate  # (here: the limits import the engines)

    area = 0.5 * float(np.sum(np.abs(triangle_orient(points, triangles))))
    perimeter = float(np.sum(np.linalg.norm(points[segments[:, 1]] - points[segments[:, 0]], axis=1)))
    return int(min(node_estimate(area, perimeter, l), MAX_SLOTS // 2))


def run(region, l):
    """Farthest-point insertion in ``region`` (Steps 3-5), fast engine; the same result as :func:`.reference.run`."""
    points = np.array(region.points, dtype=float).reshape(-1, 2)
    segments = np.array(region.segments, dtype=np.int64).reshape(-1, 2)
    triangles = constrained_delaunay(points, segments, region.holes)
    status, points, triangles, segments, values = insert_all(
        points,
        np.ascontiguousarray(triangles, dtype=np.int64),
        segments,
        limits(l),
        expected_points(points, segments, triangles, l),
    )
    if status == BROKEN:
        raise InternalError("fast engine: a Bowyer-Watson cavity did not re-triangulate (broken triangulation)")
    if status == TOO_LARGE:
        raise MeshTooLargeError(
            f"the fast engine holds at most {MAX_SLOTS // 2} points and {MAX_SLOTS} triangles, "
            "and this region needs more; use a larger l"
        )
    if status != OK:
        raise EquimeshError(
            f"the fast engine needs every constraint to bound the region, but segment {-2 - status} "
            "is an edge of zero or two triangles; use engine='reference'"
        )
    return Insertion(points, triangles, segments, len(region.points), values)
