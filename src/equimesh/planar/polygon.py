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

import math
import numbers
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
import shapely
from scipy.spatial import cKDTree

from .._geometry import Frame, cross, inner_angle, orient_sign, power_of_two_scale, segments_intersect, signed_area
from ..errors import EquimeshError, InvalidLengthError, InvalidPolygonError
from ..tolerance import MAX_EXTENT, MAX_LENGTH, MIN_LENGTH, REL_TOL, at_least
from . import _corner, _coupled


def real_number(value, name, error):
    """``value`` as a float, raising ``error`` unless it is one real number (not complex, bool or text)."""
    if isinstance(value, (bool, np.bool_, str, bytes)) or not (
        isinstance(value, numbers.Real) or (np.ndim(value) == 0 and np.asarray(value).dtype.kind in "iuf")
    ):
        boolean = isinstance(value, (bool, np.bool_))
        kind = "boolean " if boolean else "complex value " if isinstance(value, numbers.Complex) or np.iscomplexobj(value) else ""
        raise error(f"{name} must be a real number, got {kind}{_plain(value)!r}")
    return float(value)


def check_count(value, name, least=1):
    """``value`` as an int, refusing anything but an integer of at least ``least`` (bool, 2.5, nan included).

    Beyond the paper: the one check of every count a caller gives (grid
    sizes, search counts, ``max_nodes``); numpy integers are accepted.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < least:
        raise EquimeshError(f"{name} must be an integer of at least {least}, got {_plain(value)!r}")
    return int(value)


def _plain(value):
    """``value`` with a numpy scalar as the Python number it holds, so that a message shows ``2.5``, not its numpy repr."""
    return value.item() if isinstance(value, np.generic) else value


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
    """A validated simple polygon, counter-clockwise, possibly with holes (openings).

    Attributes
    ----------
    vertices : (n, 2) float array, the caller's coordinates, no repeated
        vertex; counter-clockwise for the outer boundary, clockwise for a hole
        (the region lies on the left of every ring).
    input_index : (n,) int array, the caller's index of each vertex.
    frame : the local frame every computation runs in.
    local : (n, 2) float array, ``frame.to_local(vertices)``.
    holes : tuple of :class:`Polygon`, the holes' rings (clockwise, same frame).
    label : ``""`` for the outer boundary, ``"hole k"`` for the caller's hole k.

    ``local_area``, ``local_perimeter``, ``area``, ``perimeter`` and
    :attr:`region` are those of the region (outer boundary minus the holes);
    the edge properties and names are those of this ring.
    """

    vertices: np.ndarray
    input_index: np.ndarray
    frame: Frame
    local: np.ndarray
    holes: tuple = ()
    label: str = ""

    @property
    def rings(self):
        """The outer ring, then the holes' rings: every ring with the region on its left."""
        return (self, *self.holes)

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
        return sum(signed_area(ring.local) for ring in self.rings)

    @property
    def local_perimeter(self):
        return sum(float(np.sum(ring.local_edge_lengths)) for ring in self.rings)

    @property
    def area(self):
        return self.local_area / self.frame.scale**2

    @property
    def perimeter(self):
        return self.local_perimeter / self.frame.scale

    @property
    def _of(self):
        return f" of {self.label}" if self.label else ""

    def vertex_name(self, i):
        j = int(self.input_index[i % len(self.vertices)])
        x, y = self.vertices[i % len(self.vertices)]
        return f"vertex {j}{self._of} at ({x:.10g}, {y:.10g})"

    def edge_name(self, i):
        n = len(self.vertices)
        a, b = int(self.input_index[i % n]), int(self.input_index[(i + 1) % n])
        return f"edge ({a}, {b}){self._of}"

    def inner_angle(self, i):
        """Inner angle at vertex ``i``, in degrees (in [0, 360))."""
        return inner_angle(self.local, i)

    @cached_property
    def region(self):
        """The region (outer boundary minus the holes) in its local frame, a shapely polygon built once."""
        return shapely.Polygon(self.local, [hole.local for hole in self.holes])


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


def _parse_vertices(vertices, what="polygon"):
    """The caller's vertices as an ``(n, 2)`` float array of finite numbers, or an error naming ``what``."""
    v = real_array(vertices, f"{what} vertices", InvalidPolygonError)
    if v.ndim != 2 or v.shape[1] != 2:
        raise InvalidPolygonError(f"{what} vertices must be an (n, 2) array, got shape {v.shape}")
    bad = np.flatnonzero(~np.all(np.isfinite(v), axis=1))
    if bad.size:
        x, y = map(float, v[bad[0]])
        of = "" if what == "polygon" else f" of {what}"
        raise InvalidPolygonError(f"vertex {bad[0]}{of} has a non-finite coordinate ({x!r}, {y!r})")
    return v


def _local_frame(v, l):
    """The frame of ``v``: origin at its bounding box's lower-left corner, l (or the extent) scaled into [1, 2)."""
    origin = v.min(axis=0)
    with np.errstate(over="ignore"):  # finite coordinates: the span may overflow, never be invalid
        extent = float(np.max(v.max(axis=0) - origin))
    if not np.isfinite(extent):
        raise InvalidPolygonError("polygon coordinates span more than the floating-point range")
    if l is None:
        return Frame(origin, power_of_two_scale(extent))
    if not extent <= MAX_EXTENT * l:
        raise InvalidPolygonError(
            f"polygon spans {_num(extent)} = {_num(extent / l)} l, more than the {MAX_EXTENT:.0f} l within which "
            f"edge lengths are exact to REL_TOL; use l >= {_num(extent / MAX_EXTENT)}"
        )
    return Frame(origin, power_of_two_scale(l))


def as_polygon(vertices, l=None, holes=None):
    """Validate a simple polygon, oriented counter-clockwise, and its holes (openings), clockwise.

    Checks: an ``(n, 2)`` array of finite real numbers, at least 3 distinct
    vertices, no repeated vertex (a closing copy of the first vertex is
    dropped), not all vertices collinear, no self-intersection (no two edges
    share a point other than the common vertex of consecutive edges) and, when
    ``l`` is given, an extent of at most ``MAX_EXTENT * l``.  The local frame
    scales ``l`` (or, without ``l``, the extent) into ``[1, 2)``.  Each hole
    passes the same checks and :func:`_check_holes` (inside the polygon, apart
    from its boundary and from each other).
    """
    v = _ring_vertices(_parse_vertices(vertices), "")
    outer = _ring(v, _local_frame(v, l), "")
    if holes is None:
        return outer
    return replace(outer, holes=_check_holes(outer, holes, l))


