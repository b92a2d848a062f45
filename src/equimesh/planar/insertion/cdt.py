"""Compiled constrained Delaunay triangulation (CDT) operations of the fast engine.

Triangles live in slots of three arrays: ``V[t]`` its vertices counter-
clockwise, ``N[t, e]`` the triangle across edge ``e = (V[t, e], V[t, e+1])``
(-1 for none) and ``S[t, e]`` the constraint segment that edge lies on (-1
for none).  Every sign is decided by the exact predicates of
:mod:`._predicates`.

* :func:`adjacency` turns the initial CDT (from Triangle) into these arrays;
* :func:`walk` follows the segment from a triangle's centroid to its
  circumcentre and decides the reference engine's visibility test (does the
  closed segment touch a constraint?) locally, returning the triangle that
  contains the circumcentre;
* :func:`cavity` and :func:`fill` insert a point by Bowyer-Watson: the
  cavity is every triangle whose circumcircle strictly contains the point,
  grown from the triangle containing it across non-constraint edges only, so
  a constraint is never crossed (constrained Bowyer-Watson gives the CDT of
  the new point set, Definition 1 of the paper); the cavity is then
  re-filled with a fan of triangles from the point.

Every function but :func:`adjacency` is compiled without numba's reference
counting (``nrt=False``; the reason is in :mod:`.fast`).
"""

import numpy as np

from ..._jit import compiled
from .predicates import incircle, orient2d


