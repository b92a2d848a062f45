"""What the output of Problem 2 (Section 3 of the paper) must satisfy.

Each ``check_*`` function states one guarantee of
:func:`equimesh.uniform_triangulation` and raises ``AssertionError`` naming
the offending edge, point or triangle.  :func:`assert_problem2_invariants`
runs all of them.  Visibility ("the segment lies in the closed polygon") is
decided by shapely's ``covers`` predicate, independently of the library's own
geometry, on the region grown by :data:`VISIBILITY_SLACK` ``* l``: points
computed on the boundary (Step 2 points, probes) are off it by a rounding
error and must still see along it.  The slack makes the separation and
Delaunay checks (slightly) stricter and the covering check looser by a
distance far below ``REL_TOL l``.  Comparisons with ``l`` use the one
documented tolerance :data:`equimesh.REL_TOL`, relative.
"""

import numpy as np
import shapely
from invariants import check_edge_lengths
from scipy.spatial import cKDTree

from equimesh import G1, REL_TOL
from equimesh._geometry import circumcenters, point_segment_distance
from equimesh.mesh import unique_edges
from equimesh.planar.polygon import as_polygon

#: G1 edges are lattice edges: length l up to this relative error.
G1_REL = 1e-12
#: Relative slack of the empty-circumcircle test (cocircular lattice points).
DELAUNAY_REL = 1e-9
#: Regions are grown by this times l before testing visibility (module docstring).
VISIBILITY_SLACK = 1e-9


def ccw(vertices):
    """The polygon's vertices, validated and counter-clockwise."""
    return as_polygon(vertices).vertices


def rings(vertices, holes=()):
    """The outer ring (counter-clockwise) and the holes' rings (clockwise): the region on the left of each."""
    return [ring.vertices for ring in as_polygon(vertices, holes=list(holes)).rings]


def shape(vertices, holes=()):
    """The closed region P: the polygon minus its holes, as a shapely polygon."""
    outer, *inner = rings(vertices, holes)
    return shapely.Polygon(outer, inner)


def ring_edges(vertices, holes=()):
    """``(a, b)``: the start and end points of every edge of every ring."""
    r = rings(vertices, holes)
    return np.vstack(r), np.vstack([np.roll(v, -1, axis=0) for v in r])


def visible(region, a, b):
    """Whether each segment ``a[i] b[i]`` lies in the closed (prepared) shapely ``region``."""
    a, b = np.asarray(a, dtype=float).reshape(-1, 2), np.asarray(b, dtype=float).reshape(-1, 2)
    out = np.ones(len(a), dtype=bool)
    proper = np.any(a != b, axis=1)
    if proper.any():
        lines = shapely.linestrings(np.stack([a[proper], b[proper]], axis=1))
        out[proper] = shapely.covers(region, lines)
    same = ~proper
    if same.any():
        out[same] = shapely.covers(region, shapely.points(a[same]))
    return out


def region_of(geometry, l):
    """``geometry`` grown by :data:`VISIBILITY_SLACK` ``* l`` (mitred corners), prepared for many predicates."""
    grown = geometry.buffer(VISIBILITY_SLACK * l, join_style="mitre")
    shapely.prepare(grown)
    return grown


def polygon_region(vertices, l, holes=()):
    """The closed polygon P (minus its holes) as a visibility region."""
    return region_of(shape(vertices, holes), l)


def lattice_mask(mesh):
    """Triangles of the lattice part K: all three edges in G1 (three pairwise lattice-adjacent vertices)."""
    t = mesh.triangles
    g1 = {tuple(e) for e in mesh.edges[mesh.edge_groups == G1].tolist()}
    pairs = np.sort(np.stack([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]], axis=1), axis=2)
    return np.array([all(tuple(p) in g1 for p in tri) for tri in pairs.tolist()], dtype=bool)


def strip_region(mesh, vertices, l, holes=()):
    """The closed region R = P minus the interior of the lattice part, as a visibility region."""
    poly = shape(vertices, holes)
    lat = mesh.triangles[lattice_mask(mesh)]
    if len(lat):
        poly = poly.difference(shapely.unary_union(shapely.polygons(mesh.points[lat])))
    return region_of(poly, l)


