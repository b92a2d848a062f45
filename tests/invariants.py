"""What the output of Algorithm INCREMENT (Problem 1, Section 2) must satisfy.

Each ``check_*`` function states one guarantee and raises ``AssertionError``
with the offending edge, point or triangle when it fails.
:func:`assert_problem1_invariants` runs all of them; the test modules call it
or the single check they are about.  Every comparison with ``l`` uses the one
documented tolerance :data:`equimesh.REL_TOL`, relative, so nothing here
depends on the scale of the input.
"""

import numpy as np
import shapely
from scipy.spatial import Voronoi, cKDTree

import equimesh
from equimesh import REL_TOL
from equimesh._geometry import circumcenters, cross, orient, point_segment_distance
from equimesh.planar.polygon import as_polygon

#: Theorem 2 of the paper: the node count is at most 16/3 of the optimum.
THEOREM2_FACTOR = 16.0 / 3.0


def ccw_vertices(polygon):
    """The polygon's vertices, validated and counter-clockwise."""
    return as_polygon(polygon).vertices


def check_edge_lengths(mesh, l):
    """Theorem 1: every edge is between l and 2l long, i.e. in [(1 - REL_TOL) l, 2l (1 + REL_TOL)]."""
    lengths = mesh.edge_lengths()
    lo, hi = int(np.argmin(lengths)), int(np.argmax(lengths))
    assert lengths[lo] >= (1.0 - REL_TOL) * l, f"edge {tuple(mesh.edges[lo])} has length {lengths[lo]!r} < l = {l!r}"
    assert lengths[hi] <= 2.0 * l * (1.0 + REL_TOL), (
        f"edge {tuple(mesh.edges[hi])} has length {lengths[hi]!r} > 2l = {2 * l!r}"
    )


def check_separation(mesh, l):
    """Every pair of output points is at least (1 - REL_TOL) l apart (the packing of Theorem 2's proof)."""
    pts = mesh.points
    pairs = cKDTree(pts).query_pairs(l, output_type="ndarray")
    if len(pairs):
        d = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
        k = int(np.argmin(d))
        assert d[k] >= (1.0 - REL_TOL) * l, (
            f"points {tuple(pairs[k])} at {pts[pairs[k]].tolist()} are {d[k]!r} < l = {l!r} apart"
        )


def covering_candidates(points, vertices):
    """Points of P among which ``x -> d(x, points)`` attains its maximum over P.

    The distance to the nearest point is maximal over the convex polygon P at
    a Voronoi vertex inside P, at a crossing of a Voronoi edge with the
    boundary of P, or at a vertex of P.  Returned: the Voronoi vertices inside
    P (up to a relative margin), the crossings of every Voronoi ridge's
    bisector with every edge of P (a superset of the ridge crossings, which
    is harmless: every returned point lies in P), the vertices of P and the
    midpoints of its edges.
    """
    a, b = vertices, np.roll(vertices, -1, axis=0)
    scale = np.ptp(vertices, axis=0).max()
    vor = Voronoi(points)
    inside = np.all(
        cross(b - a, vor.vertices[:, None, :] - a) >= -1e-12 * scale * np.linalg.norm(b - a, axis=1), axis=1
    )
    p, q = points[vor.ridge_points[:, 0]], points[vor.ridge_points[:, 1]]
    mid, normal = 0.5 * (p + q), q - p
    # Bisector {x : (x - mid) . normal = 0} against edge a + t (b - a), t in [0, 1].
    along = np.einsum("rk,ek->re", normal, b - a)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = (np.einsum("rk,rk->r", mid, normal)[:, None] - normal @ a.T) / along
    r, e = np.nonzero((t >= 0.0) & (t <= 1.0))
    crossings = a[e] + t[r, e][:, None] * (b - a)[e]
    return np.vstack([vor.vertices[inside], crossings, vertices, 0.5 * (a + b)])


def covering_radius(points, vertices):
    """``max over x in P of d(x, points)`` and the point where it is attained."""
    cand = covering_candidates(points, vertices)
    dist, _ = cKDTree(points).query(cand)
    k = int(np.argmax(dist))
    return float(dist[k]), cand[k]


def check_covering(mesh, polygon, l):
    """Covering (Step 4 halts): every point of P is within distance l (1 + REL_TOL) of an output point."""
    radius, where = covering_radius(mesh.points, ccw_vertices(polygon))
    assert radius <= l * (1.0 + REL_TOL), f"point {where.tolist()} of P is {radius!r} > l = {l!r} from every node"