def adjacency(V, SA, SB, n_points):
    """``(N, S, count)`` for triangles ``V``; ``count[s]`` = triangles that have segment ``s`` as an edge."""
    nt = V.shape[0]
    keys = np.empty(3 * nt, dtype=np.int64)
    for t in range(nt):
        for e in range(3):
            keys[3 * t + e] = V[t, e] * n_points + V[t, (e + 1) % 3]
    order = np.argsort(keys, kind="mergesort")
    skeys = keys[order]
    N = np.full((nt, 3), -1, dtype=np.int64)
    S = np.full((nt, 3), -1, dtype=np.int64)
    for t in range(nt):
        for e in range(3):
            twin = V[t, (e + 1) % 3] * n_points + V[t, e]
            pos = np.searchsorted(skeys, twin)
            if pos < len(skeys) and skeys[pos] == twin:
                N[t, e] = order[pos] // 3
    count = np.zeros(len(SA), dtype=np.int64)
    for s in range(len(SA)):
        for key in (SA[s] * n_points + SB[s], SB[s] * n_points + SA[s]):
            pos = np.searchsorted(skeys, key)
            if pos < len(skeys) and skeys[pos] == key:
                h = order[pos]
                S[h // 3, h % 3] = s
                count[s] += 1
    return N, S, count


adjacency = compiled(adjacency)


def walk(P, V, N, S, t, gx, gy, cx, cy, max_steps):
    """Walk from ``g`` (inside triangle ``t``) towards ``c``: ``(status, triangle)``.

    status 1: the closed segment ``gc`` touches no constraint and ``c`` lies
    in the returned (closed) triangle; 0: it touches a constraint; -1: a
    degenerate case (``g`` not strictly inside ``t``, the line ``gc``
    through a vertex, ``c`` on a vertex) that the caller decides by brute
    force.  The segment meets triangle edges only where it crosses them and
    every constraint is a union of edges, so it touches a constraint exactly
    when it crosses a constraint edge or ends on one.
    """
    for e in range(3):
        i, j = V[t, e], V[t, (e + 1) % 3]
        if orient2d(P[i, 0], P[i, 1], P[j, 0], P[j, 1], gx, gy) <= 0.0:
            return -1, -1
    for _ in range(max_steps):
        o0, o1, o2 = _edge_sides(P, V, t, cx, cy)
        if o0 >= 0.0 and o1 >= 0.0 and o2 >= 0.0:
            zeros = int(o0 == 0.0) + int(o1 == 0.0) + int(o2 == 0.0)
            if zeros == 0:
                return 1, t
            if zeros > 1:
                return -1, -1
            e = 0 if o0 == 0.0 else (1 if o1 == 0.0 else 2)
            return (0 if S[t, e] >= 0 else 1), t
        a, b, c = V[t, 0], V[t, 1], V[t, 2]
        s0 = orient2d(gx, gy, cx, cy, P[a, 0], P[a, 1])
        s1 = orient2d(gx, gy, cx, cy, P[b, 0], P[b, 1])
        s2 = orient2d(gx, gy, cx, cy, P[c, 0], P[c, 1])
        if s0 == 0.0 or s1 == 0.0 or s2 == 0.0:
            return -1, -1
        # The edge the segment leaves t by: its start vertex right of the line gc, its end vertex left.
        if s2 < 0.0 and s0 > 0.0:
            out, o_out = 2, o2
        elif s1 < 0.0 and s2 > 0.0:
            out, o_out = 1, o1
        elif s0 < 0.0 and s1 > 0.0:
            out, o_out = 0, o0
        else:
            return -1, -1
        if o_out >= 0.0:
            return -1, -1
        if S[t, out] >= 0:
            return 0, t
        t = N[t, out]
        if t < 0:
            return -1, -1
    return -1, -1


walk = compiled(walk, nrt=False)


def _edge_sides(P, V, t, x, y):
    """``orient`` of each edge ``e`` of triangle ``t`` with the point: all >= 0 when the closed triangle contains it."""
    a, b, c = V[t, 0], V[t, 1], V[t, 2]
    ax, ay, bx, by, cx, cy = P[a, 0], P[a, 1], P[b, 0], P[b, 1], P[c, 0], P[c, 1]
    return orient2d(ax, ay, bx, by, x, y), orient2d(bx, by, cx, cy, x, y), orient2d(cx, cy, ax, ay, x, y)


_edge_sides = compiled(_edge_sides, nrt=False)


def _on_segment(sx, sy, tx, ty, rx, ry, d):
    return d == 0.0 and min(sx, tx) <= rx <= max(sx, tx) and min(sy, ty) <= ry <= max(sy, ty)


_on_segment = compiled(_on_segment, nrt=False)


def segments_touch(px, py, qx, qy, ax, ay, bx, by):
    """Whether closed segments ``pq`` and ``ab`` share a point; :func:`equimesh._geometry.segments_intersect`.

    Segments whose bounding boxes are disjoint are answered by comparisons alone.
    """
    if max(px, qx) < min(ax, bx) or max(ax, bx) < min(px, qx) or max(py, qy) < min(ay, by) or max(ay, by) < min(py, qy):
        return False
    d1 = np.sign(orient2d(ax, ay, bx, by, px, py))
    d2 = np.sign(orient2d(ax, ay, bx, by, qx, qy))
    d3 = np.sign(orient2d(px, py, qx, qy, ax, ay))
    d4 = np.sign(orient2d(px, py, qx, qy, bx, by))
    if d1 * d2 < 0 and d3 * d4 < 0:
        return True
    return (
        _on_segment(ax, ay, bx, by, px, py, d1)
        or _on_segment(ax, ay, bx, by, qx, qy, d2)
        or _on_segment(px, py, qx, qy, ax, ay, d3)
        or _on_segment(px, py, qx, qy, bx, by, d4)
    )


segments_touch = compiled(segments_touch, nrt=False)


def locate(P, V, N, alive, n_slots, start, x, y, max_steps):
    """The lowest live slot whose closed triangle contains ``(x, y)``, or -1.

    Walks from triangle ``start``, each step across the first edge that has
    the point strictly on its outer side (a visibility walk), to a triangle
    containing the point; the answer is the lower of it and, when the point
    lies on one of its edges, the triangle across that edge: those are all
    the triangles containing it.  When the walk leaves the triangulation,
    runs out of steps or stops with the point on a vertex, every slot is
    scanned instead; the answer is the same.
    """
    t = start
    for _ in range(max_steps):
        o0, o1, o2 = _edge_sides(P, V, t, x, y)
        if o0 >= 0.0 and o1 >= 0.0 and o2 >= 0.0:
            zeros = int(o0 == 0.0) + int(o1 == 0.0) + int(o2 == 0.0)
            if zeros == 0:
                return t
            if zeros > 1:
                break
            n = N[t, 0 if o0 == 0.0 else (1 if o1 == 0.0 else 2)]
            return t if n < 0 else min(t, n)
        t = N[t, 0 if o0 < 0.0 else (1 if o1 < 0.0 else 2)]
        if t < 0:
            break
    for t in range(n_slots):
        if alive[t]:
            o0, o1, o2 = _edge_sides(P, V, t, x, y)
            if o0 >= 0.0 and o1 >= 0.0 and o2 >= 0.0:
                return t
    return -1


locate = compiled(locate, nrt=False)


def cavity(P, V, N, S, start, px, py, mark, stamp, cav):
    """Bowyer-Watson cavity of point ``p`` from triangle ``start``: its slots in ``cav[:k]``; returns ``k``.

    ``start`` is always in the cavity; a neighbour joins when it is across
    a non-constraint edge and ``p`` is strictly inside its circumcircle.
    Members get ``mark[t] = stamp``.  Returns -1 if ``cav`` is too short
    (the caller grows it and starts again with a new stamp).
    """
    mark[start] = stamp
    cav[0] = start
    k = 1
    i = 0
    while i < k:
        t = cav[i]
        i += 1
        for e in range(3):
            n = N[t, e]
            if S[t, e] >= 0 or n < 0 or mark[n] == stamp:
                continue
            a, b, c = V[n, 0], V[n, 1], V[n, 2]
            if incircle(P[a, 0], P[a, 1], P[b, 0], P[b, 1], P[c, 0], P[c, 1], px, py) > 0.0:
                if k == len(cav):
                    return -1
                mark[n] = stamp
                cav[k] = n
                k += 1
    return k


cavity = compiled(cavity, nrt=False)


def cavity_boundary(V, N, S, cav, k, split, mark, stamp, edges):
    """Boundary edges of the cavity ``cav[:k]`` (without the split segment), rows ``(u, v, outer, segment)``.

    Returns their number, or -1 if a constraint has the cavity on both sides
    (the engine requires every constraint to bound the region) or there are
    more than ``len(edges)`` (more than ``k + 2``: not a triangulated disc).
    """
    m = 0
    for i in range(k):
        t = cav[i]
        for e in range(3):
            s, n = S[t, e], N[t, e]
            if s >= 0 and s == split:
                continue
            inside = n >= 0 and mark[n] == stamp
            if inside and s >= 0:
                return -1
            if not inside:
                if m == len(edges):
                    return -1
                edges[m, 0], edges[m, 1], edges[m, 2], edges[m, 3] = V[t, e], V[t, (e + 1) % 3], n, s
                m += 1
    return m


cavity_boundary = compiled(cavity_boundary, nrt=False)


def fill(P, V, N, S, edges, m, p, slots, vfan, vstamp, stamp):
    """Fan triangles ``(u, v, p)`` over the cavity boundary ``edges[:m]`` into ``slots[:m]``.

    Links them to the outside and to each other; returns False when a fan
    triangle is not strictly counter-clockwise or a boundary vertex repeats
    (a broken cavity: the caller raises InternalError).
    """
    px, py = P[p, 0], P[p, 1]
    for f in range(m):
        t, u, v, outer = slots[f], edges[f, 0], edges[f, 1], edges[f, 2]
        if orient2d(P[u, 0], P[u, 1], P[v, 0], P[v, 1], px, py) <= 0.0 or vstamp[u] == stamp:
            return False
        vstamp[u] = stamp
        vfan[u] = t
        V[t, 0], V[t, 1], V[t, 2] = u, v, p
        N[t, 0], N[t, 1], N[t, 2] = outer, -1, -1
        S[t, 0], S[t, 1], S[t, 2] = edges[f, 3], -1, -1
        if outer >= 0:
            for j in range(3):
                if V[outer, j] == v and V[outer, (j + 1) % 3] == u:
                    N[outer, j] = t
    for f in range(m):
        v = edges[f, 1]
        if vstamp[v] == stamp:
            g = vfan[v]
            N[slots[f], 1] = g
            N[g, 2] = slots[f]
    return True


fill = compiled(fill, nrt=False)