def _ring_vertices(v, label):
    """``v`` without a closing copy of its first vertex; at least 3 distinct vertices, none repeated."""
    if len(v) > 1 and np.array_equal(v[0], v[-1]):
        v = v[:-1]
    distinct = len(np.unique(v, axis=0))
    if distinct < 3:
        raise InvalidPolygonError(f"{label or 'a polygon'} needs at least 3 distinct vertices, got {distinct}")
    _check_no_repeated_vertex(v, f" of {label}" if label else "")
    return v


def _ring(v, frame, label):
    """A simple ring in ``frame``: counter-clockwise for the outer boundary (``label`` empty), clockwise for a hole."""
    local = frame.to_local(v)
    _check_not_collinear(local, label or "polygon")
    index = np.arange(len(v))
    _check_simple(Polygon(v, index, frame, local, label=label))
    low = int(np.lexsort((local[:, 1], local[:, 0]))[0])
    counter_clockwise = orient_sign(local[low - 1], local[low], local[(low + 1) % len(v)]) > 0
    if counter_clockwise == bool(label):
        v, index, local = v[::-1].copy(), index[::-1].copy(), local[::-1].copy()
    return Polygon(v, index, frame, local, label=label)


def _check_holes(outer, holes, l):
    """The holes as clockwise rings: each inside P, none touching its boundary or another hole.

    With ``l`` given, also Lemma 3 (1) across boundaries: every hole at least
    ``l`` (up to REL_TOL) from the outer boundary and from every other hole.
    """
    if isinstance(holes, (str, bytes)) or not hasattr(holes, "__iter__"):
        raise InvalidPolygonError(f"holes must be a list of polygons, got {type(holes).__name__}")
    lo, hi = outer.vertices.min(axis=0), outer.vertices.max(axis=0)
    rings = []
    for k, hole in enumerate(holes):
        label = f"hole {k}"
        v = _parse_vertices(hole, label)
        out = np.flatnonzero(np.any((v < lo) | (v > hi), axis=1))
        if out.size:
            x, y = v[out[0]]
            raise InvalidPolygonError(f"{label} is not inside the polygon: its vertex {out[0]} at ({x:.10g}, {y:.10g}) lies outside")
        rings.append(_ring(_ring_vertices(v, label), outer.frame, label))
    if not rings:
        return ()
    region = shapely.Polygon(outer.local)
    shapes = [shapely.Polygon(ring.local) for ring in rings]
    for ring, shape in zip(rings, shapes):
        if shapely.intersects(region.exterior, shape.exterior):
            raise InvalidPolygonError(f"{ring.label} overlaps the boundary of the polygon (their edges cross or touch)")
        if not region.contains(shape):
            raise InvalidPolygonError(f"{ring.label} lies outside the polygon")
    tree = shapely.STRtree(shapes)
    i, j = tree.query(shapes, predicate="intersects")
    if np.any(i < j):
        a, b = sorted(min(zip(i[i < j].tolist(), j[i < j].tolist())))
        raise InvalidPolygonError(f"hole {a} and hole {b} overlap")
    if l is not None:
        _check_holes_apart(outer, rings, shapes, tree, l)
    return tuple(rings)


def _check_holes_apart(outer, rings, shapes, tree, l):
    """Lemma 3 (1) across boundaries: each hole at least ``l`` from the outer boundary and from every other hole."""
    lp = outer.local_length(l)
    gap = shapely.distance(shapely.LinearRing(outer.local), [shape.exterior for shape in shapes])
    close = np.flatnonzero(~at_least(gap, lp))
    if close.size:
        k = int(close[0])
        d = _num(gap[k] / outer.frame.scale)
        raise InvalidPolygonError(
            f"{rings[k].label} is {d} from the boundary of the polygon, closer than l = {_num(l)} "
            f"(Lemma 3 (1)); move it or use l <= {d}"
        )
    i, j = tree.query(shapes, predicate="dwithin", distance=lp)
    keep = i < j
    i, j = i[keep], j[keep]
    gap = shapely.distance(np.array(shapes)[i], np.array(shapes)[j])
    close = np.flatnonzero(~at_least(gap, lp))
    if close.size:
        k = close[np.lexsort((j[close], i[close]))[0]]
        d = _num(gap[k] / outer.frame.scale)
        raise InvalidPolygonError(
            f"hole {i[k]} and hole {j[k]} are {d} apart, closer than l = {_num(l)} (Lemma 3 (1)); "
            f"move them apart or use l <= {d}"
        )


def _check_no_repeated_vertex(v, of=""):
    order = np.lexsort((v[:, 1], v[:, 0]))
    same = np.all(v[order[1:]] == v[order[:-1]], axis=1)
    if np.any(same):
        k = np.flatnonzero(same)[0]
        i, j = sorted((int(order[k]), int(order[k + 1])))
        raise InvalidPolygonError(f"vertices {i} and {j}{of} coincide at ({v[i, 0]:.10g}, {v[i, 1]:.10g})")


def _check_not_collinear(local, what):
    other = int(np.flatnonzero(np.any(local != local[0], axis=1))[0])
    if not np.any(orient_sign(local[0], local[other], local)):
        raise InvalidPolygonError(f"{what} has zero area (all vertices collinear)")


