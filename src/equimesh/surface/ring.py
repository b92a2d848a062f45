"""Step 2 of Algorithm INCREMENT on a closed plane polyline with marked corners (Section 4, step 3, beyond the paper).

A curved boundary (the flattened outline of a surface, the image of an
opening, a boundary loop of a triangle mesh) is resampled into a polygon for
Problem 2 (:func:`equimesh.uniform_triangulation`), parameters such as (u, v)
carried along:

* the sides between corners are split into ``k`` parts at equal arc length,
  ``k`` by the rule of Step 2 (:func:`~equimesh.planar.boundary.sides.split_counts`);
  a part's chord is at most its arc, so at most ``2l``; where curvature makes
  a chord shorter than ``l``, the side falls back to ``k - 1, k - 2, ...``
  parts;
* next to a corner sharper than :data:`~equimesh.planar.boundary.sides.SHARP_CORNER`
  each side keeps one straight edge from the corner, on which Problem 2
  staggers its points (:func:`~equimesh.planar.boundary.sides.side_positions`)
  exactly as on a polygon's sides;
* every polygon vertex lies on the polyline, with the segment and fraction
  it sits at, so its parameters are known exactly.
"""

from dataclasses import dataclass

import numpy as np

from .._geometry import Polyline, inner_angle
from ..errors import SurfaceTooSmallError, number
from ..planar.boundary.sides import split_counts, stagger_reach
from ..tolerance import at_least


@dataclass(frozen=True)
class Ring:
    """A closed polyline resampled by :func:`resample_ring`.

    Attributes
    ----------
    points : (m, 2) the polygon's vertices, in the polyline's order, starting at its first corner.
    params : (m, k) the parameters carried by the polyline, interpolated at each vertex.
    side : (m,) the side (``i``: from the polyline's corner ``i`` to corner ``i + 1``)
        each polygon edge (j, j+1) lies on.
    """

    points: np.ndarray
    params: np.ndarray
    side: np.ndarray


def resample_ring(xy, params, corners, l, spacing, too_short=None, angles=None):
    """Step 2 on a closed plane polyline: a polygon on it whose edges are at least ``l`` long.

    Parameters
    ----------
    xy : (n, 2) array
        The polyline's points, the region on its left (counter-clockwise
        for an outer boundary, clockwise for an opening); the first point is
        not repeated at the end.
    params : (n, k) array
        Parameters carried along (e.g. (u, v)), interpolated linearly on each
        segment; a corner's parameters are kept bit for bit.
    corners : sequence of int
        Increasing indices into ``xy``, at least one: the points every
        polygon keeps.  The sides run from each corner to the next (with one
        corner, once around the loop).
    l, spacing : float
        Target length and Step 2 spacing (in units of l).
    too_short : callable, optional
        ``too_short(side, arc, chord)`` returns the exception raised for a
        side that no split leaves with chords of at least ``l``.
    angles : sequence of float, optional
        The inner angle (degrees) of each corner, where the polyline's own
        angle at the vertex is not the corner's (a staircase of mesh edges);
        by default the polyline's.

    A side is split into ``k`` equal parts along its arc, ``k`` by the rule
    of Step 2 (:func:`~equimesh.planar.boundary.sides.split_counts`), the paper's
    Step 2 at arc length; where a chord is shorter than ``l``, ``k - 1,
    k - 2, ...`` parts.  Next to a corner sharper than ``SHARP_CORNER`` the
    side keeps one straight edge from the corner, ``stagger_reach + l`` long
    (:func:`_corner_edges`): Problem 2 staggers its points there
    (:func:`~equimesh.planar.boundary.sides.side_positions`) on a straight edge, where
    the proof of their separation holds as it stands (docs/proofs.md, "Sharp
    corners"); staggered points placed on the curve itself would be ``l``
    apart along the arc, closer than ``l`` as chords.
    """
    xy, params = np.asarray(xy, dtype=float), np.asarray(params, dtype=float)
    corners = np.asarray(corners, dtype=np.int64)
    n = len(xy)
    chains = [np.r_[c0 : c1 + 1] if c1 > c0 else np.r_[c0:n, : c1 + 1] for c0, c1 in zip(corners, np.roll(corners, -1))]
    sides = [Polyline(xy[c], closed=False, values=params[c]) for c in chains]
    if angles is None:
        angles = [inner_angle(xy, c) for c in corners]
    stretches = _corner_edges(xy, sides, corners, angles, l)
    points, carried, side = [], [], []
    for i, (polyline, stretch) in enumerate(zip(sides, stretches)):
        pts, prm = split_side(polyline, stretch, l, spacing)
        if pts is None:
            chord = float(np.linalg.norm(polyline.points[-1] - polyline.points[0]))
            raise (too_short or _too_short)(i, polyline.length, chord)
        points.append(pts[:-1])
        carried.append(prm[:-1])
        side.append(np.full(len(pts) - 1, i))
    return Ring(np.vstack(points), np.vstack(carried), np.concatenate(side))


#: Passes of :func:`_corner_edges` at one corner: the angle between the
#: straight edges may be sharper than the polyline's, needing longer edges;
#: ``stagger_reach`` is a whole multiple of l, so it settles within a pass or two.
CORNER_PASSES = 4


