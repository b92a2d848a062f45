"""Section 4, step 3: the boundary of the flattened auxiliary triangulation as a polygon.

The boundary of the flattened auxiliary triangulation is a closed polyline
through the images of the boundary nodes of the parameter rectangle,
generally not convex (paper, Fig. 2).  It is resampled into polygon edges
between l and 2l, the input of Problem 2 (:func:`equimesh.uniform_triangulation`),
by :func:`resample_ring`, which serves any closed plane polyline with marked
corners (here the images of the four corners of the grid's domain):

* the sides between corners get the points of Step 2 exactly as a polygon's
  sides do in Problem 2 (:func:`equimesh.planar.polygon.side_positions`, at
  arc length): ``k`` equal parts by :func:`~equimesh.planar.polygon.split_counts`,
  or, next to a corner sharper than :data:`~equimesh.planar.polygon.SHARP_CORNER`,
  the staggered points of :func:`~equimesh.planar.polygon.stagger`;
  a part's chord is at most its arc, so at most ``2l``; where curvature makes
  a chord shorter than ``l``, the side falls back to ``k - 1, k - 2, ...``
  equal parts;
* every polygon vertex lies on the polyline, with the segment and fraction
  it sits at, so its parameters (for the outline its (u, v), on the boundary
  of the parameter rectangle: paper, eq. (3) on a boundary edge) are known
  exactly.
"""

from dataclasses import dataclass

import numpy as np

from .._geometry import cross
from ..errors import SurfaceTooSmallError
from ..planar.polygon import side_positions
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


def resample_ring(xy, params, corners, l, spacing, too_short=None):
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

    The points of side ``i`` are those of :func:`~equimesh.planar.polygon.side_positions`
    on the ring of the sides' arc lengths and the polyline's inner angles at
    the corners (so a corner sharper than ``SHARP_CORNER`` is staggered as in
    Problem 2), at arc length.  Every part is at most ``2l`` along the arc,
    so its chord is too; a side with a chord shorter than ``l`` falls back
    to equal parts, one fewer at a time.
    """
    xy, params = np.asarray(xy, dtype=float), np.asarray(params, dtype=float)
    corners = np.asarray(corners, dtype=np.int64)
    n = len(xy)
    chains = [np.r_[c0 : c1 + 1] if c1 > c0 else np.r_[c0:n, : c1 + 1] for c0, c1 in zip(corners, np.roll(corners, -1))]
    arcs = [np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(xy[c], axis=0), axis=1))]) for c in chains]
    sides = side_positions([arc[-1] for arc in arcs], [inner_angle(xy, c) for c in corners], l, spacing)
    points, carried, side = [], [], []
    for i, (chain, arc, (num, den)) in enumerate(zip(chains, arcs, sides)):
        pts, prm = _split_side(xy[chain], params[chain], arc, num, den, l)
        if pts is None:
            chord = float(np.linalg.norm(xy[chain[-1]] - xy[chain[0]]))
            raise (too_short or _too_short)(i, float(arc[-1]), chord)
        points.append(pts[:-1])
        carried.append(prm[:-1])
        side.append(np.full(len(pts) - 1, i))
    return Ring(np.vstack(points), np.vstack(carried), np.concatenate(side))


def inner_angle(xy, i):
    """Inner angle (degrees, in [0, 360)) of the closed polyline ``xy`` at point ``i``, the region on its left."""
    p = xy[i]
    u, w = xy[i - 1] - p, xy[(i + 1) % len(xy)] - p
    return float(np.degrees(np.arctan2(cross(w, u), np.dot(w, u))) % 360.0)


def _split_side(xy, params, arc, num, den, l):
    """Points of one side at arc lengths ``arc[-1] * num / den``, else at ``k - 1, k - 2, ...`` equal parts: the first with chords >= l."""
    length, k = arc[-1], len(num)  # k = 0: the side is shorter than l
    for num, den in [(num, den)][:k] + [(np.arange(j, dtype=float), float(j)) for j in range(k - 1, 0, -1)]:
        pts, prm = _at_arc(xy, params, arc, np.append(length * num / den, length))
        if np.all(at_least(np.linalg.norm(np.diff(pts, axis=0), axis=1), l)):
            return pts, prm
    return None, None


def _too_short(side, arc, chord):
    """The default refusal of :func:`resample_ring`: a side the resampling cannot split into chords of at least l."""
    return SurfaceTooSmallError(
        f"side {side} of the boundary polyline is {number(arc)} long (its ends {number(chord)} apart), "
        "too short to split into parts of at least l"
    )


def resample_outline(plane, grid, l, spacing):
    """Resample the flattened boundary ``plane[grid.boundary]`` into a polygon (:func:`resample_ring`).

    ``plane`` holds the flattened nodes of the auxiliary grid ``grid`` (step
    2); the corners are the images of the corners of the grid's domain, in
    the counter-clockwise order of ``grid.boundary``.

    Raises
    ------
    SurfaceTooSmallError
        A side whose corners are closer than ``l`` on the plane, named by its
        side and corners of the parameter rectangle.
    """
    loop, uv, domain = grid.boundary, grid.uv[grid.boundary], grid.domain
    corners = np.flatnonzero(grid.boundary_corner)
    ends = [(uv[c0], uv[c1]) for c0, c1 in zip(corners, np.roll(corners, -1))]

    def too_short(side, arc, chord):
        a, b = ends[side]
        return SurfaceTooSmallError(
            f"{side_name(side_index(a, b, domain), domain)} of the surface, from {corner_name(a)} to {corner_name(b)}, "
            f"is {number(arc)} long on the flattened surface (its corners {number(chord)} apart), "
            f"shorter than l = {number(l)}; use l <= {number(round_down(chord))}"
        )

    ring = resample_ring(plane[loop], uv, corners, l, spacing, too_short)
    sides = np.array([side_index(a, b, domain) for a, b in ends])
    return Outline(ring.points, ring.params, sides[ring.side], domain)


def side_index(uv_a, uv_b, domain):
    """Index into :data:`~equimesh.surface.chart.SIDES` of the side of ``domain`` through two of its points."""
    axis = 0 if uv_a[0] == uv_b[0] else 1
    return 2 * axis + int(uv_a[axis] == domain.upper[axis])


def round_down(x, digits=4):
    """``x`` rounded down to ``digits`` significant digits, so that a suggested bound ``l <= x`` is safe."""
    if x <= 0:
        return 0.0
    scale = 10.0 ** (np.floor(np.log10(x)) - digits + 1)
    return float(np.floor(x / scale) * scale)


def _at_arc(xy, params, arc, s):
    """Points and parameters at arc lengths ``s`` along the polyline ``xy``, endpoints exact."""
    idx = np.clip(np.searchsorted(arc, s, side="right") - 1, 0, len(arc) - 2)
    t = (s - arc[idx]) / (arc[idx + 1] - arc[idx])
    t[0], t[-1] = 0.0, 1.0
    idx[-1] = len(arc) - 2
    pts = xy[idx] + t[:, None] * (xy[idx + 1] - xy[idx])
    prm = params[idx] + t[:, None] * (params[idx + 1] - params[idx])
    pts[0], prm[0], pts[-1], prm[-1] = xy[0], params[0], xy[-1], params[-1]
    return pts, prm
