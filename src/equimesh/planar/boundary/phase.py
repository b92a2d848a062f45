"""Step 2 in phase with the lattice (beyond the paper): boundary points that make the strip periodic.

The paper splits every edge into equal parts, whatever the lattice.  Along a
straight side parallel to a lattice direction, equal parts of a length other
than l meet the lattice's first row out of step, and every strip member has a
length of its own.  :func:`in_phase` places the points of such a side at the
lattice's own period instead, half a period from the row's points, so the
triangles between the side and the row repeat (and their members repeat):

* a side parallel to a lattice direction: period l, each part a lattice
  edge's length, its two ends joined to one point of the first row;
* a side perpendicular to one: the rows end on it every ``sqrt(3) l / 2``,
  alternately nearer and farther; the points lie at the farther rows' height,
  period ``sqrt(3) l`` (parts of at most ``sqrt(3) l`` keep Problem 2's angle
  bound of 30 degrees, docs/decisions.md, "Angles of Problems 1 and 2").

The two end parts of a side take what the period leaves, each in
``[SHORTEST_END l, sqrt(3) l]`` (a longer remainder is split in equal parts).  A side qualifies
when it is straight (its polygon vertices within :data:`STRAIGHT` l of its
chord) between corners of at least :data:`~.sides.SHARP_CORNER` degrees
(sharper corners are staggered), along or across a lattice direction within
:data:`PHASE_ANGLE` degrees, with the lattice near it; every other side keeps
the paper's points.  Lemma 3 (1) is checked on the result, and a boundary that
fails it gives way to the paper's (docs/decisions.md, "Boundary points in
phase with the lattice").
"""

import math

import numpy as np

from ...errors import InvalidPolygonError
from ...tolerance import REL_TOL
from ..lattice import lattice_basis
from .resample import Boundary
from .separation import check_boundary_separation
from .sides import SHARP_CORNER

#: A side is straight when each of its polygon vertices lies within this many l of its chord: a straight side resampled,
#: straight to rounding (as the flattened outline of a developable surface, ruled or a cylinder, is).
STRAIGHT = REL_TOL
#: Degrees within which a side runs along or across a lattice direction (the merge angle of the placements tried).
PHASE_ANGLE = 1.0
#: The longest end part, in units of l (Problem 2's angle bound of 30 degrees holds up to it).
LONGEST_PART = math.sqrt(3.0)
#: The shortest end part, in units of l: the inner parts of a side along the lattice are exactly l, so its two end
#: parts keep the room an optimisation needs to lengthen its members (the bounded objective's target, ``1 + 1e-3``
#: l, takes ``1e-3 l`` a part: 100 parts).
SHORTEST_END = 1.05


def in_phase(poly, boundary, lattice, angle, l):
    """The Step 2 ``boundary`` of ``poly`` with its straight sides' points in phase with ``lattice``.

    Parameters
    ----------
    poly : Polygon (validated, :func:`~equimesh.planar.polygon.as_polygon`).
    boundary : Boundary, the paper's Step 2 points (:func:`~.resample.resample_boundary`).
    lattice : LatticePart, the kept lattice K (:func:`~equimesh.planar.lattice.lattice_part`).
    angle : float, the lattice's angle (degrees; the local frame is not turned).
    l : float

    Returns
    -------
    Boundary
        ``boundary`` with the points of every qualifying side replaced (the
        side's inner polygon vertices among them: they lie on its chord), or
        ``boundary`` itself when no side qualifies or the result fails
        Lemma 3 (1) (:func:`~.separation.check_boundary_separation`).
    """
    if not len(lattice.triangles):
        return boundary
    lp = poly.local_length(l)
    e1, e2 = lattice_basis(1.0, angle)
    directions = np.array([e1, e2, e2 - e1])  # the three lattice directions, unit vectors
    rows = lattice.points[lattice.boundary_vertices]
    parts, changed = [], False
    for r, ring in enumerate(poly.rings):
        on_ring = boundary.ring == r
        for first, last in _sides(ring, lp):
            placed = _side_points(ring, first, last, directions, rows, lp)
            if placed is None:
                keep = on_ring & (boundary.edge >= first) & (boundary.edge < last)
                parts.append((boundary.points[keep], boundary.is_vertex[keep], boundary.edge[keep]))
            else:
                parts.append(placed)
                changed = True
            parts[-1] = (*parts[-1], np.full(len(parts[-1][0]), r))
    if not changed:
        return boundary
    phased = Boundary(*(np.concatenate([part[k] for part in parts]) for k in range(4)))
    try:
        check_boundary_separation(poly, phased, l)
    except InvalidPolygonError:
        return boundary
    return phased