def _check_simple(poly):
    """No two non-consecutive edges share a point, and no two consecutive edges fold onto each other.

    Candidate pairs come from an STRtree of the edges' bounding boxes (O(n log n)
    for polygons whose edges are not all stacked on each other); each candidate
    is decided by the exact :func:`~equimesh._geometry.segments_intersect`.
    """
    what = poly.label or "polygon"
    v = poly.local
    n = len(v)
    a, b = v, np.roll(v, -1, axis=0)
    e_in, e_out = b - a, np.roll(b - a, -1, axis=0)
    spike = (orient_sign(a, b, np.roll(b, -1, axis=0)) == 0) & (np.sum(e_in * e_out, axis=1) < 0)
    if np.any(spike):
        i = int(np.flatnonzero(spike)[0])
        raise InvalidPolygonError(f"{what} folds back on itself at {poly.vertex_name(i + 1)}")
    tree = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
    i, j = tree.query(tree.geometries)
    gap = j - i
    keep = (gap >= 2) & ~((i == 0) & (j == n - 1))
    i, j = i[keep], j[keep]
    hit = segments_intersect(a[i], b[i], a[j], b[j])
    if np.any(hit):
        k = np.lexsort((j[hit], i[hit]))[0]
        raise InvalidPolygonError(
            f"{what} is not simple (self-intersecting): {poly.edge_name(i[hit][k])} intersects "
            f"{poly.edge_name(j[hit][k])}"
        )


def check_edges_at_least(poly, l):
    """Every edge of the polygon and of its holes must be at least ``l`` long (up to REL_TOL), in the local frame.

    Proven necessary for Theorems 1 and 3: both ends of a side are vertices of
    any triangulation of P, and the mesh edges on the side add up to its length.
    """
    for ring in poly.rings:
        short = np.flatnonzero(~at_least(ring.local_edge_lengths, poly.local_length(l)))
        if short.size:
            i = int(short[0])
            raise InvalidPolygonError(
                "no mesh with every edge in [l, 2l] exists (both ends of a side are nodes, so some mesh edge on it "
                f"is no longer than the side): {ring.edge_name(i)} has length {_num(ring.edge_lengths[i])}, "
                f"shorter than l = {_num(l)}"
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
            f"inner angle {poly.inner_angle(i):.10g} degrees at {poly.vertex_name(i)} is below 90 degrees"
        )


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


#: Corners of P with an inner angle below this many degrees get staggered
#: Step 2 points (:func:`stagger`).  At 60 degrees or more, points at distances
#: ``s, t >= l`` from the corner on its two sides are at least ``min(s, t) >= l``
#: apart (law of cosines), so equal parts need nothing more
#: (docs/proofs.md, "Sharp corners").
SHARP_CORNER = 60.0


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


def stagger(angle, l, reach):
    """The staggered Step 2 points next to a corner of inner angle ``angle`` (degrees), up to ``reach`` from it.

    Returns ``(leaving, arriving)``: distances from the corner of the points
    on the side leaving it (counter-clockwise) and on the side arriving at it.
    For a corner of at least :data:`SHARP_CORNER` degrees both are empty.
    Otherwise the points ``k l`` for ``k = 1 .. K``, ``K = ceil(1 / sin angle)``,
    alternate between the sides (:func:`_multiples`): along each side the
    parts are ``2l`` (``l`` for the first leaving part), and two points of
    different sides are at least ``l`` apart at any angle because their
    distances from the corner differ by at least ``l``; past ``K l`` the sides
    themselves are ``l`` apart (docs/proofs.md, "Sharp corners").
    """
    return _multiples(angle, l, min(_stagger_count(angle), math.floor(reach / l) + 1))


def _multiples(angle, l, count):
    """The points ``k l``, ``k = 1 .. count``, of a sharp corner: odd ``k`` leaving, even ``k`` arriving.

    Where ``2 k l sin(angle / 2) > l`` the two points at ``k l`` on both sides
    are ``l`` apart already, so ``k l`` is placed on both (parts of ``l``: a
    ``2l`` part there would leave its midpoint ``l`` from every point, and
    the insertion a sliver against it).
    """
    k = np.arange(1, count + 1)
    both = 2.0 * k * math.sin(math.radians(angle) / 2.0) >= 1.0 + REL_TOL
    return k[(k % 2 == 1) | both] * l, k[(k % 2 == 0) | both] * l


def _stagger_count(angle):
    """``K = ceil(1 / sin angle)`` staggered points for a corner sharper than :data:`SHARP_CORNER`, else 0."""
    if not angle < SHARP_CORNER * (1.0 - REL_TOL):
        return 0
    return math.ceil((1.0 - REL_TOL) / math.sin(math.radians(angle)))


def stagger_reach(angle, l):
    """How far from a corner of ``angle`` degrees :func:`stagger` places points: ``K l`` (0 if not sharp)."""
    return _stagger_count(angle) * l


def side_positions(lengths, angles, l, spacing=2.0):
    """Step 2 on a closed ring of sides: where each side's points lie, staggered next to sharp corners.

    Side ``i`` runs from corner ``i`` (inner angle ``angles[i]`` degrees) to
    corner ``i + 1`` and is ``lengths[i]`` long.  Returns one
    ``(numerators, denominator)`` pair per side: its points lie at the
    fractions ``numerators / denominator`` of the side, the first (0) being
    corner ``i``.  Shared by the polygon's Step 2 and the surface outline.

    * Next to a corner sharper than :data:`SHARP_CORNER` the points of
      :func:`stagger` are placed; between the last staggered point from each
      end, the middle of length ``M`` is split into ``k`` equal parts by
      :func:`split_counts` (``l <= M / k <= 2l``).  A side at least
      ``stagger_reach`` of both its corners plus ``l`` long keeps them all.
    * A side with no staggered point is split into equal parts exactly as the
      paper's Step 2 (numerators ``0 .. k - 1``, denominator ``k``), bit for
      bit.
    * Sides too short for all their staggered points are placed by
      :func:`_separate_short_sides`; then each sharp corner still closer
      than ``l`` (also one whose sides fit their staggers but end, shorter
      than the proven length, near a staggered point of the other side) is
      decided by :func:`_place_corners_on_a_grid`.  Every part is in
      ``[l, 2l]`` in every case (docs/proofs.md, "Sharp corners").
    """
    lengths = np.asarray(lengths, dtype=float)
    n = len(lengths)
    reach = [max(lengths[i - 1], lengths[i]) for i in range(n)]
    corners = [stagger(a, l, r) for a, r in zip(angles, reach)]
    sides, short = [], []
    for i, length in enumerate(lengths):
        start, end = _chains(corners, i, length)
        if (len(start) or len(end)) and not at_least(length - start.max(initial=0.0) - end.max(initial=0.0), l):
            short.append(i)
        sides.append(_place(length, start, end, l, spacing))
    if short:
        _separate_short_sides(sides, short, corners, lengths, angles, l, spacing)
    if short or not all(at_least(_corner_gap(sides, lengths, angles, l, c), l) for c in range(n)):
        _place_corners_on_a_grid(sides, lengths, angles, l, spacing)
    return sides


