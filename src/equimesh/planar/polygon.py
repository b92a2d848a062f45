"""Input polygons: validation and boundary resampling (Step 2 of Algorithm INCREMENT).

Problem 1 (Section 2 of the paper) assumes a convex polygon whose inner angles
are all at least 90 degrees and whose edges are all at least ``l`` long.
Problem 2 (Section 3) drops convexity.  Every violated assumption raises
:class:`~equimesh.errors.InvalidPolygonError` naming the vertex or edge at
fault, with vertex indices counted in the caller's input order and numbers in
the caller's units.

Every geometric quantity is computed in the polygon's local frame
(:class:`~equimesh._geometry.Frame`: translated to the lower-left corner of
its bounding box and scaled by a power of two), so that a polygon far from the
origin is validated as precisely as the same polygon near it.  Validation is
O(n log n) in the number of vertices.
"""

import numbers
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from .._geometry import Frame, cross, orient_sign, power_of_two_scale, segments_intersect, signed_area
from ..errors import InvalidLengthError, InvalidPolygonError
from ..tolerance import MAX_EXTENT, MAX_LENGTH, MIN_LENGTH, REL_TOL, at_least


def real_number(value, name, error):
    """``value`` as a float, raising ``error`` unless it is one real number (not complex, bool or text)."""
    if isinstance(value, (bool, np.bool_, str, bytes)) or not (
        isinstance(value, numbers.Real) or (np.ndim(value) == 0 and np.asarray(value).dtype.kind in "iuf")
    ):
        kind = "complex value " if isinstance(value, numbers.Complex) or np.iscomplexobj(value) else ""
        shown = value.item() if isinstance(value, np.generic) else value
        raise error(f"{name} must be a real number, got {kind}{shown!r}")
    return float(value)


def check_length(l):
    """Return ``l`` as a float, raising :class:`InvalidLengthError` unless it is in the supported range.

    The range ``[MIN_LENGTH, MAX_LENGTH]`` (:mod:`equimesh.tolerance`) keeps
    ``l^2`` a normal float; every computation then runs in a frame where l is
    in ``[1, 2)``.
    """
    value = real_number(l, "target length l", InvalidLengthError)
    if not np.isfinite(value) or value <= 0.0:
        raise InvalidLengthError(f"target length l must be positive and finite, got {value!r}")
    if not MIN_LENGTH <= value <= MAX_LENGTH:
        raise InvalidLengthError(
            f"target length l = {value!r} is outside the supported range [{MIN_LENGTH:g}, {MAX_LENGTH:g}]; "
            "rescale the coordinates"
        )
    return value


def _num(x):
    """A length or angle for a message: the shortest repr that round-trips, so different values print differently."""
    return repr(float(x))


@dataclass(frozen=True)
class Polygon:
    """A validated simple polygon, counter-clockwise.

    Attributes
    ----------
    vertices : (n, 2) float array, the caller's coordinates, counter-clockwise,
        no repeated vertex.
    input_index : (n,) int array, the caller's index of each vertex.
    frame : the local frame every computation runs in.
    local : (n, 2) float array, ``frame.to_local(vertices)``.
    """

    vertices: np.ndarray
    input_index: np.ndarray
    frame: Frame
    local: np.ndarray

    def local_length(self, l):
        """The length ``l`` in the local frame (exact: the scale is a power of two)."""
        return l * self.frame.scale

    @property
    def local_edge_lengths(self):
        return np.linalg.norm(np.roll(self.local, -1, axis=0) - self.local, axis=1)

    @property
    def edge_lengths(self):
        return self.local_edge_lengths / self.frame.scale

    @property
    def local_area(self):
        return signed_area(self.local)

    @property
    def local_perimeter(self):
        return float(np.sum(self.local_edge_lengths))

    @property
    def area(self):
        return self.local_area / self.frame.scale**2

    @property
    def perimeter(self):
        return self.local_perimeter / self.frame.scale

    def vertex_name(self, i):
        j = int(self.input_index[i % len(self.vertices)])
        x, y = self.vertices[i % len(self.vertices)]
        return f"vertex {j} at ({x:.10g}, {y:.10g})"

    def edge_name(self, i):
        n = len(self.vertices)
        a, b = int(self.input_index[i % n]), int(self.input_index[(i + 1) % n])
        return f"edge ({a}, {b})"

    def inner_angle(self, i):
        """Inner angle at vertex ``i``, in degrees (in [0, 360))."""
        n = len(self.local)
        u = self.local[(i - 1) % n] - self.local[i % n]
        w = self.local[(i + 1) % n] - self.local[i % n]
        return float(np.degrees(np.arctan2(cross(w, u), np.dot(w, u))) % 360.0)

    def shapely(self):
        """The polygon in its local frame."""
        return shapely.Polygon(self.local)