def check_theorem3(mesh, l):
    """Theorem 3: every edge in [(1 - REL_TOL) l, 2l (1 + REL_TOL)]; every G1 edge has length l (1e-12 relative)."""
    check_edge_lengths(mesh, l)
    lengths = mesh.edge_lengths()[mesh.edge_groups == G1]
    if len(lengths):
        err = np.abs(lengths / l - 1.0)
        k = int(np.argmax(err))
        assert err[k] <= G1_REL, f"G1 edge of length {lengths[k]!r} differs from l = {l!r} by {err[k]:.3g} relative"


def check_separation(mesh, vertices, l, holes=()):
    """Lemma 3 (1) and Step 4: output points that see each other in P are at least (1 - REL_TOL) l apart."""
    pts = mesh.points
    pairs = cKDTree(pts).query_pairs((1.0 - REL_TOL) * l, output_type="ndarray")
    if not len(pairs):
        return
    d = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
    close = pairs[d < (1.0 - REL_TOL) * l]
    if not len(close):
        return
    seen = visible(polygon_region(vertices, l, holes), pts[close[:, 0]], pts[close[:, 1]])
    if seen.any():
        i, j = close[np.flatnonzero(seen)[0]]
        raise AssertionError(
            f"points {i} {pts[i].tolist()} and {j} {pts[j].tolist()} see each other at distance "
            f"{np.linalg.norm(pts[i] - pts[j])!r} < l = {l!r}"
        )


def covering_samples(mesh, vertices, l, holes=()):
    """Where the covering radius is probed: circumcentres in P, edge midpoints, centroids, dense boundary samples."""
    pts, tri = mesh.points, mesh.triangles
    t = np.sort(tri, axis=1)
    centers, _ = circumcenters(pts[t[:, 0]], pts[t[:, 1]], pts[t[:, 2]])
    poly = shape(vertices, holes)
    shapely.prepare(poly)
    centers = centers[np.isfinite(centers).all(axis=1)]
    centers = centers[shapely.covers(poly, shapely.points(centers))]
    mids = pts[mesh.edges].mean(axis=1)
    centroids = pts[tri].mean(axis=1)
    a, b = ring_edges(vertices, holes)
    boundary = []
    for p, q in zip(a, b):
        k = max(1, int(np.ceil(8.0 * np.linalg.norm(q - p) / l)))
        boundary.append(p + (q - p) * (np.arange(k)[:, None] / k))
    return np.vstack([centers, mids, centroids, *boundary])


def check_covering(mesh, vertices, l, holes=()):
    """Step 4 halts: every probed point of P is within l (1 + REL_TOL) of an output point it sees (in P)."""
    pts = mesh.points
    x = covering_samples(mesh, vertices, l, holes)
    radius = l * (1.0 + REL_TOL)
    near = cKDTree(pts).query_ball_point(x, radius)
    rows = np.repeat(np.arange(len(x)), [len(n) for n in near])
    cols = np.fromiter((j for n in near for j in n), dtype=np.int64, count=len(rows))
    seen = visible(polygon_region(vertices, l, holes), x[rows], pts[cols]) if len(rows) else np.zeros(0, dtype=bool)
    covered = np.zeros(len(x), dtype=bool)
    covered[rows[seen]] = True
    if not covered.all():
        k = int(np.flatnonzero(~covered)[0])
        d, _ = cKDTree(pts).query(x[k])
        raise AssertionError(
            f"point {x[k].tolist()} of P sees no output point within l = {l!r} (nearest at {d!r}, maybe hidden)"
        )