def _corner_edges(xy, sides, corners, angles, l):
    """Per side, the stretch ``(a, b)`` of its arc split into equal parts, or None for one straight edge.

    At a corner sharper than ``SHARP_CORNER`` (its inner angle ``angles``
    first) the sides keep straight edges from the corner to the points at
    distance ``stagger_reach(angle) + l`` from it (first reached along each
    side), ``angle`` being then the angle
    between those two edges (recomputed until the reach no longer grows,
    at most :data:`CORNER_PASSES` passes).  A side whose stretch between such
    points is shorter than ``l``, or that never gets that far from the
    corner, is one straight edge; Problem 2 then drops the staggered points
    it has no room for, or refuses the corner.  A side with no sharp corner
    is split whole: ``(0, length)``.
    """
    n = len(sides)
    start, end = [0.0] * n, [side.length for side in sides]
    single = [False] * n
    for i, (c, angle) in enumerate(zip(corners, angles)):
        leaving, arriving = i, (i - 1) % n
        ahead, into = sides[leaving], sides[arriving]
        back = Polyline(into.points[::-1], closed=False, arc=into.length - into.arc[::-1])  # from the corner
        reach = 0.0
        for _ in range(CORNER_PASSES):
            need = stagger_reach(angle, l)
            if need <= reach:
                break
            reach = need
            s, t = arc_at_distance(ahead, reach + l), arc_at_distance(back, reach + l)
            if s is None or t is None:
                single[leaving] = single[arriving] = True
                break
            start[leaving], end[arriving] = s, into.length - t
            p, q = (polyline.at(np.array([x]))[0] for polyline, x in ((ahead, s), (back, t)))
            angle = inner_angle(np.array([q, xy[c], p]), 1)
    return [None if one or not at_least(b - a, l) else (a, b) for one, a, b in zip(single, start, end)]


def arc_at_distance(polyline, distance):
    """Arc length along the open ``polyline`` at which it first reaches ``distance`` from its start, or None."""
    arc = float(reach(polyline, distance, np.array([0]))[0])
    return None if np.isnan(arc) else arc


def reach(polyline, distance, starts):
    """Arc positions at which ``polyline``, followed forward from its vertices ``starts``, first reaches ``distance``.

    For each start vertex ``i`` the first point at a straight-line distance
    ``distance`` from vertex ``i``, found on the first segment whose end is
    that far (:func:`at_distance`); ``nan`` where there is none: past the end
    of an open polyline, or within one turn of a closed one, whose arc
    positions run on past its length.
    """
    pts, arc = polyline.points, polyline.arc
    n, length = len(pts), polyline.length
    starts = np.asarray(starts, dtype=np.int64)
    found = np.full(len(starts), np.nan)
    todo = np.arange(len(starts))
    for k in range(1, n + 1 if polyline.closed else n):
        if not polyline.closed:
            todo = todo[starts[todo] + k < n]
        if not todo.size:
            break
        j = starts[todo] + k
        origin, a, b = pts[starts[todo]], pts[(j - 1) % n], pts[j % n]
        far = np.linalg.norm(b - origin, axis=1) >= distance
        hit, j = todo[far], j[far]
        t = at_distance(origin[far], a[far], b[far], distance)
        before, after = (arc[m % n] + (m // n) * length for m in (j - 1, j))
        found[hit] = before + t * (after - before)
        todo = todo[~far]
    return found


def at_distance(origin, a, b, distance):
    """The fraction ``t`` of each segment ``ab`` at which ``a + t (b - a)`` is ``distance`` from ``origin`` (the
    larger root; ``a`` within it, ``b`` beyond it)."""
    p, e = a - origin, b - a
    qa, qb, qc = np.sum(e * e, axis=-1), 2.0 * np.sum(p * e, axis=-1), np.sum(p * p, axis=-1) - distance * distance
    return (-qb + np.sqrt(qb * qb - 4.0 * qa * qc)) / (2.0 * qa)


def split_side(polyline, stretch, l, spacing):
    """Points of one side with chords of at least ``l``, or None: its start, the stretch split evenly, its end.

    The stretch ``(a, b)`` is split into ``k`` equal parts (Step 2's count),
    else ``k - 1, k - 2, ...``; straight edges join ``a`` and ``b`` to the
    side's ends when they are not the ends themselves.  ``stretch`` None: one
    straight edge, the side's chord.
    """
    length = polyline.length
    if stretch is None:
        candidates = [np.array([0.0, length])]
    else:
        a, b = stretch
        k = int(split_counts([b - a], l, spacing)[0])  # 0: the side is shorter than l
        head, tail = [0.0] if a > 0 else [], [b] if b < length else []
        candidates = [np.concatenate([head, a + (b - a) * np.arange(j) / j, tail, [length]]) for j in range(k, 0, -1)]
    for s in candidates:
        pts, prm = polyline.at(s), polyline.values_at(s)
        if np.all(at_least(np.linalg.norm(np.diff(pts, axis=0), axis=1), l)):
            return pts, prm
    return None, None


def _too_short(side, arc, chord):
    """The default refusal of :func:`resample_ring`: a side the resampling cannot split into chords of at least l."""
    return SurfaceTooSmallError(
        f"side {side} of the boundary polyline is {number(arc)} long (its ends {number(chord)} apart), "
        "too short to split into parts of at least l"
    )
