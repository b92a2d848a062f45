"""The planar mesh value object returned by Problem 1 and Problem 2."""

from dataclasses import dataclass, field

import numpy as np

from ._geometry import orient

#: Edge group labels.  ``G1`` is the paper's "group of edges that have the same
#: length on the plane": lattice edges of length exactly l (Problem 2).
OTHER = 0
G1 = 1


def half_edges(triangles):
    """Directed edges ``(3M, 2)`` of a triangle array: all (0, 1) sides, then (1, 2), then (2, 0)."""
    t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    return np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])


def unique_edges(triangles):
    """Sorted unique undirected edges ``(E, 2)`` of a triangle array."""
    return np.unique(np.sort(half_edges(triangles), axis=1), axis=0)


def edge_lengths(points, edges):
    """Euclidean lengths of ``edges`` (E, 2) between rows of ``points`` (N, d), d = 2 or 3."""
    points = np.asarray(points, dtype=float)
    edges = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    return np.linalg.norm(points[edges[:, 1]] - points[edges[:, 0]], axis=1)


def boundary_ring(segments, start):
    """Walk oriented constraint segments forming one closed ring, from vertex ``start``."""
    successor = dict(zip(segments[:, 0].tolist(), segments[:, 1].tolist()))
    ring = [start]
    while (nxt := successor[ring[-1]]) != start:
        ring.append(nxt)
    return np.array(ring, dtype=np.int64)


def boundary_first(segments, n_points):
    """Renumbering that puts the boundary ring through vertex 0 first, then the other points in order.

    Returns ``(order, inverse, n_ring)``: new point ``k`` is old point
    ``order[k]``, old point ``i`` becomes ``inverse[i]``.
    """
    ring = boundary_ring(segments, start=0)
    order = np.concatenate([ring, np.setdiff1d(np.arange(n_points), ring)])
    inverse = np.empty_like(order)
    inverse[order] = np.arange(len(order))
    return order, inverse, len(ring)


def counter_clockwise(points, triangles):
    """Return ``triangles`` with every row reordered to counter-clockwise."""
    t = np.array(triangles, dtype=np.int64, copy=True).reshape(-1, 3)
    p = np.asarray(points)
    cw = orient(p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]) < 0
    t[cw] = t[cw][:, [0, 2, 1]]
    return t


@dataclass(frozen=True)
class PlanarMesh:
    """A triangulation of a planar polygon.

    Attributes
    ----------
    points : (N, 2) float array.
    triangles : (M, 3) int array, each counter-clockwise.
    edges : (E, 2) int array, unique, each row sorted, rows sorted.
    edge_groups : (E,) int8 array, :data:`G1` or :data:`OTHER` per edge.
    length : the target length l the mesh was built for.
    n_boundary : number of leading points that lie on the polygon boundary.
    """

    points: np.ndarray
    triangles: np.ndarray
    edges: np.ndarray
    edge_groups: np.ndarray
    length: float
    n_boundary: int
    info: dict = field(default_factory=dict, compare=False)

    @classmethod
    def build(cls, points, triangles, length, n_boundary, g1_edges=None, info=None):
        """Assemble a mesh: orient triangles, extract edges, label ``g1_edges`` (pairs) as G1."""
        points = np.asarray(points, dtype=float)
        triangles = counter_clockwise(points, triangles)
        edges = unique_edges(triangles)
        groups = np.full(len(edges), OTHER, dtype=np.int8)
        if g1_edges is not None and len(g1_edges):
            g1 = np.sort(np.asarray(g1_edges, dtype=np.int64), axis=1)
            groups[_rows_in(edges, g1)] = G1
        return cls(points, triangles, edges, groups, float(length), int(n_boundary), info or {})

    @property
    def n_nodes(self):
        return len(self.points)

    def edge_lengths(self):
        return edge_lengths(self.points, self.edges)

    @property
    def g1_mask(self):
        return self.edge_groups == G1

    def triangle_areas(self):
        p, t = self.points, self.triangles
        return 0.5 * orient(p[t[:, 0]], p[t[:, 1]], p[t[:, 2]])


def _rows_in(rows, table):
    """Boolean mask: which rows of ``rows`` (E, 2) occur in ``table`` (K, 2)."""
    return np.isin(_edge_key(rows), _edge_key(table))


def _edge_key(pairs):
    return pairs[:, 0] * (1 << 32) + pairs[:, 1]
