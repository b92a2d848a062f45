"""Refusals of Problem 2 restated in terms of the surface (Section 4, step 3).

Problem 2 triangulates the resampled flattened boundary (the outline), a
polygon the user never gave.  When it refuses that polygon because two
mutually visible boundary points are closer than l (Lemma 3 (1)), the points
it names are mapped back through the outline to (u, v), to the side or corner
of the parameter rectangle they lie on and to space, and the refusal says what
to change.

Next to a corner below ``SHARP_CORNER`` degrees the outline keeps straight
edges (:func:`~equimesh.surface.ring.resample_ring`) on which Problem 2
staggers its points, which needs both sides of the corner ``stagger_reach + l`` long
(docs/proofs.md, "Sharp corners"): the refusal there names the corner, its
angle and the largest l for which its sides are long enough.
"""

import re

import numpy as np
import shapely

from ..errors import InvalidSurfaceError, at, number
from ..planar.boundary.sides import SHARP_CORNER, stagger_reach
from .charts.chart import corner_name, side_name
from .charts.openings import holes_of
from .outline import hole_image
from .plane_length import PlaneLength, round_down
from .regularity import evaluate


def restate_polygon_error(exc, surface, flat_points, grid, outline, l):
    """An :class:`~equimesh.errors.InvalidSurfaceError` saying in surface terms why Problem 2 refused ``outline``.

    Parameters
    ----------
    exc : InvalidPolygonError
        From :func:`equimesh.uniform_triangulation`; ``exc.points`` (if set)
        are points of the outline's plane.
    surface, flat_points, grid, outline, l
        The pipeline's surface, flattened auxiliary nodes (step 2), auxiliary
        grid (step 1), outline (step 3) and target length (a float, or the
        :class:`~equimesh.surface.plane_length.PlaneLength` Problem 2 meshed at).
    """
    l = PlaneLength.of(l)
    named = re.match(r"hole (\d+)(?: and hole (\d+))?", str(exc))  # Problem 2's refusals of the holes themselves
    if named and outline.holes:
        return _hole_too_close([int(k) for k in named.groups() if k], surface, flat_points, grid, outline, l)
    if not exc.points or len(exc.points) != 2:
        return InvalidSurfaceError(
            f"the surface cannot be meshed with {l}: somewhere it is narrower than {l.symbol} or has a corner "
            f"sharper than about {SHARP_CORNER:.0f} degrees on the flattened surface; try a smaller l"
        )
    xy = np.asarray(exc.points, dtype=float)
    domain = outline.domain
    seg, _, uv = outline.loop().project(xy)
    rings = [outline.ring_of(k) for k in seg]
    space = evaluate(surface, uv)
    gap = float(np.linalg.norm(xy[1] - xy[0]))
    places = [_place(outline, k, r) for k, r in zip(seg, rings)]
    one, two = (f"{name} at {at(p, x)}" for name, p, x in zip(places, uv, space))
    close = f"boundary points on {one} and on {two} are {number(gap)} apart on the flattened surface, closer than {l}"
    if any(rings):
        return InvalidSurfaceError(
            f"{close}: a hole is too narrow there or has a corner too sharp for its edges' length on the flattened "
            f"surface; try l < {number(l.suggest(round_down(gap)))}"
        )
    sides = outline.side[seg]
    if sides[0] // 2 != sides[1] // 2:  # adjacent sides: the corner between them
        corner = np.zeros(2)
        for s in sides:
            corner[s // 2] = domain.side_values[s]
        angle = _corner_angle(flat_points, grid, corner)
        name = f"{corner_name(corner)} at point ({', '.join(number(c) for c in evaluate(surface, corner)[0])})"
        if angle < SHARP_CORNER:
            side, length, need = min(_stagger_needs(flat_points, grid, sides), key=lambda x: x[1] / x[2])
            return InvalidSurfaceError(
                f"the {name} is {angle:.1f} degrees on the flattened surface: {close}; next to corners sharper than "
                f"{SHARP_CORNER:.0f} degrees the staggered boundary points need {side_name(side, domain)} at least "
                f"{number(need * l.factor)} l long (docs/proofs.md, 'Sharp corners'), it is {number(length)} on the "
                f"flattened surface; use l <= {number(l.suggest(round_down(length / need)))}"
            )
        return InvalidSurfaceError(
            f"near the {name} ({angle:.1f} degrees on the flattened surface) {close}; try l < "
            f"{number(l.suggest(round_down(gap)))}"
        )
    width = _side_distance(flat_points, grid, sides) if sides[0] != sides[1] else gap
    return InvalidSurfaceError(
        f"the surface is only {number(width)} wide on the flattened surface there: {close}; use l <= "
        f"{number(l.suggest(round_down(width)))}"
    )


def _place(outline, segment, ring):
    """``side v = 0`` or ``hole 1`` for a segment of :meth:`Outline.loop` on ring ``ring``."""
    return f"hole {ring - 1}" if ring else side_name(outline.side[segment], outline.domain)


def _hole_too_close(named, surface, flat_points, grid, outline, l):
    """Lemma 3 (1) across boundaries, in (u, v): the named hole closer than l to the boundary or to another hole.

    The gap is the smaller of the one between the exact images of the rings
    on the flattened surface (:func:`~equimesh.surface.outline.hole_image`)
    and the one between the resampled rings Problem 2 refused (their chords
    cut corners), with the (u, v) where it is smallest; a smaller l resamples
    the rings anew, so the bound it suggests is a hint, not a promise.
    """
    k = named[0]
    other = named[1] if len(named) > 1 else None
    rings = outline.rings
    exact = [shapely.LinearRing(hole_image(uv, flat_points, grid)) for uv, _ in holes_of(surface)]
    against = (
        (shapely.LinearRing(flat_points[grid.boundary]), shapely.LinearRing(rings[0]))
        if other is None
        else (exact[other], shapely.LinearRing(rings[other + 1]))
    )
    pairs = [(exact[k], against[0]), (shapely.LinearRing(rings[k + 1]), against[1])]
    gaps = [float(shapely.distance(a, b)) for a, b in pairs]
    near = shapely.shortest_line(*pairs[int(np.argmin(gaps))])
    _, _, uv = outline.loop().project(np.asarray(near.coords))
    what = "the boundary of the surface" if other is None else f"hole {other}"
    gap = min(gaps)
    return InvalidSurfaceError(
        f"hole {k} comes within {number(gap)} of {what} on the flattened surface, at {at(uv[0])} on hole {k} and "
        f"{at(uv[1])}, closer than {l} (Lemma 3 (1)); move it or try l < {number(l.suggest(round_down(gap)))}"
    )


def _corner_angle(flat_points, grid, corner):
    """Inner angle (degrees) of the flattened boundary at the corner ``corner`` of the parameter rectangle."""
    loop = grid.boundary
    k = int(np.flatnonzero(np.all(grid.uv[loop] == corner, axis=1))[0])
    c = flat_points[loop[k]]
    a, b = flat_points[loop[(k + 1) % len(loop)]] - c, flat_points[loop[k - 1]] - c
    return float(np.degrees(np.arctan2(a[0] * b[1] - a[1] * b[0], a @ b)) % 360.0)


def _stagger_needs(flat_points, grid, sides):
    """``(side, length, need)`` for each side: its length on the plane and the staggering's need in units of l.

    A side at least ``stagger_reach`` of both its corners plus ``l`` long
    keeps every staggered point (:func:`~equimesh.planar.boundary.sides.side_positions`).
    """
    a, b = flat_points[grid.boundary], flat_points[np.roll(grid.boundary, -1)]
    domain = grid.domain
    for side in sides:
        length = float(np.sum(np.linalg.norm((b - a)[grid.boundary_segment_side == side], axis=1)))
        axis, other = side // 2, 1 - side // 2
        need = 1.0
        for bound in (domain.lower[other], domain.upper[other]):
            corner = np.empty(2)
            corner[axis], corner[other] = domain.side_values[side], bound
            need += stagger_reach(_corner_angle(flat_points, grid, corner), 1.0)
        yield int(side), length, need


def _side_distance(flat_points, grid, sides):
    """Distance on the plane between two opposite sides of the flattened boundary."""
    loop, side = grid.boundary, grid.boundary_segment_side
    lines = []
    for s in sides:
        seg = np.flatnonzero(side == s)
        nodes = np.r_[loop[seg], np.roll(loop, -1)[seg[-1]]]
        lines.append(shapely.LineString(flat_points[nodes]))
    return float(lines[0].distance(lines[1]))
