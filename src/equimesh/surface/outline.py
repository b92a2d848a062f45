"""Section 4, step 3: the boundary of the flattened auxiliary triangulation as a polygon.

The boundary of the flattened auxiliary triangulation is a closed polyline
through the images of the boundary nodes of the parameter rectangle,
generally not convex (paper, Fig. 2).  Its sides (between the images of the
corners of the auxiliary grid's domain) are resampled into polygon edges between l and 2l, the
input of Problem 2 (:func:`equimesh.uniform_triangulation`):

* a side of arc length ``L`` gets ``k`` parts by the rule of Step 2
  (:func:`equimesh.planar.polygon.split_counts`), placed at equal arc length; a part's
  chord is at most its arc, so at most ``2l``; where curvature makes a chord
  shorter than ``l``, ``k`` is lowered for that side;
* every polygon vertex lies on the flattened polyline, with the boundary
  segment and fraction it sits at, so its (u, v) is known exactly and lies on
  the boundary of the parameter rectangle (paper, eq. (3) on a boundary edge).
"""

from dataclasses import dataclass

import numpy as np

from ..errors import SurfaceTooSmallError
from ..planar.polygon import split_counts
from ..tolerance import at_least
from ._places import corner_name, number, side_name
from .chart import Domain


@dataclass(frozen=True)
class Outline:
    """The resampled boundary polygon and where its vertices sit in (u, v).

    Attributes
    ----------
    vertices : (n, 2) plane coordinates, counter-clockwise.
    uv : (n, 2) parameter coordinates, on the boundary of the domain.
    side : (n,) the side of the domain each polygon edge (i, i+1) runs along
        (index into :data:`~equimesh.surface.chart.SIDES`).
    domain : Domain, the parameter rectangle.
    """

    vertices: np.ndarray
    uv: np.ndarray
    side: np.ndarray
    domain: Domain


def resample_outline(plane, grid, l, spacing):
    """Resample the flattened boundary ``plane[grid.boundary]`` side by side into a polygon.

    ``plane`` holds the flattened nodes of the auxiliary grid ``grid`` (step
    2); the sides run between the corners of the grid's domain, in the
    counter-clockwise order of ``grid.boundary``.

    Raises
    ------
    SurfaceTooSmallError
        A side whose corners are closer than ``l`` on the plane, named by its
        side and corners of the parameter rectangle.
    """
    loop, uv, domain = grid.boundary, grid.uv, grid.domain
    corners = np.flatnonzero(grid.boundary_corner)
    vertices, params, sides = [], [], []
    for c0, c1 in zip(corners, np.roll(corners, -1)):
        chain = loop[c0 : c1 + 1] if c1 > c0 else np.r_[loop[c0:], loop[: c1 + 1]]
        pts, prm = _resample_side(plane[chain], uv[chain], l, spacing, domain)
        vertices.append(pts[:-1])
        params.append(prm[:-1])
        sides.append(np.full(len(pts) - 1, side_index(prm[0], prm[-1], domain)))
    return Outline(np.vstack(vertices), np.vstack(params), np.concatenate(sides), domain)


def side_index(uv_a, uv_b, domain):
    """Index into :data:`~equimesh.surface.chart.SIDES` of the side of ``domain`` through two of its points."""
    axis = 0 if uv_a[0] == uv_b[0] else 1
    return 2 * axis + int(uv_a[axis] == domain.upper[axis])


def _resample_side(xy, uv, l, spacing, domain):
    seg = np.linalg.norm(np.diff(xy, axis=0), axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)])
    k = int(split_counts([arc[-1]], l, spacing)[0])
    while k >= 1:
        s = arc[-1] * np.arange(k + 1) / k
        s[-1] = arc[-1]
        pts, prm = _at_arc(xy, uv, arc, s)
        if np.all(at_least(np.linalg.norm(np.diff(pts, axis=0), axis=1), l)):
            return pts, prm
        k -= 1
    chord = float(np.linalg.norm(xy[-1] - xy[0]))
    raise SurfaceTooSmallError(
        f"{side_name(side_index(uv[0], uv[-1], domain), domain)} of the surface, from {corner_name(uv[0])} to {corner_name(uv[-1])}, "
        f"is {number(arc[-1])} long on the flattened surface (its corners {number(chord)} apart), "
        f"shorter than l = {number(l)}; use l <= {number(round_down(chord))}"
    )


def round_down(x, digits=4):
    """``x`` rounded down to ``digits`` significant digits, so that a suggested bound ``l <= x`` is safe."""
    if x <= 0:
        return 0.0
    scale = 10.0 ** (np.floor(np.log10(x)) - digits + 1)
    return float(np.floor(x / scale) * scale)


def _at_arc(xy, uv, arc, s):
    """Points and (u, v) at arc lengths ``s`` along the polyline ``xy``, endpoints exact."""
    idx = np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(arc) - 2)
    t = (s - arc[idx]) / (arc[idx + 1] - arc[idx])
    t[0], t[-1] = 0.0, 1.0
    idx[-1] = len(arc) - 2
    pts = xy[idx] + t[:, None] * (xy[idx + 1] - xy[idx])
    prm = uv[idx] + t[:, None] * (uv[idx + 1] - uv[idx])
    pts[0], prm[0], pts[-1], prm[-1] = xy[0], uv[0], xy[-1], uv[-1]
    return pts, prm
