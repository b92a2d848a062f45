"""Reference engine: Steps 3-4 of Algorithm INCREMENT, read literally.

Every iteration recomputes the constrained Delaunay triangulation (CDT) of the
current points from scratch, lists every candidate for the farthest point,
inserts the best one while its distance is at least ``(1 - REL_TOL) l`` and
stops otherwise.  Slow (one triangulation per inserted point) and obviously
right; faster engines are tested against it.

Candidates (the local maxima of the visibility distance ``d~(x, S)`` over the
closed region R, i.e. the vertices of the bounded Voronoi diagram):

1. the circumcentre ``c`` of every CDT triangle ``t`` that ``c`` is visible
   from, with value the circumradius.  In a CDT no point visible from the
   interior of ``t`` lies inside its circumcircle, and a point inside the
   circle that is visible from ``c`` would be visible from ``t`` too (both
   lie in the convex part of the disc cut off by the constraints), so
   ``d~(c, S)`` is exactly the circumradius.  Visibility is tested on the
   segment from the centroid of ``t`` to ``c``; a circumcentre closer than
   ``REL_TOL l`` to a constraint is left to candidate 2 (it would otherwise
   create a sliver next to the constraint).  So is one closer than
   ``SLIVER_GAP l`` whose value is ``l`` up to REL_TOL (at most
   ``(1 + REL_TOL) l``): near-cocircular inputs (a rectangle 4l x (4 - 2^-12) l)
   put such a circumcentre a hair inside a boundary part of length 2l, and
   inserting it would leave a triangle of altitude ~1e-9 l.  Leaving it out
   keeps every guarantee: it is within ``(1 + REL_TOL) l`` of every point, so
   the covering radius stays at most ``(1 + REL_TOL) l`` and the edges of its
   triangle at most ``2 (1 + REL_TOL) l`` (Lemma 1);
2. the midpoint ``m`` of every constraint segment ``ab`` (the boundary of P or
   of the lattice part): along ``ab``, ``d~(x, S) <= min(|xa|, |xb|) <= |ab|/2``
   with equality only at ``m``; its value is ``min(|ab|/2, |m - apex|)`` where
   ``apex`` is the third vertex of the CDT triangle on ``ab`` (the diametral
   half-disc of ``ab`` lies in that triangle's circumcircle unless the apex is
   inside it).  Only segments of length at least ``2 (1 - REL_TOL) l`` can
   qualify, so only those are listed.  An inserted midpoint splits its
   constraint in two.

Tie-breaking: the candidate with the largest value wins; exactly equal values
(common on lattices and regular polygons) are broken by the smallest ``x``,
then the smallest ``y`` of the candidate point.  Circumcentres are computed
from the triangle's vertices in increasing index order, so the same triangle
always gives the same bits.
"""

import numpy as np

from ..._geometry import circumcenters, point_segment_distance, segments_intersect
from ...mesh import half_edges
from ...tolerance import REL_TOL, SLIVER_GAP, at_least, at_most
from .region import Insertion, constrained_delaunay


def run(region, l):
    """Farthest-point insertion in ``region`` (Steps 3-5), reference engine."""
    points = np.array(region.points, dtype=float)
    segments = np.array(region.segments, dtype=np.int64).reshape(-1, 2)
    values = []
    while True:
        triangles = constrained_delaunay(points, segments, region.holes)
        point, value, split = best_candidate(points, triangles, segments, l)
        if point is None or not at_least(value, l):
            break
        new = len(points)
        points = np.vstack([points, point])
        values.append(value)
        if split is not None:
            a, b = segments[split]
            segments = np.vstack([np.delete(segments, split, axis=0), [[a, new], [new, b]]])
    return Insertion(points, triangles, segments, len(region.points), np.array(values))


def best_candidate(points, triangles, segments, l):
    """The candidate farthest from the current points: ``(point, value, split_segment)``.

    ``split_segment`` is the index of the constraint the point lies on, or None.
    Only candidates that could reach ``(1 - REL_TOL) l`` are listed; returns
    ``(None, 0.0, None)`` when there is none.
    """
    centers, radii = circle_candidates(points, triangles, segments, l)
    mids, mid_values, mid_segments = midpoint_candidates(points, triangles, segments, l)
    cand = np.vstack([centers, mids])
    vals = np.concatenate([radii, mid_values])
    split = np.concatenate([np.full(len(radii), -1), mid_segments])
    if not len(vals):
        return None, 0.0, None
    best = np.lexsort((cand[:, 1], cand[:, 0], -vals))[0]
    return cand[best], float(vals[best]), (None if split[best] < 0 else int(split[best]))


def circle_candidates(points, triangles, segments, l):
    """Candidate 1: visible circumcentres whose circumradius reaches ``(1 - REL_TOL) l``."""
    t = np.sort(triangles, axis=1)
    a, b, c = points[t[:, 0]], points[t[:, 1]], points[t[:, 2]]
    centers, radii = circumcenters(a, b, c)
    live = np.flatnonzero(at_least(radii, l) & np.isfinite(radii))
    if not live.size:
        return np.empty((0, 2)), np.empty(0)
    centers, radii = centers[live], radii[live]
    centroids = (a[live] + b[live] + c[live]) / 3.0
    sa, sb = points[segments[:, 0]], points[segments[:, 1]]
    gap = point_segment_distance(centers[:, None, :], sa[None], sb[None]).min(axis=1)
    near = (gap <= REL_TOL * l) | ((gap <= SLIVER_GAP * l) & at_most(radii, l))
    hidden = segments_intersect(centroids[:, None, :], centers[:, None, :], sa[None], sb[None]).any(axis=1)
    ok = ~near & ~hidden
    return centers[ok], radii[ok]


def midpoint_candidates(points, triangles, segments, l):
    """Candidate 2: midpoints of constraint segments of length at least ``2 (1 - REL_TOL) l``."""
    sa, sb = points[segments[:, 0]], points[segments[:, 1]]
    half = 0.5 * np.linalg.norm(sb - sa, axis=1)
    long_ = np.flatnonzero(at_least(half, l))
    if not long_.size:
        return np.empty((0, 2)), np.empty(0), np.empty(0, dtype=np.int64)
    mids = 0.5 * (sa[long_] + sb[long_])
    apex = apexes(triangles, segments[long_])
    has = apex >= 0
    values = half[long_].copy()
    values[has] = np.minimum(values[has], np.linalg.norm(mids[has] - points[apex[has]], axis=1))
    return mids, values, long_


def apexes(triangles, pairs):
    """Third vertex of the triangle that has edge ``pairs[i]``, or -1 (vectorised)."""
    t = np.asarray(triangles)
    if not len(t):
        return np.full(len(pairs), -1)
    n = int(max(t.max(), pairs.max(initial=0))) + 1
    edges = np.sort(half_edges(t), axis=1)
    third = np.concatenate([t[:, 2], t[:, 0], t[:, 1]])
    keys = edges[:, 0] * n + edges[:, 1]
    order = np.argsort(keys, kind="stable")
    keys, third = keys[order], third[order]
    p = np.sort(pairs, axis=1)
    want = p[:, 0] * n + p[:, 1]
    pos = np.minimum(np.searchsorted(keys, want), len(keys) - 1)
    return np.where(keys[pos] == want, third[pos], -1)
