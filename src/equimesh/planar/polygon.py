"""Input polygons: validation and boundary resampling (Step 2 of Algorithm INCREMENT).

Problem 1 (Section 2 of the paper) assumes a convex polygon whose inner angles
are all at least 90 degrees and whose edges are all at least ``l`` long.
Problem 2 (Section 3) drops convexity.  Every violated assumption raises
:class:`~equimesh.errors.InvalidPolygonError` naming the vertex or edge at
fault, with vertex indices counted in the caller's input order.
"""

from dataclasses import dataclass

import numpy as np
import shapely
import shapely.prepared
from scipy.spatial import cKDTree

from .._geometry import cross, segments_intersect, signed_area
from ..errors import InvalidLengthError, InvalidPolygonError
from ..tolerance import REL_TOL, at_least


def check_length(l):
    """Return ``l`` as a float, raising :class:`InvalidLengthError` unless it is positive and finite."""
    try:
        value = float(l)
    except (TypeError, ValueError):
        raise InvalidLengthError(f"target length l must be a number, got {l!r}") from None
    if not np.isfinite(value) or value <= 0.0:
        raise InvalidLengthError(f"target length l must be positive and finite, got {value!r}")
    return value


@dataclass(frozen=True)
class Polygon:
    """A validated simple polygon, counter-clockwise.

    Attributes
    ----------
    vertices : (n, 2) float array, counter-clockwise, no repeated vertex.
    input_index : (n,) int array, the caller's index of each vertex.
    """

    vertices: np.ndarray
    input_index: np.ndarray

    @property
    def edge_lengths(self):
        return np.linalg.norm(np.roll(self.vertices, -1, axis=0) - self.vertices, axis=1)

    @property
    def area(self):
        return signed_area(self.vertices)

    @property
    def perimeter(self):
        return float(np.sum(self.edge_lengths))

    def vertex_name(self, i):
        j = int(self.input_index[i % len(self.vertices)])
        x, y = self.vertices[i % len(self.vertices)]
        return f"vertex {j} at ({x:.6g}, {y:.6g})"

    def edge_name(self, i):
        n = len(self.vertices)
        a, b = int(self.input_index[i % n]), int(self.input_index[(i + 1) % n])
        return f"edge ({a}, {b})"

    def shapely(self):
        return shapely.Polygon(self.vertices)


def as_polygon(vertices):
    """Validate a simple polygon and orient it counter-clockwise.

    Checks: an ``(n, 2)`` array of finite numbers, at least 3 distinct
    vertices, no repeated vertex (a closing copy of the first vertex is
    dropped), non-zero area and no self-intersection (no two edges share a
    point other than the common vertex of consecutive edges).
    """
    try:
        v = np.array(vertices, dtype=float)
    except (TypeError, ValueError):
        raise InvalidPolygonError("polygon vertices must be an (n, 2) array of numbers") from None
    if v.ndim != 2 or v.shape[1] != 2:
        raise InvalidPolygonError(f"polygon vertices must be an (n, 2) array, got shape {v.shape}")
    bad = np.flatnonzero(~np.all(np.isfinite(v), axis=1))
    if bad.size:
        raise InvalidPolygonError(f"vertex {bad[0]} has a non-finite coordinate {tuple(v[bad[0]])}")
    if len(v) > 1 and np.array_equal(v[0], v[-1]):
        v = v[:-1]
    if len(np.unique(v, axis=0)) < 3:
        raise InvalidPolygonError(f"a polygon needs at least 3 distinct vertices, got {len(np.unique(v, axis=0))}")
    _check_no_repeated_vertex(v)
    area = signed_area(v)
    if area == 0.0:
        raise InvalidPolygonError("polygon has zero area (all vertices collinear)")
    index = np.arange(len(v))
    if area < 0:
        v, index = v[::-1].copy(), index[::-1].copy()
    poly = Polygon(v, index)
    _check_simple(poly)
    return poly


def _check_no_repeated_vertex(v):
    order = np.lexsort((v[:, 1], v[:, 0]))
    same = np.all(v[order[1:]] == v[order[:-1]], axis=1)
    if np.any(same):
        k = np.flatnonzero(same)[0]
        i, j = sorted((int(order[k]), int(order[k + 1])))
        raise InvalidPolygonError(f"vertices {i} and {j} coincide at ({v[i, 0]:.6g}, {v[i, 1]:.6g})")