def real_array(value, what, error):
    """``value`` as a float array, raising ``error`` ("``what`` must be ...") unless every entry is a real number."""
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):
        raise error(f"{what} must be an array of numbers") from None
    if raw.dtype.kind == "c" or (raw.dtype.kind == "O" and any(isinstance(x, complex) for x in raw.ravel())):
        raise error(f"{what} must be real numbers, got complex values")
    try:
        if raw.dtype.kind not in "iufO":
            raise ValueError
        return np.array(raw, dtype=float)
    except (TypeError, ValueError):
        raise error(f"{what} must be an array of numbers") from None


def _parse_vertices(vertices):
    """The caller's vertices as an ``(n, 2)`` float array of finite numbers, or an error."""
    v = real_array(vertices, "polygon vertices", InvalidPolygonError)
    if v.ndim != 2 or v.shape[1] != 2:
        raise InvalidPolygonError(f"polygon vertices must be an (n, 2) array, got shape {v.shape}")
    bad = np.flatnonzero(~np.all(np.isfinite(v), axis=1))
    if bad.size:
        x, y = map(float, v[bad[0]])
        raise InvalidPolygonError(f"vertex {bad[0]} has a non-finite coordinate ({x!r}, {y!r})")
    return v


def _local_frame(v, l):
    """The frame of ``v``: origin at its bounding box's lower-left corner, l (or the extent) scaled into [1, 2)."""
    origin = v.min(axis=0)
    with np.errstate(over="ignore", invalid="ignore"):
        extent = float(np.max(v.max(axis=0) - origin))
    if not np.isfinite(extent):
        raise InvalidPolygonError("polygon coordinates span more than the floating-point range")
    if l is None:
        return Frame(origin, power_of_two_scale(extent))
    if not extent <= MAX_EXTENT * l:
        raise InvalidPolygonError(
            f"polygon spans {extent:.6g} = {extent / l:.6g} l, more than the {MAX_EXTENT:.0f} l within which "
            f"edge lengths are exact to REL_TOL; use l >= {extent / MAX_EXTENT:.6g}"
        )
    return Frame(origin, power_of_two_scale(l))


def as_polygon(vertices, l=None):
    """Validate a simple polygon and orient it counter-clockwise.

    Checks: an ``(n, 2)`` array of finite real numbers, at least 3 distinct
    vertices, no repeated vertex (a closing copy of the first vertex is
    dropped), not all vertices collinear, no self-intersection (no two edges
    share a point other than the common vertex of consecutive edges) and, when
    ``l`` is given, an extent of at most ``MAX_EXTENT * l``.  The local frame
    scales ``l`` (or, without ``l``, the extent) into ``[1, 2)``.
    """
    v = _parse_vertices(vertices)
    if len(v) > 1 and np.array_equal(v[0], v[-1]):
        v = v[:-1]
    distinct = len(np.unique(v, axis=0))
    if distinct < 3:
        raise InvalidPolygonError(f"a polygon needs at least 3 distinct vertices, got {distinct}")
    _check_no_repeated_vertex(v)
    frame = _local_frame(v, l)
    local = frame.to_local(v)
    _check_not_collinear(local)
    index = np.arange(len(v))
    _check_simple(Polygon(v, index, frame, local))
    low = int(np.lexsort((local[:, 1], local[:, 0]))[0])
    if orient_sign(local[low - 1], local[low], local[(low + 1) % len(v)]) < 0:
        v, index, local = v[::-1].copy(), index[::-1].copy(), local[::-1].copy()
    return Polygon(v, index, frame, local)


def _check_no_repeated_vertex(v):
    order = np.lexsort((v[:, 1], v[:, 0]))
    same = np.all(v[order[1:]] == v[order[:-1]], axis=1)
    if np.any(same):
        k = np.flatnonzero(same)[0]
        i, j = sorted((int(order[k]), int(order[k + 1])))
        raise InvalidPolygonError(f"vertices {i} and {j} coincide at ({v[i, 0]:.10g}, {v[i, 1]:.10g})")


