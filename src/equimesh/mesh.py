"""The planar mesh value object returned by Problem 1 and Problem 2."""

from dataclasses import dataclass, field

import numpy as np

from ._geometry import Frame
from ._jit import compiled

#: Edge group labels.  ``G1`` is the paper's "group of edges that have the same
#: length on the plane": lattice edges of length exactly l (Problem 2).
OTHER = 0
G1 = 1


def half_edges(triangles):
    """Directed edges ``(3M, 2)`` of a triangle array: all (0, 1) sides, then (1, 2), then (2, 0)."""
    t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    return np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])


def edge_keys(edges, n=None):
    """``(keys, n)``: one int64 ``min * n + max`` per edge ``(E, 2)`` (``n`` above every index, by default the largest
    index plus one), ordered like the sorted rows."""
    e = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    if n is None:
        n = int(e.max()) + 1 if e.size else 1
    return np.minimum(e[:, 0], e[:, 1]) * n + np.maximum(e[:, 0], e[:, 1]), n


def single_edges(triangles):
    """Directed edges ``(B, 2)`` of ``triangles`` that belong to exactly one triangle (the boundary), in the order of
    :func:`half_edges`, each as its triangle runs it."""
    directed = half_edges(triangles)
    _, inverse, counts = np.unique(edge_keys(directed)[0], return_inverse=True, return_counts=True)
    return directed[counts[inverse] == 1]


def unique_edges(triangles):
    """Sorted unique undirected edges ``(E, 2)`` of a triangle array.

    Sorted through one int64 key ``min * n + max`` per edge (as
    :func:`edge_keys`, built column by column): a 1-D sort, far faster than
    ``np.unique(..., axis=0)`` at a million points; the keys and the pairs are
    made by compiled loops (numpy's temporaries cost more than the sort).
    """
    t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    if not t.size:
        return np.empty((0, 2), dtype=np.int64)
    n = int(t.max()) + 1
    keys = _side_keys(t, n)
    keys.sort()
    return _distinct_pairs(keys, n)


def _side_keys(t, n):
    keys = np.empty(3 * len(t), dtype=np.int64)
    for k in range(3):
        i, j = (0, 1) if k == 0 else ((1, 2) if k == 1 else (2, 0))
        for r in range(len(t)):
            a, b = t[r, i], t[r, j]
            keys[k * len(t) + r] = min(a, b) * n + max(a, b)
    return keys


_side_keys = compiled(_side_keys)


def _distinct_pairs(keys, n):
    """The rows ``(key // n, key % n)`` of the distinct values of the sorted ``keys``."""
    count = 0
    for r in range(len(keys)):
        count += int(r == 0 or keys[r] != keys[r - 1])
    edges = np.empty((count, 2), dtype=np.int64)
    count = 0
    for r in range(len(keys)):
        if r == 0 or keys[r] != keys[r - 1]:
            edges[count, 0] = keys[r] // n
            edges[count, 1] = keys[r] - edges[count, 0] * n
            count += 1
    return edges


_distinct_pairs = compiled(_distinct_pairs)


def edge_lengths(points, edges):
    """Euclidean lengths of ``edges`` (E, 2) between rows of ``points`` (N, d), d = 2 or 3.

    The same floats as ``np.linalg.norm(q - p, axis=1)`` (the squares summed
    in coordinate order), in a compiled loop (gathering the rows took several
    times longer at a million edges).
    """
    points = np.asarray(points, dtype=float)
    return _edge_lengths(np.ascontiguousarray(points), np.asarray(edges, dtype=np.int64).reshape(-1, 2))


def _edge_lengths(points, edges):
    out = np.empty(len(edges))
    for k in range(len(edges)):
        i, j = edges[k, 0], edges[k, 1]
        total = 0.0
        for c in range(points.shape[1]):
            d = points[j, c] - points[i, c]
            total += d * d
        out[k] = np.sqrt(total)
    return out


_edge_lengths = compiled(_edge_lengths)


def triangle_orient(points, triangles):
    """Twice the signed area of each triangle (> 0 counter-clockwise), over the first two coordinates of ``points``.

    The floats of :func:`equimesh._geometry.orient` on the triangles'
    corners, in a compiled loop (the solver's guards call it at every step;
    gathering rows at a million triangles took several times longer).
    """
    return _triangle_orient(np.asarray(points, dtype=float), np.asarray(triangles, dtype=np.int64).reshape(-1, 3))


def _triangle_orient(points, triangles):
    out = np.empty(len(triangles))
    for t in range(len(triangles)):
        a, b, c = triangles[t, 0], triangles[t, 1], triangles[t, 2]
        ax, ay = points[a, 0], points[a, 1]
        out[t] = (points[b, 0] - ax) * (points[c, 1] - ay) - (points[b, 1] - ay) * (points[c, 0] - ax)
    return out


_triangle_orient = compiled(_triangle_orient)


def boundary_ring(segments, start):
    """Walk oriented constraint segments forming one closed ring, from vertex ``start``."""
    successor = dict(zip(segments[:, 0].tolist(), segments[:, 1].tolist()))
    ring = [start]
    while (nxt := successor[ring[-1]]) != start:
        ring.append(nxt)
    return np.array(ring, dtype=np.int64)