def _sides(ring, lp):
    """``(first, last)`` vertex indices of the ring's sides: maximal runs of vertices on one line, vertex 0 ending one.

    A vertex is inside a side when it lies within ``STRAIGHT lp`` of the
    line through its neighbours (between them: the polygon is simple); every
    other vertex (and vertex 0) ends a side.  ``last`` may be ``len(ring)``: vertex 0 again.
    """
    v = ring.local
    n = len(v)
    before, after = np.roll(v, 1, axis=0), np.roll(v, -1, axis=0)
    chord = after - before
    off = np.abs(chord[:, 0] * (v - before)[:, 1] - chord[:, 1] * (v - before)[:, 0]) / np.linalg.norm(chord, axis=1)
    ends = np.flatnonzero(off > STRAIGHT * lp)  # a simple polygon does not turn back on itself at a vertex
    ends = np.union1d(ends, [0])
    return list(zip(ends, np.append(ends[1:], n)))


def _side_points(ring, first, last, directions, rows, lp):
    """``(points, is_vertex, edge)`` of the side from vertex ``first`` to ``last`` in phase with the lattice, or None.

    None when the side does not qualify (see the module).  Its inner parts are the period, its end parts in
    ``[SHORTEST_END l, sqrt(3) l]`` (:func:`_end`).
    """
    v = ring.local
    n = len(v)
    a, b = v[first], v[last % n]
    length = float(np.linalg.norm(b - a))
    d = (b - a) / length
    normal = np.array([-d[1], d[0]])  # the region lies on the left of every ring
    inner = v[first + 1 : last]
    if len(inner) and np.max(np.abs((inner - a) @ normal)) > STRAIGHT * lp:
        return None
    if min(ring.inner_angle(first), ring.inner_angle(last % n)) < SHARP_CORNER:
        return None
    sin_tol = math.sin(math.radians(PHASE_ANGLE))
    cross, dot = np.abs(directions @ normal), np.abs(directions @ d)
    if np.any(cross <= sin_tol):
        period = lp
    elif np.any(dot <= sin_tol):
        period = LONGEST_PART * lp
    else:
        return None
    s, h = (rows - a) @ d, (rows - a) @ normal
    near = (s > 0) & (s < length) & (h > 0)
    if not np.any(near):
        return None
    s, h = s[near], h[near]
    first_row = h <= h.min() + lp / 4  # the row (or, across the rows, the nearer row ends) next to the side
    s = s[first_row]
    middle = s[np.argmin(np.abs(s - length / 2))] + period / 2
    targets, head = _end(list(np.arange(middle % period, length, period)), lp)
    mirrored, tail = _end([length - t for t in reversed(targets)], lp)
    if not mirrored:
        return None
    targets = [length - t for t in reversed(mirrored)]
    positions = np.array([0.0, *head, *targets, *(length - t for t in reversed(tail))])  # parts in [l, 2l] (_end)
    edge = first + np.searchsorted((v[first:last] - a) @ d, positions, side="right") - 1
    points = a + positions[:, None] * d
    return points, np.all(points == v[edge], axis=1), edge  # a point may fall on an inner vertex of the side


def _end(targets, lp):
    """``(targets, points)`` at the end at 0 (``targets`` increasing): the targets less those closer to it than
    ``SHORTEST_END l``, or leaving a part between ``sqrt(3) l`` and ``2 SHORTEST_END l`` (too long for the angle
    bound, too short for two parts), and the points splitting what is then left before the first target into equal
    parts in ``[SHORTEST_END l, sqrt(3) l]``."""
    while targets and (targets[0] < SHORTEST_END * lp or LONGEST_PART * lp < targets[0] < 2.0 * SHORTEST_END * lp):
        targets = targets[1:]
    if not targets:
        return targets, []
    parts = math.ceil(targets[0] / (LONGEST_PART * lp))
    return targets, [targets[0] * j / parts for j in range(1, parts)]
