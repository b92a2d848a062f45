"""Problem 2 (Section 3 of the paper): the triangular lattice part H'.

A triangular lattice G of spacing l is overlaid on the polygon P.  Its
vertices too close to the boundary of P are removed; the lattice triangles
whose three vertices survive form the lattice part K (the paper's H'), whose
edges all have length exactly l (group G1).  The rest of P, the boundary strip
R = P \\ K, is filled by :mod:`equimesh.planar.strip`.

Reading of the paper.  The paper removes the lattice vertices within distance
1 (= l) of the *vertices* V(P).  That breaks Lemma 3 and Theorem 3: a lattice
vertex can sit arbitrarily close to the middle of a long edge of P, giving an
edge far shorter than l.  We remove every lattice vertex whose distance to the
*boundary* of P is below ``clearance * l`` (``clearance >= 1``).  Then

* every kept vertex is at least ``l`` from every boundary point of P, and
  lattice vertices are pairwise at least ``l`` apart: Lemma 3 (1);
* a lattice triangle with three kept vertices lies inside P: a boundary edge
  of P entering it would pass within ``sqrt(3)/2 l < l`` of one of its
  vertices, and a vertex of P inside it would be within ``l / sqrt(3)`` of one;
* every point x of P with ``d(x, boundary) >= (clearance + 1) l`` lies in K
  (the lattice triangle containing x has diameter l, so its vertices are
  kept), hence R lies within ``(clearance + 1) l`` of the boundary of P, the
  fact behind the O(perimeter / l) count of non-G1 edges.

Dangling lattice vertices and edges (kept, but in no kept triangle) are
dropped: K is exactly a union of whole lattice triangles, so its boundary is a
set of lattice edges of length l and R is a polygonal region bounded by
constraint segments; the points the strip needs there are placed by the
insertion, under the same guarantees as everywhere else in R.
"""

from dataclasses import dataclass

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from ..mesh import half_edges, single_edges
from .clearance import clear_of_boundary

#: Lattice steps (di, dj) between neighbouring vertices, in the basis
#: a1 = l (cos t, sin t), a2 = l (cos(t + 60), sin(t + 60)).
NEIGHBOUR_STEPS = ((1, 0), (0, 1), (-1, 1), (-1, 0), (0, -1), (1, -1))


@dataclass(frozen=True)
class LatticePart:
    """The kept lattice part K of Problem 2.

    Attributes
    ----------
    points : (k, 2) float, the vertices of kept lattice triangles.
    ij : (k, 2) int, their lattice coordinates.
    triangles : (t, 3) int into ``points``, counter-clockwise.
    boundary_edges : (b, 2) int into ``points``, the edges of K that belong
        to one kept triangle only (oriented with K on their left).
    holes : (h, 2) float, one point inside each edge-connected component of K.
    """

    points: np.ndarray
    ij: np.ndarray
    triangles: np.ndarray
    boundary_edges: np.ndarray
    holes: np.ndarray

    @property
    def boundary_vertices(self):
        return np.unique(self.boundary_edges)


def lattice_basis(l, angle):
    """The two lattice vectors of length ``l`` at ``angle`` and ``angle + 60`` degrees.

    The lattice is invariant under rotation by 60 degrees, so ``angle`` is
    reduced modulo 60 first (exactly: ``fmod`` is exact): a huge angle such as
    1e20 gives the same lattice as its remainder, at full precision.
    """
    t = np.radians(float(angle) % 60.0)
    return l * np.array([[np.cos(t), np.sin(t)], [np.cos(t + np.pi / 3), np.sin(t + np.pi / 3)]])


def lattice_points(ij, l, angle, offset):
    """Coordinates ``offset + i a1 + j a2`` of lattice vertices ``ij`` (k, 2)."""
    return np.asarray(offset, dtype=float) + np.asarray(ij, dtype=float) @ lattice_basis(l, angle)


def local_offset(poly, l, angle, offset):
    """The caller's ``offset`` (position of lattice vertex (0, 0)) in the polygon's local frame.

    Kept as is (exact for a moderate offset, so lattice vertices the caller
    placed on exact coordinates stay there) while it lies within twice the
    polygon's local extent plus one l of the local origin.  Farther away (an
    offset of 0 for a polygon near 1e9) it is moved by a whole number of
    lattice vectors next to the origin: the same lattice, whose vertices near
    the polygon are then computed from small numbers, so G1 edges stay l to
    rounding.
    """
    lp = poly.local_length(l)
    local = poly.frame.to_local(offset)
    if np.max(np.abs(local)) <= 2.0 * float(np.max(poly.local)) + lp:
        return local
    basis = lattice_basis(lp, angle)
    return local - np.round(local @ np.linalg.inv(basis)) @ basis