def boundary_first(segments, n_points, starts=(0,)):
    """Renumbering that puts the boundary rings through vertices ``starts`` first, then the other points in order.

    Returns ``(order, inverse, n_ring)``: new point ``k`` is old point
    ``order[k]``, old point ``i`` becomes ``inverse[i]``; ``n_ring`` is the
    number of points on the rings (one ring per start, in that order).
    """
    ring = np.concatenate([boundary_ring(segments, start=int(s)) for s in starts])
    rest = np.ones(n_points, dtype=bool)
    rest[ring] = False
    order = np.concatenate([ring, np.flatnonzero(rest)])
    inverse = np.empty_like(order)
    inverse[order] = np.arange(len(order))
    return order, inverse, len(ring)


def counter_clockwise(points, triangles):
    """Return ``triangles`` with every row reordered to counter-clockwise."""
    t = np.array(triangles, dtype=np.int64, copy=True).reshape(-1, 3)
    cw = np.flatnonzero(triangle_orient(points, t) < 0)
    t[cw] = t[cw][:, [0, 2, 1]]
    return t


@dataclass(frozen=True)
class PlanarMesh:
    """A triangulation of a planar polygon.

    Attributes
    ----------
    points : (N, 2) float array, in the caller's coordinates.
    triangles : (M, 3) int array, each counter-clockwise.
    edges : (E, 2) int array, unique, each row sorted, rows sorted.
    edge_groups : (E,) int8 array, :data:`G1` or :data:`OTHER` per edge.
    length : the target length l the mesh was built for.
    n_boundary : number of leading points that lie on the polygon boundary.
    frame : the :class:`~equimesh._geometry.Frame` the mesh was built in, or None.
    local_points : (N, 2) float array, the points in ``frame`` (None without a frame).

    Precision: the guarantees (Theorems 1 and 3) hold exactly, to REL_TOL, for
    the local points; :meth:`edge_lengths` and :meth:`triangle_areas` are
    computed from them (divided by the power-of-two scale, which is exact).
    ``points`` carry one more rounding of about ``ulp(|frame.origin|)``.
    """

    points: np.ndarray
    triangles: np.ndarray
    edges: np.ndarray
    edge_groups: np.ndarray
    length: float
    n_boundary: int
    info: dict = field(default_factory=dict, compare=False)
    frame: Frame = field(default=None, compare=False)
    local_points: np.ndarray = field(default=None, compare=False, repr=False)

    @classmethod
    def build(cls, points, triangles, length, n_boundary, g1_edges=None, info=None, frame=None, pinned=None):
        """Assemble a mesh: orient triangles, extract edges, label ``g1_edges`` (pairs) as G1.

        With a ``frame``, ``points`` are local coordinates in it; ``pinned``
        (``(local_rows, caller_rows)``, e.g. the polygon's vertices) gives the
        exact caller coordinates of the points equal to ``local_rows``, which
        mapping back would round.
        """
        local = np.asarray(points, dtype=float)
        triangles = counter_clockwise(local, triangles)
        edges = unique_edges(triangles)
        groups = np.full(len(edges), OTHER, dtype=np.int8)
        if g1_edges is not None and len(g1_edges):
            g1 = np.sort(np.asarray(g1_edges, dtype=np.int64), axis=1)
            groups[_rows_in(edges, g1)] = G1
        caller = local if frame is None else frame.to_caller(local)
        if pinned is not None:
            pinned_local = np.asarray(pinned[0], dtype=float)
            where = {row.tobytes(): k for k, row in enumerate(pinned_local)}
            # Only rows whose x equals a pinned x can match: a vectorised filter, then the exact (bitwise) lookup.
            for i in np.flatnonzero(np.isin(local[:, 0], pinned_local[:, 0])):
                k = where.get(local[i].tobytes())
                if k is not None:
                    caller[i] = pinned[1][k]
        return cls(
            caller,
            triangles,
            edges,
            groups,
            float(length),
            int(n_boundary),
            info or {},
            frame,
            None if frame is None else local,
        )

    @property
    def n_nodes(self):
        return len(self.points)

    @property
    def local(self):
        """``(points, scale)``: the points the guarantees hold for, and the scale from caller lengths to them."""
        if self.frame is None:
            return self.points, 1.0
        return self.local_points, self.frame.scale

    def edge_lengths(self):
        points, scale = self.local
        return edge_lengths(points, self.edges) / scale

    @property
    def g1_mask(self):
        return self.edge_groups == G1

    def triangle_areas(self):
        p, scale = self.local
        return 0.5 * triangle_orient(p, self.triangles) / scale**2


def _rows_in(rows, table):
    """Boolean mask: which rows of ``rows`` (E, 2) occur in ``table`` (K, 2)."""
    return np.isin(_edge_key(rows), _edge_key(table))


def _edge_key(pairs):
    return pairs[:, 0] * (1 << 32) + pairs[:, 1]
