"""Input polygons: validation against the assumptions of Problems 1 and 2.

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
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
import shapely

from .._checks import real_array
from .._geometry import Frame, cross, inner_angle, orient_sign, power_of_two_scale, segments_intersect, signed_area
from ..errors import InvalidPolygonError, number
from ..tolerance import MAX_EXTENT, MIN_TRIANGLE_AREA, REL_TOL, at_least


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
        return f"vertex {j}{self._of} at ({number(x, 10)}, {number(y, 10)})"

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
            f"polygon spans {number(extent, None)} = {number(extent / l, None)} l, more than the {MAX_EXTENT:.0f} l "
            "within which "
            f"edge lengths are exact to REL_TOL; use l >= {number(extent / MAX_EXTENT, None)}"
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
    from its boundary and from each other); with ``l``, no corner of any ring
    is too sharp for a non-degenerate triangle (:func:`check_corners_resolvable`).
    """
    v = _ring_vertices(_parse_vertices(vertices), "")
    outer = _ring(v, _local_frame(v, l), "")
    if l is not None:
        check_corners_resolvable(outer)
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
            raise InvalidPolygonError(
                f"{label} is not inside the polygon: its vertex {out[0]} at ({number(x, 10)}, {number(y, 10)}) lies "
                "outside"
            )
        rings.append(_ring(_ring_vertices(v, label), outer.frame, label))
        if l is not None:
            check_corners_resolvable(rings[-1])
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
        d = number(gap[k] / outer.frame.scale, None)
        raise InvalidPolygonError(
            f"{rings[k].label} is {d} from the boundary of the polygon, closer than l = {number(l, None)} "
            f"(Lemma 3 (1)); move it or use l <= {d}"
        )
    i, j = tree.query(shapes, predicate="dwithin", distance=lp)
    keep = i < j
    i, j = i[keep], j[keep]
    gap = shapely.distance(np.array(shapes)[i], np.array(shapes)[j])
    close = np.flatnonzero(~at_least(gap, lp))
    if close.size:
        k = close[np.lexsort((j[close], i[close]))[0]]
        d = number(gap[k] / outer.frame.scale, None)
        raise InvalidPolygonError(
            f"hole {i[k]} and hole {j[k]} are {d} apart, closer than l = {number(l, None)} (Lemma 3 (1)); "
            f"move them apart or use l <= {d}"
        )


#: The sharpest corner Problem 2 meshes, in degrees: ``sin`` of it is
#: ``2 MIN_TRIANGLE_AREA`` (docs/decisions.md, "A triangle-quality floor").
MIN_CORNER_ANGLE = math.degrees(math.asin(2.0 * MIN_TRIANGLE_AREA))


def check_corners_resolvable(ring):
    """Refuse a corner of ``ring`` sharper than :data:`MIN_CORNER_ANGLE`, as computed in the local frame.

    At a corner of inner angle ``a`` this sharp the corner's two neighbours in
    any mesh with edges in [l, 2l] are its neighbours along the two sides
    (the corner is far narrower than l within 2l of it, and nodes are l
    apart), so one triangle holds it, with sides of l to 2l at the angle
    ``a``: its area is between ``l^2 sin(a) / 2`` and ``2 l^2 sin(a)``, and
    below :data:`MIN_CORNER_ANGLE` it can be (below ``asin(MIN_TRIANGLE_AREA /
    2)`` it must be) below the floor ``MIN_TRIANGLE_AREA l^2`` of a
    non-degenerate triangle.  This includes a corner that rounds to 0 degrees
    (a vertex within rounding of the line of its neighbours).
    """
    v = ring.local
    u, w = np.roll(v, 1, axis=0) - v, np.roll(v, -1, axis=0) - v
    angle = np.degrees(np.arctan2(cross(w, u), np.sum(w * u, axis=1))) % 360.0
    sharp = np.flatnonzero(angle < MIN_CORNER_ANGLE)
    if sharp.size:
        i = int(sharp[0])
        raise InvalidPolygonError(
            f"the corner at {ring.vertex_name(i)} is {number(float(angle[i]))} degrees, sharper than the "
            f"{number(MIN_CORNER_ANGLE)} degrees Problem 2 meshes: the one triangle at it, with sides of l to 2l, has "
            f"an area down to l^2 sin(angle) / 2, below the {number(MIN_TRIANGLE_AREA)} l^2 of a non-degenerate "
            "triangle; widen the corner"
        )


def _check_no_repeated_vertex(v, of=""):
    order = np.lexsort((v[:, 1], v[:, 0]))
    same = np.all(v[order[1:]] == v[order[:-1]], axis=1)
    if np.any(same):
        k = np.flatnonzero(same)[0]
        i, j = sorted((int(order[k]), int(order[k + 1])))
        raise InvalidPolygonError(
            f"vertices {i} and {j}{of} coincide at ({number(v[i, 0], 10)}, {number(v[i, 1], 10)})"
        )


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
                f"is no longer than the side): {ring.edge_name(i)} has length {number(ring.edge_lengths[i], None)}, "
                f"shorter than l = {number(l, None)}"
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
            f"inner angle {number(poly.inner_angle(i), 10)} degrees at {poly.vertex_name(i)} is below 90 degrees"
        )


def pinned_vertices(poly):
    """``(local, caller)`` rows of every ring's vertices, so the output keeps the caller's exact coordinates."""
    return tuple(np.vstack([getattr(ring, name) for ring in poly.rings]) for name in ("local", "vertices"))