def _check_not_collinear(local):
    other = int(np.flatnonzero(np.any(local != local[0], axis=1))[0])
    if not np.any(orient_sign(local[0], local[other], local)):
        raise InvalidPolygonError("polygon has zero area (all vertices collinear)")


def _check_simple(poly):
    """No two non-consecutive edges share a point, and no two consecutive edges fold onto each other.

    Candidate pairs come from an STRtree of the edges' bounding boxes (O(n log n)
    for polygons whose edges are not all stacked on each other); each candidate
    is decided by the exact :func:`~equimesh._geometry.segments_intersect`.
    """
    v = poly.local
    n = len(v)
    a, b = v, np.roll(v, -1, axis=0)
    e_in, e_out = b - a, np.roll(b - a, -1, axis=0)
    spike = (orient_sign(a, b, np.roll(b, -1, axis=0)) == 0) & (np.sum(e_in * e_out, axis=1) < 0)
    if np.any(spike):
        i = int(np.flatnonzero(spike)[0])
        raise InvalidPolygonError(f"polygon folds back on itself at {poly.vertex_name(i + 1)}")
    tree = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
    i, j = tree.query(tree.geometries)
    gap = j - i
    keep = (gap >= 2) & ~((i == 0) & (j == n - 1))
    i, j = i[keep], j[keep]
    hit = segments_intersect(a[i], b[i], a[j], b[j])
    if np.any(hit):
        k = np.lexsort((j[hit], i[hit]))[0]
        raise InvalidPolygonError(
            f"polygon is not simple (self-intersecting): {poly.edge_name(i[hit][k])} intersects "
            f"{poly.edge_name(j[hit][k])}"
        )


def check_edges_at_least(poly, l):
    """Every edge of the polygon must be at least ``l`` long (up to REL_TOL), compared in the local frame."""
    lengths = poly.local_edge_lengths
    short = np.flatnonzero(~at_least(lengths, poly.local_length(l)))
    if short.size:
        i = int(short[0])
        raise InvalidPolygonError(
            f"{poly.edge_name(i)} has length {_num(poly.edge_lengths[i])}, shorter than l = {_num(l)}"
        )


def check_convex_right_angles(poly):
    """Problem 1: the polygon is convex and every inner angle is at least 90 degrees.

    With ``e_in`` and ``e_out`` the edges entering and leaving a vertex of a
    counter-clockwise polygon, convexity is ``cross(e_in, e_out) >= 0`` and an
    inner angle of at least 90 degrees is ``dot(e_in, e_out) >= 0``; both are
    tested in the local frame with a relative tolerance of REL_TOL so that
    exact right angles and straight vertices given in floating point are
    accepted.
    """
    v = poly.local
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
        raise InvalidPolygonError(
            f"inner angle {poly.inner_angle(i):.4g} degrees at {poly.vertex_name(i)} is below 90 degrees"
        )


@dataclass(frozen=True)
class Boundary:
    """The resampled boundary ring of Step 2, in the polygon's local frame.

    Attributes
    ----------
    points : (m, 2) float array, local coordinates, counter-clockwise,
        starting at polygon vertex 0.
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
    ``[ceil(L / 2l), floor(L / l)]`` (:func:`split_counts`).  With the default
    ``spacing = 2`` this is ``k = ceil(L / 2l)``, the fewest boundary points
    (Problem 1 minimises the node count).  Problem 2 uses a spacing below 2 (see
    :func:`equimesh.planar.strip.uniform_triangulation`): a boundary part of
    exactly ``2l`` leaves its midpoint at distance exactly ``l``, and the
    farthest-point insertion then places a point a hair inside it, a sliver.

    In a convex polygon with inner angles of at least 90 degrees (Problem 1)
    all boundary points are then pairwise at least ``l`` apart; the proof is
    in ``docs/proofs.md``, section "Step 2 boundary separation (Problem 1)".
    For other polygons the separation is checked by
    :func:`check_boundary_separation`.  The points are in the local frame.
    """
    v = poly.local
    parts = split_counts(poly.local_edge_lengths, poly.local_length(l), spacing)
    points, is_vertex, edge = [], [], []
    for i, (a, b, k) in enumerate(zip(v, np.roll(v, -1, axis=0), parts)):
        j = np.arange(k)[:, None]
        points.append(a + (b - a) * j / k)
        is_vertex.append(np.arange(k) == 0)
        edge.append(np.full(k, i))
    return Boundary(np.vstack(points), np.concatenate(is_vertex), np.concatenate(edge))