def _chains(corners, i, length):
    """The staggered points of side ``i`` below ``length``: from its first corner, and from its last (distances from it)."""
    start, end = corners[i][0], corners[(i + 1) % len(corners)][1]
    return start[start < length], end[end < length]


def _place(length, start, end, l, spacing):
    """A side of ``length`` with the staggered points ``start`` (from its first corner) and ``end`` (from its last).

    Staggered points that leave a middle shorter than ``l`` are dropped, the
    farthest from its corner first; the middle is split by
    :func:`split_counts`.
    """
    while (len(start) or len(end)) and not at_least(length - start.max(initial=0.0) - end.max(initial=0.0), l):
        if start.max(initial=0.0) >= end.max(initial=0.0):
            start = start[:-1]
        else:
            end = end[:-1]
    if not len(start) and not len(end):
        k = int(split_counts([length], l, spacing)[0])
        return np.arange(k, dtype=float), float(k)
    first, last = start.max(initial=0.0), length - end.max(initial=0.0)
    k = int(split_counts([last - first], l, spacing)[0])
    middle = first + (last - first) * np.arange(1, k) / k
    return np.concatenate([[0.0], start, middle, length - end[::-1]]), length


#: Rounds in which :func:`_separate_short_sides` lets each short side take its
#: best candidate given its neighbours: a bound on the work, not a tolerance.
#: One round settles a side whose neighbours are fixed; the extra rounds let
#: two short sides of one sharp corner (thin triangles) adapt to each other.
SETTLE_PASSES = 4


def _separate_short_sides(sides, short, corners, lengths, angles, l, spacing):
    """Place the ``short`` sides (in place) so that the two sides of every sharp corner are ``l`` apart.

    First each short side takes the best of its candidates
    (:func:`_short_side`), again when a neighbour changed, for at most
    :data:`SETTLE_PASSES` rounds.  Then each sharp corner still below ``l``
    (:func:`_corner_gap`), in order, is tried with its stagger mirrored (odd
    ``k`` on the arriving side): its two sides are placed again (and the
    sides next to them) and the trial is kept if it raises the smallest gap
    at their corners.  Both rounds run first with the staggers alone, then,
    if a corner is still below ``l``, with multiples of ``l`` from the other
    corners too.  Deterministic; the sides keep parts in ``[l, 2l]``.
    """
    n = len(lengths)
    flipped, free = [False] * n, list(short)

    def settle(sides, free, flipped, multiples):
        dirty = set(free)
        for _ in range(SETTLE_PASSES):
            for i in [i for i in free if i in dirty]:
                dirty.discard(i)
                best = _short_side(i, sides, lengths, angles, l, spacing, flipped, multiples)
                if best is not sides[i]:
                    sides[i] = best
                    dirty |= {(i - 1) % n, (i + 1) % n}
            if not dirty & set(free):
                return

    def lowest(sides, changed):
        return min(_corner_gap(sides, lengths, angles, l, c % n) for i in changed for c in (i, i + 1))

    for multiples in (False, True):
        settle(sides, free, flipped, multiples)
        for c in sorted({j % n for i in short for j in (i, i + 1)}):
            if at_least(_corner_gap(sides, lengths, angles, l, c), l):
                continue
            trial, mirrored = list(sides), list(corners)
            mirrored[c] = corners[c][::-1]
            for i in ((c - 1) % n, c):
                trial[i] = _place(lengths[i], *_chains(mirrored, i, lengths[i]), l, spacing)
            trial_flipped = flipped[:c] + [not flipped[c]] + flipped[c + 1 :]
            trial_free = sorted(set(free) | {(c - 1) % n, c})
            near = sorted({i % n for i in range(c - 2, c + 2)} & set(trial_free))
            settle(trial, near, trial_flipped, multiples)
            if lowest(trial, near) > lowest(sides, near):
                sides[:], corners[:], flipped[:], free = trial, mirrored, trial_flipped, trial_free
        if at_least(lowest(sides, range(n)), l):
            return


def _short_side(i, sides, lengths, angles, l, spacing, flipped, multiples):
    """The placement of side ``i``: its current one if its sharp corners are separated, else the best candidate.

    Candidates keep a prefix of a chain from each end and a middle of ``l``
    to ``3l``: at a sharp corner its stagger continued along the side
    (:func:`_multiples` up to the side's length, mirrored where
    ``flipped``), at another corner nothing or, with ``multiples``, the
    multiples of ``l``, so that the last part before it can be ``l``.  They
    are tried in order (by start, then by end; the longest stagger first,
    the fewest multiples first) and the first whose :func:`_corner_gap` at
    both ends is at least ``l`` (up to REL_TOL) is taken, else the one with
    the largest gap.
    """
    n = len(lengths)
    length = lengths[i]

    def gap(side):
        trial = {(i - 1) % n: sides[(i - 1) % n], (i + 1) % n: sides[(i + 1) % n], i: side}
        return min(_corner_gap(trial, lengths, angles, l, c % n) for c in (i, i + 1))

    best, best_gap = sides[i], gap(sides[i])
    if at_least(best_gap, l):
        return best
    count = math.floor(length / l * (1.0 + REL_TOL))

    def chain(c, arriving):
        if not _stagger_count(angles[c]):
            return np.arange(1, count * multiples + 1) * l
        return _multiples(angles[c], l, count)[int(arriving) ^ int(flipped[c])]

    def prefixes(c, points):
        sizes = range(len(points) + 1)
        return sizes[::-1] if _stagger_count(angles[c]) else sizes

    start, end = chain(i, False), chain((i + 1) % n, True)
    start, end = start[start < length], end[end < length]
    reach_start, reach_end = np.append(0.0, start), np.append(0.0, end)
    for a in prefixes(i, start):
        for b in prefixes((i + 1) % n, end):
            middle = length - reach_start[a] - reach_end[b]
            if not at_least(middle, l) or at_least(middle, 3.0 * l):
                continue
            side = _place(length, start[:a], end[:b], l, spacing)
            g = gap(side)
            if at_least(g, l):
                return side
            if g > best_gap:
                best, best_gap = side, g
    return best


