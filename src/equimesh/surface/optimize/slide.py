"""Boundary nodes sliding along a closed polyline in (u, v) by one arc parameter (beyond the paper).

The paper keeps the boundary nodes fixed in the final optimisation.  Under the
"bounded" objective (:mod:`equimesh.surface.optimize`) a boundary node of a
triangle-mesh chart (the flattened rim, :mod:`equimesh.surface.mesh_outline`)
may instead slide along its loop: its one variable is its arc position ``s``,
``uv = loop(s)`` piecewise linear, ``d uv / d s`` the unit direction of the
segment ``s`` lies on (from the segment's start: at a loop vertex the segment
that begins there).  It stays between the loop's corners before and after it
(docs/decisions.md, "Boundary nodes slide under bounded").  The openings of a
parametric chart (:mod:`equimesh.surface.charts.openings`) slide the same way along
their (u, v) polygons, every vertex a corner.
"""

from dataclasses import dataclass

import numpy as np

from ..._geometry import Polyline
from ...tolerance import REL_TOL


@dataclass(frozen=True)
class Slide:
    """Nodes that slide along one closed polyline in (u, v).

    Attributes
    ----------
    nodes : (k,) int array
        The sliding nodes (indices into the mesh's nodes).
    loop : Polyline
        The closed polyline in (u, v).
    s, lower, upper : (k,) float arrays
        Each node's start arc position and its bounds, all within
        ``[0, 2 * length)``: a position ``s >= length`` is ``s - length``.
    """

    nodes: np.ndarray
    loop: Polyline
    s: np.ndarray
    lower: np.ndarray
    upper: np.ndarray

    def uv(self, s):
        """(k, 2) points of the loop at arc positions ``s``."""
        return self.loop.at(s)

    def direction(self, s):
        """(k, 2) ``d uv / d s`` at arc positions ``s``."""
        return self.loop.direction(s)


def between_corners(nodes, loop, s, corners):
    """The nodes at arc positions ``s`` on the closed :class:`~equimesh._geometry.Polyline` ``loop``, sliding between
    the corners before and after each.

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
    length = loop.length
    ends = np.append(corners, corners[0] + length)
    k = np.clip(np.searchsorted(ends, s, side="right") - 1, 0, len(ends) - 2)
    lower, upper = ends[k], ends[k + 1]
    near = REL_TOL * length
    fixed = (s - lower <= near) | (upper - s <= near)
    keep = ~fixed
    return Slide(nodes[keep], loop, s[keep], lower[keep], upper[keep]), nodes[fixed]


def along_polygon(nodes, vertices, uv):
    """The nodes at ``uv`` on the closed polygon ``vertices`` (in (u, v)), each sliding along the edge it lies on.

    Every vertex is a corner (:func:`between_corners`): the parameter
    rectangle's sides, an opening's edges.
    """
    loop = Polyline(np.asarray(vertices, dtype=float))
    return between_corners(nodes, loop, loop.project(uv)[2], loop.arc[:-1])