def split_counts(lengths, l, spacing=2.0):
    """Number of equal parts for each length: ``ceil(L / (spacing l))`` kept in ``[ceil(L / 2l), floor(L / l)]``.

    A part has length ``L / k``: at most ``2l`` as ``k >= L / 2l``, at least
    ``l`` as ``k <= L / l`` (bounds taken up to REL_TOL); the range is never
    empty for ``L >= l`` (for ``L <= 2l`` it contains 1, for ``L > 2l`` it has
    length ``L / 2l > 1``).
    """
    lengths = np.asarray(lengths, dtype=float)
    fewest = np.maximum(1, np.ceil(lengths / (2.0 * l) * (1.0 - REL_TOL)))
    most = np.floor(lengths / l * (1.0 + REL_TOL))
    return np.clip(np.ceil(lengths / (spacing * l) * (1.0 - REL_TOL)), fewest, most).astype(int)


def check_boundary_separation(poly, boundary, l):
    """Lemma 3 (1): mutually visible boundary points are at least ``l`` apart.

    Only pairs closer than ``(1 - REL_TOL) l`` are examined.  Such a pair is
    accepted only when the segment joining them provably leaves the polygon:
    some point of it lies farther than ``REL_TOL l`` outside, i.e. the segment
    is not covered by the polygon grown by ``REL_TOL l``.  Resampled points lie
    on the boundary only up to rounding, so an exact visibility test would skip
    a pair whose segment runs a rounding error outside; a segment that grazes a
    reflex vertex ``r`` counts as visible too, which refuses nothing valid:
    then ``|pr| + |rq|`` is within rounding of ``|pq| < l``, so ``r`` is closer
    than ``l`` to ``p`` or ``q`` (``docs/proofs.md``, "Boundary separation
    (Problem 2)").  Holds automatically for Problem 1 (:func:`resample_boundary`);
    for a non-convex polygon it fails at necks narrower than ``l`` and at
    corners too sharp for the resampled points next to them.

    Raises :class:`InvalidPolygonError` for the closest offending pair, with
    ``points`` the two boundary points in the caller's coordinates.
    """
    pts = boundary.points
    lp = poly.local_length(l)
    pairs = cKDTree(pts).query_pairs((1.0 - REL_TOL) * lp, output_type="ndarray")
    if not len(pairs):
        return
    grown = poly.shapely().buffer(REL_TOL * lp)
    shapely.prepare(grown)
    lines = shapely.linestrings(np.stack([pts[pairs[:, 0]], pts[pairs[:, 1]]], axis=1))
    visible = shapely.covers(grown, lines)
    if not np.any(visible):
        return
    pairs = pairs[visible]
    gap = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
    i, j = pairs[np.lexsort((pairs[:, 1], pairs[:, 0], gap))[0]]
    raise _separation_error(poly, boundary, l, int(i), int(j))


def _separation_error(poly, boundary, l, i, j):
    """The error for boundary points ``i`` and ``j`` closer than ``l`` that see each other."""
    n = len(poly.local)
    p, q = boundary.points[i], boundary.points[j]
    d = _num(np.linalg.norm(q - p) / poly.frame.scale)
    ei, ej = int(boundary.edge[i]), int(boundary.edge[j])
    where = f"boundary points on {poly.edge_name(ei)} and {poly.edge_name(ej)} are {d} apart"
    caller = poly.frame.to_caller(np.array([p, q]))
    corner = ej if (ei + 1) % n == ej else ei if (ej + 1) % n == ei else None
    if corner is not None:
        message = (
            f"the corner at {poly.vertex_name(corner)} ({poly.inner_angle(corner):.6g} degrees) is too sharp "
            f"for l = {_num(l)}: {where}, closer than l; use a smaller l or a wider corner"
        )
    else:
        message = (
            f"polygon is too narrow for l = {_num(l)}: {where} and see each other across the polygon; "
            f"use l <= {d} or widen the polygon there"
        )
    return InvalidPolygonError(message, points=caller)