def _place_corners_on_a_grid(sides, lengths, angles, l, spacing):
    """Each sharp corner still closer than ``l`` after :func:`_separate_short_sides`, placed by :func:`._corner.place_corner`.

    The two sides of the corner are placed again (:func:`_grid_sides`):
    both free; the leaving side kept; the arriving one kept; or, for a side
    shared with the next (previous) sharp corner, that corner placed first
    with both its sides free and this one then with the shared side kept,
    or the other way round; then with each neighbouring sharp corner
    jointly; last, with the whole run of three or more sharp corners it
    belongs to (:func:`_run`), jointly (:func:`_grid_chain`).  The first
    trial after which every corner it touched, and their neighbours, have a
    :func:`_corner_gap` of at least ``l`` is taken, in place.  A corner that
    :func:`._corner.corner_unplaceable` proves impossible even with every
    pair checked ends the search: the ring cannot be separated, and
    :func:`check_boundary_separation` refuses it, naming the first such
    corner.  Every part stays in ``[l, 2l]``.  Deterministic.
    """
    n = len(lengths)
    free, leaving, arriving = (False, False), (True, False), (False, True)
    for c in range(n):
        if at_least(_corner_gap(sides, lengths, angles, l, c), l):
            continue
        if _corner.corner_unplaceable(math.radians(angles[c]), (lengths[c], lengths[c - 1]), l, (math.inf, math.inf)):
            return
        after, before = (c + 1) % n, (c - 1) % n
        trials = (
            [(c, free)], [(c, leaving)], [(c, arriving)],
            [(after, free), (c, leaving)], [(before, free), (c, arriving)],
            [(c, free), (after, arriving)], [(c, free), (before, leaving)],
            [(c, PAIR)], [(before, PAIR)], [(c, CHAIN)],
        )
        for steps in trials:
            if not all(_stagger_count(angles[corner]) for corner, _ in steps):
                continue
            trial, touched = list(sides), set()
            for corner, keep in steps:
                if keep in (PAIR, CHAIN):
                    run = [corner, (corner + 1) % n] if keep is PAIR else _run(lengths, angles, l, corner)
                    # a run of two is the pair's trial
                    trial = trial and (keep is PAIR or len(run) > 2) and _grid_chain(trial, lengths, angles, l, spacing, run)
                else:
                    run = [corner]
                    trial = trial and _grid_sides(trial, lengths, angles, l, spacing, corner, keep)
                touched |= {(k + d) % n for k in run for d in (-1, 0, 1)}
            if trial and all(at_least(_corner_gap(trial, lengths, angles, l, k), l) for k in touched):
                sides[:] = trial
                break


#: The trials of :func:`_place_corners_on_a_grid` placing a corner and the next one jointly, and its whole run.
PAIR, CHAIN = "pair", "chain"


def _run(lengths, angles, l, c):
    """The run of sharp corners through the sharp corner ``c``: consecutive, each two sharing a side that couples them.

    Coupled as :func:`._coupled.shared` says (no longer than ``K_1 l +
    K_2 l + 4l``); in ring order, at most all corners but one.
    """
    n = len(lengths)

    def joined(k):  # corners k and k + 1 (sharp), sharing side k
        return _coupled.shared((math.radians(angles[k]), math.radians(angles[(k + 1) % n])), lengths[k], l)

    run = [c]
    while len(run) < n - 1 and _stagger_count(angles[(run[-1] + 1) % n]) and joined(run[-1]):
        run.append((run[-1] + 1) % n)
    while len(run) < n - 1 and _stagger_count(angles[run[0] - 1]) and joined((run[0] - 1) % n):
        run.insert(0, (run[0] - 1) % n)
    return run


def _grid_chain(sides, lengths, angles, l, spacing, run):
    """``sides`` with the sides of the corners ``run`` (consecutive) placed by :func:`._coupled.place_chain`, or None.

    None too when a corner is not sharp.  The shared sides take the points
    found; the first and last side are completed by :func:`_grid_side`.
    """
    if not all(_stagger_count(angles[c]) for c in run):
        return None
    n, m = len(lengths), len(run)
    edges = [(run[0] - 1 + k) % n for k in range(m + 1)]  # T_0 .. T_m
    found = _coupled.place_chain(tuple(math.radians(angles[c]) for c in run), tuple(lengths[i] for i in edges), l)
    if found is None:
        return None
    trial = list(sides)
    for i, points in zip(edges[1:-1], found[1:-1]):
        trial[i] = np.concatenate([[0.0], points[:-1]]), lengths[i]
    for i, points, c, leaving in ((edges[0], found[0], run[0], False), (edges[-1], found[-1], run[-1], True)):
        trial[i] = _grid_side(lengths[i], points, _from_corner(sides, lengths, c, i), leaving, l, spacing)
    return trial


def _grid_sides(sides, lengths, angles, l, spacing, c, keep):
    """``sides`` with the two sides of corner ``c`` (leaving, arriving) placed by :func:`._corner.place_corner`, or None.

    The sides flagged in ``keep`` are passed as they are (:func:`_from_corner`).
    """
    n = len(lengths)
    theta = math.radians(angles[c])
    reach = _corner.corner_reach(theta, l)
    ends = (c, (c - 1) % n)
    near = [_from_corner(sides, lengths, c, i) for i in ends]
    fixed = [_corner.cut(points, lengths[i], reach, l) if kept else None for i, points, kept in zip(ends, near, keep)]
    found = _corner.place_corner(theta, tuple(lengths[i] for i in ends), l, fixed)
    if found is None:
        return None
    trial = list(sides)
    for i, points, now in zip(ends, found, near):
        trial[i] = _grid_side(lengths[i], points, now, i == c, l, spacing)
    return trial


def _from_corner(sides, lengths, c, i):
    """The points of side ``i`` (``c`` leaving corner ``c``, ``c - 1`` arriving) by distance from corner ``c``, far end included."""
    num, den = sides[i]
    positions = num[1:] / den * lengths[i]
    return np.append(positions if i == c else (lengths[i] - positions)[::-1], lengths[i])


