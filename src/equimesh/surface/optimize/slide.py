"""Boundary nodes sliding along a closed polyline in (u, v) by one arc parameter (beyond the paper).

The paper keeps the boundary nodes fixed in the final optimisation.  Under the
"bounded" objective (:mod:`equimesh.surface.optimize`) a boundary node of a
triangle-mesh chart (the flattened rim, :mod:`equimesh.surface.mesh_outline`)
may instead slide along its loop: its one variable is its arc position ``s``,
``uv = loop(s)`` piecewise linear, ``d uv / d s`` the unit direction of the
segment ``s`` lies on (from the segment's start: at a loop vertex the segment
that begins there).  It stays between the loop's corners before and after it
(docs/decisions.md, "Real surfaces in", item 52).  The openings of a
parametric chart (:mod:`equimesh.surface.charts.openings`) slide the same way along
their (u, v) polygons, every vertex a corner.
"""

from dataclasses import dataclass

import numpy as np

from ...tolerance import REL_TOL


def loop_arc(xy):
    """Arc position of each vertex of the closed polyline ``xy``, and its length last."""
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.roll(xy, -1, axis=0) - xy, axis=1))])


def on_loop(xy, arc, s):
    """Points of the closed loop ``xy`` (vertex arc positions ``arc``, its length last) at arc positions ``s``."""
    k, t = _segment(arc, s)
    a, b = xy[k], np.roll(xy, -1, axis=0)[k]
    return np.where((t == 0.0)[:, None], a, a + t[:, None] * (b - a))


def loop_direction(xy, arc, s):
    """``d loop / d s`` at arc positions ``s``: the unit direction of the segment each lies on."""
    k, _ = _segment(arc, s)
    d = np.roll(xy, -1, axis=0)[k] - xy[k]
    return d / (arc[k + 1] - arc[k])[:, None]


def _segment(arc, s):
    k = np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(arc) - 2)
    return k, (s - arc[k]) / (arc[k + 1] - arc[k])


@dataclass(frozen=True)
class Slide:
    """Nodes that slide along one closed polyline in (u, v).

    Attributes
    ----------
    nodes : (k,) int array
        The sliding nodes (indices into the mesh's nodes).
    loop : (m, 2) float array
        The closed polyline in (u, v) (its closing segment implicit).
    arc : (m + 1,) float array
        Arc position of each loop vertex, and the loop's length last.
    s, lower, upper : (k,) float arrays
        Each node's start arc position and its bounds, all within
        ``[0, 2 * length)``: a position ``s >= length`` is ``s - length``.
    """

    nodes: np.ndarray
    loop: np.ndarray
    arc: np.ndarray
    s: np.ndarray
    lower: np.ndarray
    upper: np.ndarray

    def wrapped(self, s):
        """The arc positions ``s`` taken back into ``[0, length)``."""
        length = self.arc[-1]
        return np.where(s >= length, s - length, s)

    def uv(self, s):
        """(k, 2) points of the loop at arc positions ``s``."""
        return on_loop(self.loop, self.arc, self.wrapped(s))

    def direction(self, s):
        """(k, 2) ``d uv / d s`` at arc positions ``s``."""
        return loop_direction(self.loop, self.arc, self.wrapped(s))


def between_corners(nodes, loop, arc, s, corners):
    """The nodes at arc positions ``s`` on ``loop`` sliding between the corners before and after each.

    ``corners`` are the corners' arc positions, increasing, the first at or
    before every ``s`` and all less than a loop's length after it.  A node
    within ``REL_TOL`` of the loop's length from a corner is at it (the plane's
    node and the corner may differ by rounding) and stays fixed.

    Returns
    -------
    slide : Slide
        The nodes not at a corner.
    fixed : (c,) int array
        The nodes at a corner.
    """
    ends = np.append(corners, corners[0] + arc[-1])
    k = np.clip(np.searchsorted(ends, s, side="right") - 1, 0, len(ends) - 2)
    lower, upper = ends[k], ends[k + 1]
    near = REL_TOL * arc[-1]
    fixed = (s - lower <= near) | (upper - s <= near)
    keep = ~fixed
    return Slide(nodes[keep], loop, arc, s[keep], lower[keep], upper[keep]), nodes[fixed]
