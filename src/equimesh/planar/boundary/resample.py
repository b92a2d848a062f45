"""Step 2 of Algorithm INCREMENT on a validated polygon: the resampled boundary V' of every ring.

"Place points V' on the boundary of P so that l <= d(V u V', V u V') <= 2l":
every edge of every ring (the holes' too) gets the points of
:func:`~equimesh.planar.boundary.sides.side_positions`, in the polygon's local
frame, with the edge and ring each point lies on.
"""

from dataclasses import dataclass

import numpy as np

from .sides import side_positions


@dataclass(frozen=True)
class Boundary:
    """The resampled boundary ring of Step 2, in the polygon's local frame.

    Attributes
    ----------
    points : (m, 2) float array, local coordinates: the outer ring
        counter-clockwise from polygon vertex 0, then each hole's ring
        clockwise from its vertex 0 (``Polygon.rings`` order).
    is_vertex : (m,) bool array, True where the point is a vertex of P.
    edge : (m,) int array, the edge of its ring each point starts (points j
        with ``edge[j] == i`` lie on edge i, the first of them is vertex i).
    ring : (m,) int array, the index into ``Polygon.rings`` of each point.
    """

    points: np.ndarray
    is_vertex: np.ndarray
    edge: np.ndarray
    ring: np.ndarray

    @property
    def ring_sizes(self):
        return np.bincount(self.ring)

    @property
    def segments(self):
        """Each ring closed on itself, the region on the left."""
        sizes = self.ring_sizes
        start = np.repeat(np.cumsum(sizes) - sizes, sizes)
        j = np.arange(len(self.points)) - start
        return np.column_stack([start + j, start + (j + 1) % np.repeat(sizes, sizes)])


def resample_boundary(poly, l, spacing=2.0):
    """Step 2: place points V' on the boundary so consecutive points are between l and 2l apart.

    Each edge of length ``L`` is split into ``k`` equal parts, the smallest
    number making a part at most ``spacing * l`` long, kept within
    ``[ceil(L / 2l), floor(L / l)]`` (:func:`split_counts`).  With the default
    ``spacing = 2`` this is ``k = ceil(L / 2l)``, the fewest boundary points
    (Problem 1 minimises the node count).  Problem 2 uses a spacing below 2 (see
    :func:`equimesh.planar.strip.uniform_triangulation`): a boundary part of
    exactly ``2l`` leaves its midpoint at distance exactly ``l``, and the
    farthest-point insertion then places a point a hair inside it, a sliver.
    Next to a corner sharper than :data:`SHARP_CORNER` the points of its two
    sides are staggered instead (:func:`side_positions`, :func:`stagger`).

    In a convex polygon with inner angles of at least 90 degrees (Problem 1)
    all boundary points are then pairwise at least ``l`` apart; the proof is
    in ``docs/proofs.md``, section "Step 2 boundary separation (Problem 1)".
    For other polygons the separation of points on one edge or on the two
    sides of one corner is proven in "Sharp corners" (when the sides are long
    enough) and the rest is checked by :func:`check_boundary_separation`.
    Every ring (the holes' too) is resampled alike.  The points are in the
    local frame.
    """
    lp = poly.local_length(l)
    points, is_vertex, edge, ring = [], [], [], []
    for r, each in enumerate(poly.rings):
        v = each.local
        angles = [each.inner_angle(i) for i in range(len(v))]
        sides = side_positions(each.local_edge_lengths, angles, lp, spacing)
        for i, (a, b, (num, den)) in enumerate(zip(v, np.roll(v, -1, axis=0), sides)):
            points.append(a + (b - a) * num[:, None] / den)
            is_vertex.append(np.arange(len(num)) == 0)
            edge.append(np.full(len(num), i))
            ring.append(np.full(len(num), r))
    return Boundary(*(np.concatenate(x) for x in (points, is_vertex, edge, ring)))