def check_triangulation(mesh, polygon, l):
    """Step 5 output is a valid Delaunay triangulation of P whose boundary is covered by edges.

    * indices in range, every point used, the triangle count is Euler's
      ``2N - h - 2`` for N points of which h are on the boundary;
    * every triangle counter-clockwise with positive area and an altitude
      above 1e-6 l (no slivers);
    * the areas sum to the area of P (relative 1e-9);
    * the first ``n_boundary`` points lie on the boundary of P in
      counter-clockwise order from vertex 0, the others strictly inside,
      every vertex of P is one of them (bit-identical), and every boundary
      segment between consecutive boundary points is an edge;
    * Delaunay: no point lies inside a triangle's circumcircle shrunk by the
      relative margin 1e-9.
    """
    v = ccw_vertices(polygon)
    pts, tri, nb = mesh.points, mesh.triangles, mesh.n_boundary
    n = len(pts)
    assert tri.ndim == 2 and tri.shape[1] == 3 and tri.min() >= 0 and tri.max() < n
    assert np.array_equal(np.unique(tri), np.arange(n)), "some output point is in no triangle"
    assert len(tri) == 2 * n - nb - 2, f"{len(tri)} triangles, Euler's formula wants {2 * n - nb - 2}"
    assert np.array_equal(mesh.edges, equimesh.mesh.unique_edges(tri)), "edges do not match the triangles"

    areas = 0.5 * orient(pts[tri[:, 0]], pts[tri[:, 1]], pts[tri[:, 2]])
    k = int(np.argmin(areas))
    assert areas[k] > 0, f"triangle {k} {tri[k].tolist()} is not counter-clockwise (area {areas[k]!r})"
    longest = np.max(np.linalg.norm(pts[tri] - pts[np.roll(tri, 1, axis=1)], axis=2), axis=1)
    altitude = 2.0 * areas / longest
    k = int(np.argmin(altitude))
    assert altitude[k] > 1e-6 * l, f"triangle {k} {tri[k].tolist()} is a sliver, altitude {altitude[k]!r}"
    area = shapely.Polygon(v).area
    assert abs(areas.sum() - area) <= 1e-9 * area, f"triangles cover {areas.sum()!r}, P has area {area!r}"

    a, b = v, np.roll(v, -1, axis=0)
    to_boundary = point_segment_distance(pts[:, None, :], a[None], b[None]).min(axis=1)
    scale = max(np.ptp(v, axis=0).max(), l)
    assert np.all(to_boundary[:nb] <= 1e-12 * scale), "a leading 'boundary' point is off the boundary of P"
    if n > nb:
        interior = pts[nb:]
        inside = np.all(cross(b - a, interior[:, None, :] - a) > 0, axis=1)
        assert np.all(inside), f"inserted point {interior[~inside][0].tolist()} is not strictly inside P"
    assert {tuple(p) for p in v} <= {tuple(p) for p in pts[:nb]}, "a vertex of P is missing from the mesh"
    assert np.array_equal(pts[0], v[0]), "the boundary ring does not start at vertex 0"
    ring = pts[:nb]
    assert 0.5 * np.sum(cross(ring, np.roll(ring, -1, axis=0))) > 0, "boundary ring is not counter-clockwise"
    seg = np.sort(np.column_stack([np.arange(nb), (np.arange(nb) + 1) % nb]), axis=1)
    edge_set = {tuple(e) for e in mesh.edges.tolist()}
    missing = [tuple(s) for s in seg.tolist() if tuple(s) not in edge_set]
    assert not missing, f"boundary segments {missing[:3]} are not edges of the mesh"

    t = np.sort(tri, axis=1)
    centers, radii = circumcenters(pts[t[:, 0]], pts[t[:, 1]], pts[t[:, 2]])
    hits = cKDTree(pts).query_ball_point(centers, radii * (1.0 - 1e-9))
    bad = [i for i, h in enumerate(hits) if h]
    assert not bad, f"triangle {tri[bad[0]].tolist()} has point(s) {hits[bad[0]]} inside its circumcircle"


def check_node_bounds(mesh, polygon, l):
    """Theorem 2 and packing: n' <= 16/3 node_lower_bound and n' <= packing_upper_bound(P, (1 - REL_TOL) l).

    ``node_lower_bound`` is at most the optimum n*, so ``n' <= 16/3 LB`` is
    stronger than Theorem 2 (``n' <= 16/3 n*``).  The packing bound holds
    because the output points are ``(1 - REL_TOL) l``-separated.  Returns
    the ratio ``n' / LB``.
    """
    n = mesh.n_nodes
    lb = equimesh.node_lower_bound(polygon, l)
    ub = equimesh.packing_upper_bound(polygon, (1.0 - REL_TOL) * l)
    assert 3 * n <= 16 * lb, f"n' = {n} > 16/3 * node_lower_bound = 16/3 * {lb}"
    assert n <= ub, f"n' = {n} > packing upper bound {ub}"
    return n / lb


#: Inserted values may rise by this much, relative: a circumradius is computed with a few
#: roundings, so two cocircular candidates of the same exact value can differ in the last bit.
VALUE_ROUNDING = 1e-12


def assert_values_non_increasing(insertion):
    """Step 3 takes the farthest point, and inserting a point only brings the others closer (up to rounding)."""
    v = insertion.values
    if len(v) > 1:
        k = int(np.argmax(np.diff(v)))
        assert v[k + 1] <= v[k] * (1.0 + VALUE_ROUNDING), (
            f"value {float(v[k + 1])!r} inserted after {float(v[k])!r} (step {k + 1})"
        )


def assert_problem1_invariants(mesh, polygon, l):
    """Every guarantee of Algorithm INCREMENT on one output; returns the ratio n' / LB."""
    check_edge_lengths(mesh, l)
    check_separation(mesh, l)
    check_covering(mesh, polygon, l)
    check_triangulation(mesh, polygon, l)
    return check_node_bounds(mesh, polygon, l)