def _check_simple(poly):
    v = poly.vertices
    n = len(v)
    a, b = v, np.roll(v, -1, axis=0)
    # Consecutive edges must not fold back onto each other (a zero-angle spike).
    e_in, e_out = b - a, np.roll(b - a, -1, axis=0)
    spike = (cross(e_in, e_out) == 0) & (np.sum(e_in * e_out, axis=1) < 0)
    if np.any(spike):
        i = int(np.flatnonzero(spike)[0])
        raise InvalidPolygonError(f"polygon folds back on itself at {poly.vertex_name(i + 1)}")
    i, j = np.triu_indices(n, k=2)
    keep = ~((i == 0) & (j == n - 1))
    i, j = i[keep], j[keep]
    hit = segments_intersect(a[i], b[i], a[j], b[j])
    if np.any(hit):
        k = int(np.flatnonzero(hit)[0])
        raise InvalidPolygonError(
            f"polygon is not simple: {poly.edge_name(i[k])} intersects {poly.edge_name(j[k])}"
        )


def check_edges_at_least(poly, l):
    """Every edge of the polygon must be at least ``l`` long (up to REL_TOL)."""
    lengths = poly.edge_lengths
    short = np.flatnonzero(~at_least(lengths, l))
    if short.size:
        i = int(short[0])
        raise InvalidPolygonError(
            f"{poly.edge_name(i)} has length {lengths[i]:.6g}, shorter than l = {l:.6g}"
        )


def check_convex_right_angles(poly):
    """Problem 1: the polygon is convex and every inner angle is at least 90 degrees.

    With ``e_in`` and ``e_out`` the edges entering and leaving a vertex of a
    counter-clockwise polygon, convexity is ``cross(e_in, e_out) >= 0`` and an
    inner angle of at least 90 degrees is ``dot(e_in, e_out) >= 0``; the
    latter is tested with a relative tolerance of REL_TOL so that exact right
    angles given in floating point are accepted.
    """
    v = poly.vertices
    e_in = v - np.roll(v, 1, axis=0)
    e_out = np.roll(v, -1, axis=0) - v
    norms = np.linalg.norm(e_in, axis=1) * np.linalg.norm(e_out, axis=1)
    reflex = np.flatnonzero(cross(e_in, e_out) < -REL_TOL * norms)
    if reflex.size:
        raise InvalidPolygonError(f"polygon is not convex: reflex angle at {poly.vertex_name(reflex[0])}")
    dots = np.sum(e_in * e_out, axis=1)
    acute = np.flatnonzero(dots < -REL_TOL * norms)
    if acute.size:
        i = int(acute[0])
        angle = 180.0 - np.degrees(np.arccos(np.clip(dots[i] / norms[i], -1.0, 1.0)))
        raise InvalidPolygonError(
            f"inner angle {angle:.4g} degrees at {poly.vertex_name(i)} is below 90 degrees"
        )


@dataclass(frozen=True)
class Boundary:
    """The resampled boundary ring of Step 2.

    Attributes
    ----------
    points : (m, 2) float array, counter-clockwise, starting at polygon vertex 0.
    is_vertex : (m,) bool array, True where the point is a vertex of P.
    edge : (m,) int array, the polygon edge each point starts (points j with
        ``edge[j] == i`` lie on edge i, the first of them is vertex i).
    """

    points: np.ndarray
    is_vertex: np.ndarray
    edge: np.ndarray

    @property
    def segments(self):
        m = len(self.points)
        return np.column_stack([np.arange(m), (np.arange(m) + 1) % m])