def kept_vertices(poly, l, angle=0.0, offset=(0.0, 0.0), clearance=1.0):
    """Lattice vertices over the bounding box of P and which of them are kept, in P's local frame.

    ``l`` and ``offset`` are in the caller's units.  Returns
    ``(ii, jj, points, kept)``: index grids, local coordinates
    ``(ni * nj, 2)`` and a boolean grid, True for vertices inside P at
    distance at least ``clearance * l`` from its boundary (the outer
    boundary and every hole's).
    """
    lp = poly.local_length(l)
    offset = local_offset(poly, l, angle, offset)
    basis = lattice_basis(lp, angle)
    inv = np.linalg.inv(basis)
    lo, hi = poly.local.min(axis=0), poly.local.max(axis=0)
    corners = np.array([[lo[0], lo[1]], [hi[0], lo[1]], [lo[0], hi[1]], [hi[0], hi[1]]])
    coords = (corners - offset) @ inv
    i0, j0 = np.floor(coords.min(axis=0)).astype(int) - 1
    i1, j1 = np.ceil(coords.max(axis=0)).astype(int) + 1
    ii, jj = np.meshgrid(np.arange(i0, i1 + 1), np.arange(j0, j1 + 1), indexing="ij")
    pts = lattice_points(np.column_stack([ii.ravel(), jj.ravel()]), lp, angle, offset)
    kept = clear_of_boundary(poly.region, pts, (i0, j0), ii.shape, offset, basis, clearance * lp)
    return ii, jj, pts, kept


def lattice_triangle_masks(kept):
    """Which up and down lattice triangles have all three vertices kept.

    Up triangle ``(i, j)`` is ``(i,j), (i+1,j), (i,j+1)``; down triangle
    ``(i, j)`` is ``(i+1,j), (i+1,j+1), (i,j+1)``; both counter-clockwise.
    """
    up = kept[:-1, :-1] & kept[1:, :-1] & kept[:-1, 1:]
    down = kept[1:, :-1] & kept[1:, 1:] & kept[:-1, 1:]
    return up, down


def lattice_part(poly, l, angle=0.0, offset=(0.0, 0.0), clearance=1.0):
    """Build the lattice part K of a validated polygon (the paper's H'), in its local frame.

    ``offset`` is the position of the lattice vertex (0, 0) in the caller's
    coordinates; ``angle`` (degrees) the direction of the first lattice vector.
    """
    ii, jj, pts, kept = kept_vertices(poly, l, angle, offset, clearance)
    up_kept, down_kept = lattice_triangle_masks(kept)

    flat = np.arange(kept.size).reshape(kept.shape)
    up = np.stack([flat[:-1, :-1], flat[1:, :-1], flat[:-1, 1:]], axis=-1)[up_kept]
    down = np.stack([flat[1:, :-1], flat[1:, 1:], flat[:-1, 1:]], axis=-1)[down_kept]
    tri = np.vstack([up, down])
    used, tri = np.unique(tri, return_inverse=True)
    tri = tri.reshape(-1, 3)
    ij = np.column_stack([ii.ravel()[used], jj.ravel()[used]])
    points = pts[used]
    boundary_edges = single_edges(tri)
    holes = component_seeds(points, tri)
    return LatticePart(points, ij, tri, boundary_edges, holes)


def component_seeds(points, tri):
    """Centroid of the first triangle of each edge-connected component of the triangles."""
    if not len(tri):
        return np.empty((0, 2))
    n = len(tri)
    undirected = np.sort(half_edges(tri), axis=1)
    owner = np.tile(np.arange(n), 3)
    order = np.lexsort((undirected[:, 1], undirected[:, 0]))
    u, o = undirected[order], owner[order]
    same = np.all(u[1:] == u[:-1], axis=1)
    a, b = o[:-1][same], o[1:][same]
    graph = coo_matrix((np.ones(len(a)), (a, b)), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    _, first = np.unique(labels, return_index=True)
    return points[tri[np.sort(first)]].mean(axis=1)


def lattice_adjacent(ij_a, ij_b):
    """Whether lattice vertices with coordinates ``ij_a`` and ``ij_b`` are neighbours (vectorised)."""
    d = np.asarray(ij_b) - np.asarray(ij_a)
    steps = np.array(NEIGHBOUR_STEPS)
    return np.any(np.all(d[:, None, :] == steps[None, :, :], axis=-1), axis=1)