def check_triangulation(mesh, vertices, l, holes=()):
    """A valid conforming triangulation of P whose boundary contains the boundary of P.

    * indices in range, every point used, ``edges`` are the triangles' edges;
    * every triangle counter-clockwise with positive area, the areas sum to
      area(P) (relative 1e-9);
    * no overlap: every directed edge occurs at most once, every undirected
      edge in one or two triangles, and an edge in only one triangle lies on
      the boundary of P; those edges have total length perimeter(P);
    * every vertex of P is an output point (bit-identical) and every edge of
      P is a chain of mesh edges between its endpoints;
    * the first ``n_boundary`` points lie on the boundary of P: the outer
      ring counter-clockwise from vertex 0, then each hole's ring clockwise
      from its first vertex (``info["boundary_rings"]`` points each); the
      others do not.
    """
    ring_list = rings(vertices, holes)
    pts, tri, nb = mesh.points, mesh.triangles, mesh.n_boundary
    n = len(pts)
    assert tri.ndim == 2 and tri.shape[1] == 3 and tri.min() >= 0 and tri.max() < n, "triangle index out of range"
    assert np.array_equal(np.unique(tri), np.arange(n)), "some output point is in no triangle"
    assert np.array_equal(mesh.edges, unique_edges(tri)), "edges do not match the triangles"

    areas = mesh.triangle_areas()
    k = int(np.argmin(areas))
    assert areas[k] > 0, f"triangle {k} {tri[k].tolist()} is not counter-clockwise (area {areas[k]!r})"
    poly = shape(vertices, holes)
    assert abs(areas.sum() - poly.area) <= 1e-9 * poly.area, f"triangles cover {areas.sum()!r}, P has {poly.area!r}"

    directed = np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]])
    uniq, counts = np.unique(directed, axis=0, return_counts=True)
    assert counts.max() == 1, f"directed edge {uniq[np.argmax(counts)].tolist()} is in two triangles (overlap)"
    und, ucount = np.unique(np.sort(directed, axis=1), axis=0, return_counts=True)
    assert ucount.max() <= 2, f"edge {und[np.argmax(ucount)].tolist()} is in more than two triangles"
    single = und[ucount == 1]
    a, b = ring_edges(vertices, holes)
    scale = max(float(np.ptp(a, axis=0).max()), l)

    def to_boundary(x):
        return point_segment_distance(x[:, None, :], a[None], b[None]).min(axis=1)

    mid = pts[single].mean(axis=1)
    off = np.maximum(to_boundary(mid), np.maximum(to_boundary(pts[single[:, 0]]), to_boundary(pts[single[:, 1]])))
    k = int(np.argmax(off))
    assert off[k] <= 1e-12 * scale, f"edge {single[k].tolist()} is in one triangle only but not on the boundary of P"
    total = np.linalg.norm(pts[single[:, 1]] - pts[single[:, 0]], axis=1).sum()
    perimeter = np.linalg.norm(b - a, axis=1).sum()
    assert abs(total - perimeter) <= 1e-9 * perimeter, f"boundary edges total {total!r}, perimeter {perimeter!r}"

    index = {tuple(p): i for i, p in enumerate(pts.tolist())}
    missing = [p for p in a.tolist() if tuple(p) not in index]
    assert not missing, f"vertex {missing[0]} of P is not an output point"
    single_set = {tuple(e) for e in single.tolist()}
    for p, q in zip(a, b):
        d = q - p
        on = np.flatnonzero(point_segment_distance(pts, p, q) <= 1e-12 * scale)
        chain = on[np.argsort((pts[on] - p) @ d)]
        assert chain[0] == index[tuple(p)] and chain[-1] == index[tuple(q)], f"edge {p}-{q} of P: chain ends wrong"
        links = np.sort(np.column_stack([chain[:-1], chain[1:]]), axis=1)
        gaps = [tuple(e) for e in links.tolist() if tuple(e) not in single_set]
        assert not gaps, f"edge {p.tolist()}-{q.tolist()} of P is not covered by boundary edges (gap {gaps[0]})"

    dist = to_boundary(pts)
    assert np.all(dist[:nb] <= 1e-12 * scale), "a leading 'boundary' point is off the boundary of P"
    assert np.all(dist[nb:] > 1e-12 * scale), "a point after the first n_boundary lies on the boundary of P"
    sizes = mesh.info.get("boundary_rings", (nb,))
    assert len(sizes) == len(ring_list) and sum(sizes) == nb, f"boundary rings {sizes} for {len(ring_list)} rings"
    starts = np.cumsum(sizes) - sizes
    links = set()
    for k, (start, size, v) in enumerate(zip(starts, sizes, ring_list)):
        assert np.array_equal(pts[start], v[0]), f"boundary ring {k} does not start at its vertex 0"
        j = np.arange(size)
        links |= {tuple(e) for e in np.sort(np.column_stack([start + j, start + (j + 1) % size]), axis=1).tolist()}
        r = pts[start : start + size]
        twice_area = np.sum(r[:, 0] * np.roll(r[:, 1], -1) - np.roll(r[:, 0], -1) * r[:, 1])
        assert (twice_area > 0) == (k == 0), f"boundary ring {k} has the wrong orientation"
    assert links == single_set, "the boundary rings are not the boundary"