def resample_boundary(poly, l, spacing=2.0):
    """Step 2: place points V' on the boundary so consecutive points are between l and 2l apart.

    Each edge of length ``L`` is split into ``k`` equal parts, the smallest
    number making a part at most ``spacing * l`` long, kept within
    ``[ceil(L / 2l), floor(L / l)]`` (ranges taken up to REL_TOL).  With the
    default ``spacing = 2`` this is ``k = ceil(L / 2l)``, the fewest boundary
    points (Problem 1 minimises the node count).  A part has length ``L / k``:
    at most ``2l`` as ``k >= L / 2l``, at least ``l`` as ``k <= L / l``; the
    range is never empty because ``L >= l`` (for ``L <= 2l`` it contains 1, for
    ``L > 2l`` it has length ``L / 2l > 1``).  Problem 2 uses a spacing below
    2 (see :func:`equimesh.planar.strip.uniform_triangulation`): a boundary part of
    exactly ``2l`` leaves its midpoint at distance exactly ``l``, and the
    farthest-point insertion then places a point a hair inside it, a sliver.

    Why all boundary points are pairwise at least ``l`` apart in a convex
    polygon with inner angles of at least 90 degrees:

    * on one edge, consecutive points are ``L / k >= l`` apart;
    * on adjacent edges meeting at vertex ``v`` with inner angle ``theta >= 90``,
      points at distances ``s, t`` from ``v`` satisfy
      ``d^2 = s^2 + t^2 - 2 s t cos(theta) >= s^2 + t^2``, and one of ``s, t``
      is 0 (the point is ``v``) or both are ``>= l``;
    * on non-adjacent edges ``e, f``: let ``x in e, y in f`` be a closest
      pair and walk the boundary chain from ``x`` to ``y`` through the whole
      edges ``g_1 .. g_k`` (``k >= 1``) lying between them.  The optimality of
      the closest pair makes the chain leave ``x`` and reach ``y`` at no more
      than 90 degrees to ``xy``; every turn of a polygon whose inner angles are
      at least 90 degrees is at most 90 degrees, so the directions of the
      ``g_i`` measured from ``xy`` decrease within ``[-90, 90]`` and the chain
      returns to the line ``xy``.  Hence two consecutive edges ``g_i, g_{i+1}``
      have directions ``phi >= 0 > psi`` with ``phi - psi <= 90`` (or some
      ``g_i`` is parallel to ``xy``), and projecting the chain on ``xy`` gives
      ``|xy| >= l (cos phi + cos psi) >= l (cos phi + sin phi) >= l``.

    For non-convex polygons (Problem 2) this argument does not apply and the
    separation is checked instead by :func:`check_boundary_separation`.
    """
    v = poly.vertices
    lengths = poly.edge_lengths
    parts = split_counts(lengths, l, spacing)
    points, is_vertex, edge = [], [], []
    for i, (a, b, k) in enumerate(zip(v, np.roll(v, -1, axis=0), parts)):
        j = np.arange(k)[:, None]
        points.append(a + (b - a) * j / k)
        is_vertex.append(np.arange(k) == 0)
        edge.append(np.full(k, i))
    return Boundary(np.vstack(points), np.concatenate(is_vertex), np.concatenate(edge))


def split_counts(lengths, l, spacing=2.0):
    """Number of equal parts for each length: ``ceil(L / (spacing l))`` kept in ``[ceil(L / 2l), floor(L / l)]``.

    See :func:`resample_boundary`; the range is non-empty for ``L >= l``.
    """
    lengths = np.asarray(lengths, dtype=float)
    fewest = np.maximum(1, np.ceil(lengths / (2.0 * l) * (1.0 - REL_TOL)))
    most = np.floor(lengths / l * (1.0 + REL_TOL))
    return np.clip(np.ceil(lengths / (spacing * l) * (1.0 - REL_TOL)), fewest, most).astype(int)


def check_boundary_separation(poly, boundary, l):
    """Lemma 3 (1): mutually visible boundary points are at least ``l`` apart.

    Only pairs closer than ``l`` are examined; such a pair is an error when the
    segment joining them lies in the closed polygon (the points see each
    other).  Holds automatically for Problem 1 (see :func:`resample_boundary`);
    for a non-convex polygon it fails at necks narrower than ``l``.
    """
    pts = boundary.points
    pairs = cKDTree(pts).query_pairs((1.0 - REL_TOL) * l, output_type="ndarray")
    if not len(pairs):
        return
    region = shapely.prepared.prep(poly.shapely())
    lines = shapely.linestrings(np.stack([pts[pairs[:, 0]], pts[pairs[:, 1]]], axis=1))
    gap = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
    for (i, j), line, d in zip(pairs, lines, gap):
        if region.covers(line):
            ei, ej = poly.edge_name(boundary.edge[i]), poly.edge_name(boundary.edge[j])
            raise InvalidPolygonError(
                f"polygon is too narrow for l = {l:.6g}: boundary points on {ei} and {ej} "
                f"see each other at distance {d:.6g} < l"
            )