def _grid_side(length, points, now, leaving, l, spacing):
    """A side from :func:`._corner.place_corner`'s ``points`` (by distance from the corner), as ``(positions, length)``.

    Where the grid cut the side short (past ``K l``), its points ``now`` at
    least ``l`` beyond the cut are kept and :func:`_place` splits the middle
    between, at least ``l`` long, into parts of ``[l, 2l]``; the kept points
    are consecutive points of a side, so their parts are in ``[l, 2l]`` too.
    """
    if points[-1] == length:
        inner = points[:-1]
        return np.concatenate([[0.0], inner if leaving else (length - inner)[::-1]]), length
    kept = now[(now >= points[-1] + l) & (now < length)]
    far = (length - kept)[::-1]
    return _place(length, points, far, l, spacing) if leaving else _place(length, far, points, l, spacing)


def _corner_gap(sides, lengths, angles, l, c):
    """The smallest distance between Step 2 points of the two sides of corner ``c`` (``inf`` if it is not sharp).

    Far corners count, the corner itself not.  Points farther than ``K l >= l
    / sin theta`` from the corner are at least ``l`` from the whole other side
    and are left out, so a gap of at least ``l`` is reported as such but not
    always exactly.  At a corner of at least :data:`SHARP_CORNER` degrees
    every two such points are ``l`` apart (docs/proofs.md, "Sharp corners").
    """
    reach = _stagger_count(angles[c]) * l
    if not reach:
        return math.inf
    (num_a, den_a), (num_b, den_b) = sides[c], sides[(c - 1) % len(lengths)]
    a = np.append(num_a[1:] / den_a * lengths[c], lengths[c])
    b = lengths[c - 1] * (1.0 - num_b / den_b)
    a, b = a[a < reach], b[b < reach]
    if not len(a) or not len(b):
        return math.inf
    squared = a[:, None] ** 2 + b[None, :] ** 2 - 2.0 * math.cos(math.radians(angles[c])) * a[:, None] * b[None, :]
    return math.sqrt(max(float(squared.min()), 0.0))


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
    ``points`` the two boundary points in the caller's coordinates.  The
    message says what is proven (docs/proofs.md, "Sharp corners"): that no
    mesh with every edge in ``[l, 2l]`` exists (:func:`_unmeshable_corner`),
    that no Step 2 can meet Lemma 3 (1) at a corner (its first points,
    :func:`_unseparable_corner`; or all its points, decided on a grid,
    :func:`_unplaceable_corner` at the corners of the offending pairs, or
    :func:`_unplaceable_chain` at two or more of them in a row), or neither (a
    corner or neck this method does not handle).
    """
    pts = boundary.points
    lp = poly.local_length(l)
    pairs = cKDTree(pts).query_pairs((1.0 - REL_TOL) * lp, output_type="ndarray")
    if not len(pairs):
        return
    grown = poly.region.buffer(REL_TOL * lp)
    shapely.prepare(grown)
    lines = shapely.linestrings(np.stack([pts[pairs[:, 0]], pts[pairs[:, 1]]], axis=1))
    visible = shapely.covers(grown, lines)
    if not np.any(visible):
        return
    pairs = pairs[visible]
    gap = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
    i, j = pairs[np.lexsort((pairs[:, 1], pairs[:, 0], gap))[0]]
    raise (
        _unmeshable_corner(poly, l)
        or _unseparable_corner(poly, l)
        or _unplaceable_corner(poly, l, _corners_of(poly, boundary, pairs))
        or _unplaceable_chain(poly, l, _corners_of(poly, boundary, pairs))
        or _separation_error(poly, boundary, l, int(i), int(j))
    )


def _corners(poly):
    """Every corner of every ring: ``(ring, i, theta, leaving, arriving)``, the angle in radians, side lengths local."""
    for ring in poly.rings:
        lengths = ring.local_edge_lengths
        for i in range(len(lengths)):
            yield ring, i, math.radians(ring.inner_angle(i)), lengths[i], lengths[i - 1]


def _chord(a, b, theta):
    """The distance between points at distances ``a`` and ``b`` from a corner of angle ``theta``, on its two sides."""
    return math.sqrt(max(a * a + b * b - 2.0 * a * b * math.cos(theta), 0.0))


def _first_node(length, lp):
    """Where the first node after a corner can lie on a side of ``length``: ``(lowest, highest)`` distance from it.

    The side is split into parts in ``[l, 2l]``: the first part ``f`` is at
    most ``2l`` and leaves 0 or at least ``l``, so ``f = length`` below
    ``2l`` and ``f`` in ``[l, min(2l, length - l)]`` past ``2l`` (``[l, 2l]``
    at ``2l``).  The range is widened by REL_TOL, the tolerance of the checks
    on parts and edges, so that it contains every placement they accept.
    """
    if length < 2.0 * lp * (1.0 - REL_TOL):
        return length, length
    high = 2.0 * lp if length <= 2.0 * lp * (1.0 + REL_TOL) else min(2.0 * lp, length - lp)
    return (1.0 - REL_TOL) * lp, high * (1.0 + REL_TOL)


def _unmeshable_corner(poly, l):
    """The error for the first corner at which no mesh with every edge in ``[l, 2l]`` exists, or None.

    A side of length ``beta < 2l`` at a corner ``v`` of angle ``theta`` is a
    single mesh edge ``v b`` (:func:`_first_node`).  The triangle on it has
    a third node ``q`` with ``|v q|`` in ``[l, 2l]`` and the segment ``v q``
    in P, so ``q`` lies in the sector of radii ``l`` to ``2l`` between the
    two sides; its farthest point from ``b`` is at radius ``l`` or ``2l`` on
    the other side (radii widened by REL_TOL, the tolerance of the edge
    checks).  When both are closer than ``l`` to ``b``, the edge
    ``q b`` is shorter than ``l`` in every mesh: that is
    ``beta < 2 l cos theta`` and ``beta^2 - 4 l beta cos theta + 3 l^2 < 0``
    (docs/proofs.md, "Sharp corners", the sector lemma).
    """
    lp = poly.local_length(l)
    for ring, i, theta, leaving, arriving in _corners(poly):
        for side, beta in ((i, leaving), (i - 1, arriving)):
            far = max(_chord(r, beta, theta) for r in ((1.0 - REL_TOL) * lp, 2.0 * lp * (1.0 + REL_TOL)))
            if beta < 2.0 * lp * (1.0 - REL_TOL) and far < (1.0 - REL_TOL) * lp:
                c = math.cos(theta)
                low, need = (2.0 * c - math.sqrt(4.0 * c * c - 3.0)) * l, 2.0 * c * l
                return InvalidPolygonError(
                    f"no mesh with every edge in [l, 2l] exists for l = {_num(l)}: at the corner at "
                    f"{ring.vertex_name(i)} ({math.degrees(theta):.6g} degrees) {ring.edge_name(side)} is "
                    f"{_num(beta / poly.frame.scale)} long, a single mesh edge, and the third node of its triangle "
                    f"would be closer than l to its other end, {ring.vertex_name(side if side < i else i + 1)} "
                    f"(docs/proofs.md, 'Sharp corners'); at this angle that side must be at least {need:.10g} long "
                    f"(or at most {low:.10g})"
                )
    return None


def _unseparable_corner(poly, l):
    """The error for the first corner at which no boundary resampling meets Lemma 3 (1), or None.

    Any Step 2 places on each side a first point within :func:`_first_node`'s
    range.  :func:`_chord` is convex in each distance, so if it is below ``l``
    at the four ends of the two ranges, the first points of the two sides are
    closer than ``l`` wherever they lie; when the triangle of the corner and
    the far ends of the ranges lies in P (grown by ``REL_TOL l``, as in
    :func:`check_boundary_separation`), they also see each other.  Then no
    boundary resampling meets Lemma 3 (1), which this method and the paper's
    need; it is not a proof that no mesh exists (docs/proofs.md, "Sharp
    corners").
    """
    lp = poly.local_length(l)
    grown = poly.region.buffer(REL_TOL * lp)
    for ring, i, theta, leaving, arriving in _corners(poly):
        ends = [(a, b) for a in _first_node(leaving, lp) for b in _first_node(arriving, lp)]
        if theta < math.pi and max(_chord(a, b, theta) for a, b in ends) < (1.0 - REL_TOL) * lp:
            if not _sees_within(grown, ring, i, *ends[-1]):
                continue
            need = _num((stagger_reach(math.degrees(theta), lp) + lp) / poly.frame.scale)
            return InvalidPolygonError(
                f"the corner at {ring.vertex_name(i)} ({math.degrees(theta):.6g} degrees) cannot meet Lemma 3 (1) "
                f"for l = {_num(l)}: with sides of {_num(leaving / poly.frame.scale)} and "
                f"{_num(arriving / poly.frame.scale)} the first boundary points of its two sides are closer than l "
                "wherever they lie, so no Step 2 separates them (a limit of the paper's method, not a proof that no "
                f"mesh exists; docs/proofs.md, 'Sharp corners'); sides of at least {need} are handled; "
                "use a smaller l, longer sides or a wider corner"
            )
    return None


def _sees_within(grown, ring, i, leaving, arriving):
    """Whether the triangle of corner ``i`` and the points ``leaving`` and ``arriving`` along its sides lies in ``grown``.

    Then every two points of the two sides within those distances see each
    other (the segment joining them lies in the triangle).
    """
    v, n = ring.local[i], len(ring.local)
    lengths = ring.local_edge_lengths
    far = [v + (ring.local[j % n] - v) * r / lengths[k] for j, r, k in ((i + 1, leaving, i), (i - 1, arriving, i - 1))]
    return grown.covers(shapely.Polygon([v, *far]))


#: Bisection steps of :func:`_visible_radii` between the last halving of the sides that is seen and the one
#: before: a bound on the work (the radii are then within ``2^-VISIBLE_BISECTIONS`` of the largest seen at that
#: ratio), not a tolerance.
VISIBLE_BISECTIONS = 20


def _visible_radii(grown, ring, i, sides):
    """``sides`` scaled down until :func:`_sees_within` holds for them, or ``(0, 0)`` (nothing seen).

    Halved first (at most 64 times), then bisected between the first
    halving seen and the one before (:data:`VISIBLE_BISECTIONS` steps): the
    triangles of the corner and ``t sides`` grow with ``t``, so every ``t``
    below one seen is seen too.  Never below the halving alone.
    """
    for k in range(64):
        if _sees_within(grown, ring, i, *(x / 2.0**k for x in sides)):
            break
    else:
        return 0.0, 0.0
    low, high = 0.5**k, 2.0 * 0.5**k
    for _ in range(VISIBLE_BISECTIONS * bool(k)):
        middle = (low + high) / 2.0
        if _sees_within(grown, ring, i, *(x * middle for x in sides)):
            low = middle
        else:
            high = middle
    return tuple(x * low for x in sides)


def _corners_of(poly, boundary, pairs):
    """The corners ``(ring, i)`` at which a pair of ``pairs`` (boundary point indices) lies on the two sides.

    A vertex of P lies on the edge it starts and on the one it ends.
    """
    found = set()
    for i, j in pairs:
        r = int(boundary.ring[i])
        if r != int(boundary.ring[j]):
            continue
        n = len(poly.rings[r].local)
        edges = [{int(boundary.edge[k]), int(boundary.edge[k] - boundary.is_vertex[k]) % n} for k in (i, j)]
        found |= {(r, b) for a in edges[0] for b in edges[1] if (a + 1) % n == b}
        found |= {(r, a) for a in edges[0] for b in edges[1] if (b + 1) % n == a}
    return sorted(found)


def _unplaceable_corner(poly, l, corners):
    """The error for the first of ``corners`` (``(ring, i)``) that no Step 2 can separate (Lemma 3 (1)), or None.

    Only corners sharper than :data:`SHARP_CORNER` are decided
    (:func:`._corner.corner_unplaceable`, then on finer cells
    :func:`._coupled.chain_unplaceable` with no second corner): distances are
    checked within the largest of the sides' lengths halved until the triangle they span with
    the corner lies in P (grown by ``REL_TOL l``), where every two points of
    the two sides see each other (:func:`_sees_within`).  When no split of
    the two sides into parts of ``[l, 2l]`` keeps them ``l`` apart there, no
    boundary resampling meets Lemma 3 (1), which this method and the
    paper's need; it is not a proof that no mesh exists (docs/proofs.md,
    "Sharp corners").
    """
    lp = poly.local_length(l)
    grown = poly.region.buffer(REL_TOL * lp)
    for r, i in corners:
        ring = poly.rings[r]
        angle, lengths = ring.inner_angle(i), ring.local_edge_lengths
        sides = (lengths[i], lengths[i - 1])
        if not angle < SHARP_CORNER:
            continue
        radii = _visible_radii(grown, ring, i, sides)
        theta = math.radians(angle)
        if not _corner.corner_unplaceable(theta, sides, lp, radii) and not _coupled.chain_unplaceable(
            (theta, None), (sides[1], sides[0], 0.0), lp, (radii[1], radii[0], 0.0, 0.0)
        ):
            continue
        need = _num((stagger_reach(angle, lp) + lp) / poly.frame.scale)
        return InvalidPolygonError(
            f"the corner at {ring.vertex_name(i)} ({angle:.6g} degrees) cannot meet Lemma 3 (1) for l = {_num(l)}: "
            f"no split of its sides of {_num(sides[0] / poly.frame.scale)} and {_num(sides[1] / poly.frame.scale)} "
            "into parts of [l, 2l] keeps every two points of different sides l apart (decided on a grid of cells), so "
            "no Step 2 separates them (a limit of the paper's method, not a proof that no mesh exists; docs/proofs.md, "
            f"'Sharp corners'); sides of at least {need} are handled; use a smaller l, longer sides or a wider corner"
        )
    return None


def _unplaceable_chain(poly, l, corners):
    """The error for the first sharp corners in a row, one of ``corners``, that no Step 2 separates together, or None.

    First each two consecutive corners ``i``, ``i + 1`` both sharper than
    :data:`SHARP_CORNER` (either in ``corners``), then each run of three or
    more through one of ``corners`` (:func:`_run`), are decided by
    :func:`._coupled.chain_unplaceable`, distances checked within each
    corner's :func:`_visible_radii` as in :func:`_unplaceable_corner`.  When
    no split of their sides into parts of ``[l, 2l]`` keeps every corner's
    two sides ``l`` apart there, no boundary resampling meets Lemma 3 (1);
    it is not a proof that no mesh exists (docs/proofs.md, "Sharp corners").
    """
    lp = poly.local_length(l)
    grown = poly.region.buffer(REL_TOL * lp)
    pairs = sorted({(r, (j - k) % len(poly.rings[r].local)) for r, j in corners for k in (0, 1)})
    runs = [(r, [i, (i + 1) % len(poly.rings[r].local)]) for r, i in pairs]
    for r, j in corners:
        ring = poly.rings[r]
        angles = [ring.inner_angle(i) for i in range(len(ring.local))]
        if _stagger_count(angles[j]):
            run = _run(ring.local_edge_lengths, angles, lp, j)
            if len(run) > 2 and (r, run) not in runs:
                runs.append((r, run))
    for r, run in runs:
        ring = poly.rings[r]
        n, lengths = len(ring.local), ring.local_edge_lengths
        angles = [ring.inner_angle(c) for c in run]
        if not max(angles) < SHARP_CORNER:
            continue
        edges = [lengths[(run[0] - 1 + k) % n] for k in range(len(run) + 1)]
        radii = sum((_visible_radii(grown, ring, c, (edges[k + 1], edges[k]))[::-1] for k, c in enumerate(run)), ())
        if not _coupled.chain_unplaceable(tuple(math.radians(a) for a in angles), tuple(edges), lp, radii):
            continue
        names = [f"{ring.vertex_name(c)} ({a:.6g} degrees)" for c, a in zip(run, angles)]
        sides = ", ".join(_num(x / poly.frame.scale) for x in edges)
        return InvalidPolygonError(
            f"the corners at {', '.join(names[:-1])} and {names[-1]} cannot meet Lemma 3 (1) together for l = {_num(l)}: "
            f"no split of their sides of {sides} (the middle {'ones' if len(run) > 2 else 'one'} shared) into parts of "
            f"[l, 2l] keeps every two points of different sides l apart at {'both corners' if len(run) == 2 else 'every corner'} "
            "(decided on a grid of cells), so "
            "no Step 2 separates them (a limit of the paper's method, not a proof that no mesh exists; docs/proofs.md, "
            "'Sharp corners'); use a smaller l, longer sides or wider corners"
        )
    return None


def _separation_error(poly, boundary, l, i, j):
    """The error for boundary points ``i`` and ``j`` closer than ``l`` that see each other."""
    p, q = boundary.points[i], boundary.points[j]
    d = _num(np.linalg.norm(q - p) / poly.frame.scale)
    ri, rj = (poly.rings[int(boundary.ring[k])] for k in (i, j))
    ei, ej = int(boundary.edge[i]), int(boundary.edge[j])
    where = f"boundary points on {ri.edge_name(ei)} and {rj.edge_name(ej)} are {d} apart"
    caller = poly.frame.to_caller(np.array([p, q]))
    n = len(ri.local)
    corner = None if ri is not rj else ej if (ei + 1) % n == ej else ei if (ej + 1) % n == ei else None
    if corner is not None:
        angle = ri.inner_angle(corner)
        need = _num((stagger_reach(angle, poly.local_length(l)) / poly.frame.scale) + l)
        message = (
            f"the corner at {ri.vertex_name(corner)} ({angle:.6g} degrees) is not handled for l = {_num(l)}: "
            f"{where}, closer than l (Lemma 3 (1)); the staggered Step 2 is proven at {angle:.6g} degrees for sides "
            f"of at least {need}, longer if the next corner is sharp too; for these the searches found no placement "
            "and none is proven impossible, even for each corner alone (a limit of this method, not a proof that no "
            "mesh exists; docs/proofs.md, 'Sharp corners'); "
            "use a smaller l, longer sides or a wider corner"
        )
    else:
        message = (
            f"polygon is too narrow for l = {_num(l)}: {where} and see each other across the polygon "
            f"(Lemma 3 (1), a limit of this method); use l <= {d} or widen the polygon there"
        )
    return InvalidPolygonError(message, points=caller)


def pinned_vertices(poly):
    """``(local, caller)`` rows of every ring's vertices, so the output keeps the caller's exact coordinates."""
    return tuple(np.vstack([getattr(ring, name) for ring in poly.rings]) for name in ("local", "vertices"))
