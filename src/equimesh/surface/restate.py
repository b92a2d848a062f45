"""Refusals of Problem 2 restated in terms of the surface (Section 4, step 3).

Problem 2 triangulates the resampled flattened boundary (the outline), a
polygon the user never gave.  When it refuses that polygon because two
mutually visible boundary points are closer than l (Lemma 3 (1)), the points
it names are mapped back through the outline to (u, v), to the side or corner
of the parameter rectangle they lie on and to space, and the refusal says what
to change.

Corners below ``SHARP_CORNER`` degrees get staggered boundary points
(:func:`~equimesh.surface.outline.resample_ring`, as Step 2 of Problem 2), which
needs both sides of the corner ``stagger_reach + l`` long
(docs/proofs.md, "Sharp corners"): the refusal there names the corner, its
angle and the largest l for which its sides are long enough.
"""

import numpy as np
import shapely

from ..errors import InvalidSurfaceError
from ..planar.polygon import SHARP_CORNER, stagger_reach
from ._places import at, corner_name, number, side_name
from .outline import round_down
from .regularity import evaluate
from .remap import Loop

def restate_polygon_error(exc, surface, flat_points, grid, outline, l):
    """An :class:`~equimesh.errors.InvalidSurfaceError` saying in surface terms why Problem 2 refused ``outline``.

    Parameters
    ----------
    exc : InvalidPolygonError
        From :func:`equimesh.uniform_triangulation`; ``exc.points`` (if set)
        are points of the outline's plane.
    surface, flat_points, grid, outline, l
        The pipeline's surface, flattened auxiliary nodes (step 2), auxiliary
        grid (step 1), outline (step 3) and target length.
    """
    if not exc.points or len(exc.points) != 2:
        return InvalidSurfaceError(
            f"the surface cannot be meshed with l = {number(l)}: somewhere it is narrower than l or has a corner "
            f"sharper than about {SHARP_CORNER:.0f} degrees on the flattened surface; try a smaller l"
        )
    xy = np.asarray(exc.points, dtype=float)
    domain = outline.domain
    seg, _, uv = Loop(outline.vertices, outline.uv, outline.side, domain).project(xy)
    sides = outline.side[seg]
    space = evaluate(surface, uv)
    gap = float(np.linalg.norm(xy[1] - xy[0]))
    one, two = (f"{side_name(s, domain)} at {at(p, x)}" for s, p, x in zip(sides, uv, space))
    close = f"boundary points on {one} and on {two} are {number(gap)} apart on the flattened surface, closer than l = {number(l)}"
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
                f"{number(need)} l long (docs/proofs.md, 'Sharp corners'), it is {number(length)} on the flattened "
                f"surface; use l <= {number(round_down(length / need))}"
            )
        return InvalidSurfaceError(f"near the {name} ({angle:.1f} degrees on the flattened surface) {close}; try l < {number(round_down(gap))}")
    width = _side_distance(flat_points, grid, sides) if sides[0] != sides[1] else gap
    return InvalidSurfaceError(
        f"the surface is only {number(width)} wide on the flattened surface there: {close}; use l <= {number(round_down(width))}"
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
    keeps every staggered point (:func:`~equimesh.planar.polygon.side_positions`).
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