def check_constrained_delaunay(mesh, vertices, l, holes=()):
    """Definition 1 in R: no output point visible (in R) from a strip triangle lies inside its circumcircle.

    Strip triangles are those not in the lattice part K; visibility is taken
    in the closed region R = P minus the interior of K, whose boundary edges
    are the constraints (the boundary of P and of K).  The circle is shrunk by
    the relative margin :data:`DELAUNAY_REL` (cocircular lattice points).
    """
    pts = mesh.points
    strip = np.flatnonzero(~lattice_mask(mesh))
    if not len(strip):
        return
    t = np.sort(mesh.triangles[strip], axis=1)
    centers, radii = circumcenters(pts[t[:, 0]], pts[t[:, 1]], pts[t[:, 2]])
    hits = cKDTree(pts).query_ball_point(centers, radii * (1.0 - DELAUNAY_REL))
    rows, cols = [], []
    for i, h in enumerate(hits):
        for j in h:
            if j not in t[i]:
                rows.append(i)
                cols.append(j)
    if not rows:
        return
    rows, cols = np.array(rows), np.array(cols)
    centroids = pts[t].mean(axis=1)
    seen = visible(strip_region(mesh, vertices, l, holes), centroids[rows], pts[cols])
    if seen.any():
        k = int(np.flatnonzero(seen)[0])
        raise AssertionError(
            f"strip triangle {t[rows[k]].tolist()} has point {cols[k]} {pts[cols[k]].tolist()}, visible in R, "
            "inside its circumcircle"
        )


def check_lattice_part(mesh, vertices, l, clearance=1.0, holes=()):
    """The lattice part K: its triangles' vertices are kept lattice vertices, at least clearance * l from the boundary.

    Also checks that K has ``info["n_lattice_triangles"]`` triangles.
    """
    mask = lattice_mask(mesh)
    assert mask.sum() == mesh.info["n_lattice_triangles"], (
        f"{mask.sum()} all-G1 triangles, the lattice part has {mesh.info['n_lattice_triangles']}"
    )
    if not mask.any():
        return
    used = np.unique(mesh.triangles[mask])
    a, b = ring_edges(vertices, holes)
    d = point_segment_distance(mesh.points[used][:, None, :], a[None], b[None]).min(axis=1)
    k = int(np.argmin(d))
    assert d[k] >= (1.0 - REL_TOL) * clearance * l, (
        f"lattice vertex {used[k]} is {d[k]!r} < clearance * l = {clearance * l!r} from the boundary"
    )


def assert_problem2_invariants(mesh, vertices, l, clearance=1.0, holes=()):
    """Every guarantee of Problem 2 on one output (``holes``: the openings passed to it)."""
    check_theorem3(mesh, l)
    check_triangulation(mesh, vertices, l, holes)
    check_lattice_part(mesh, vertices, l, clearance, holes)
    check_separation(mesh, vertices, l, holes)
    check_covering(mesh, vertices, l, holes)
    check_constrained_delaunay(mesh, vertices, l, holes)
