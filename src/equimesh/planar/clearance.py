"""Which lattice vertices lie inside P at clearance from its boundary (Problem 2, Section 3), in time ~ perimeter.

The lattice part K of :mod:`equimesh.planar.lattice` keeps a lattice vertex
when it lies inside P and ``at_least(d(x, boundary), clearance l)``.  Testing
every vertex against the boundary (a shapely distance per vertex, each
O(boundary edges)) costs O(A / l^2 * P / l); the placement search does it
for hundreds of placements.  Here the same answer is obtained row by row:

* Band.  A vertex within ``R`` of a boundary segment lies on a lattice row
  ``j`` within ``R / h`` (``h = l sqrt(3) / 2``, the row spacing) of the
  segment, and within ``R / h`` lattice steps of the part of the segment
  between rows ``j -+ R / h``.  Each segment yields, per row it reaches, an
  interval of lattice indices containing every vertex within ``R`` of it; the
  distance is computed for those (vertex, segment) pairs only:
  O((P / l) (clearance + 1)) pairs in all.
* Inside.  A vertex farther than ``R`` from every segment is inside P iff an
  odd number of boundary crossings of its row lie to its left (crossings
  are counted with a difference array and a cumulative sum along the row).
* Doubt.  A vertex whose computed distance lies within ``DOUBT`` (relative)
  of the threshold ``(1 - REL_TOL) clearance l`` is decided by the original
  test (shapely's containment and distance), so that rounding in the band's
  own distance can never change the answer.

Cost of one call: O(A / l^2) elementwise array operations (the index grid,
its coordinates, one cumulative sum: tens of nanoseconds per lattice vertex)
plus O(P / l) distance evaluations and shapely calls only for the vertices
in doubt (those exactly at clearance, e.g. on a lattice aligned with the
boundary).
"""

import numpy as np
import shapely

from .._geometry import point_segment_distance
from ..tolerance import REL_TOL, at_least

#: Relative width of the doubtful window around the clearance threshold: a vertex
#: whose band distance is within it is decided by shapely, as before.  The band's
#: distance and shapely's differ by a few ulps (1e-16 relative), and the lattice
#: coordinates by at most 2^16 l * 1e-16: the window is 10^8 times wider.
DOUBT = 1e-7


def expand(lo, hi):
    """Rows ``(k, value)`` for every integer value in ``[lo[k], hi[k]]`` (empty ranges give nothing)."""
    counts = np.maximum(hi - lo + 1, 0)
    owner = np.repeat(np.arange(len(lo)), counts)
    starts = np.cumsum(counts) - counts
    return owner, lo[owner] + (np.arange(len(owner)) - starts[owner])


def clear_of_boundary(shape, points, first, grid_shape, offset, basis, distance):
    """Boolean grid: lattice vertex inside ``shape`` and ``at_least(d(x, boundary), distance)``.

    ``points`` ``(ni * nj, 2)`` are the coordinates of lattice indices
    ``first + (a, b)`` for ``(a, b)`` in the ``grid_shape = (ni, nj)`` grid, row
    major, computed as ``offset + (i, j) @ basis``.  ``shape`` is a shapely
    polygon (holes included); ``distance`` the clearance ``clearance * l``.
    """
    ni, nj = grid_shape
    i0, j0 = first
    inv = np.linalg.inv(basis)
    h = abs(float(np.linalg.det(basis))) / float(np.linalg.norm(basis[1]))
    threshold = (1.0 - REL_TOL) * distance
    reach = (1.0 + 2.0 * DOUBT) * distance
    w = reach / h
    rings = [np.asarray(r.coords, dtype=float)[:-1] for r in (shape.exterior, *shape.interiors)]
    a = np.vstack(rings)
    b = np.vstack([np.roll(r, -1, axis=0) for r in rings])
    ua, ub = (a - offset) @ inv, (b - offset) @ inv

    # Band: (segment, row) pairs, then (segment, vertex) pairs, then the nearest segment per vertex.
    vlo, vhi = np.minimum(ua[:, 1], ub[:, 1]), np.maximum(ua[:, 1], ub[:, 1])
    seg, row = expand(
        np.maximum(np.ceil(vlo - w), j0).astype(np.int64), np.minimum(np.floor(vhi + w), j0 + nj - 1).astype(np.int64)
    )
    dv = ub[seg, 1] - ua[seg, 1]
    flat = dv == 0.0
    # The divisor is never 0 and the numerators are finite, so only a nearly flat segment (dv tiny) can
    # overflow: t is then +-inf, clipped to [0, 1] below.
    with np.errstate(over="ignore"):
        t1 = np.where(flat, 0.0, (row - w - ua[seg, 1]) / np.where(flat, 1.0, dv))
        t2 = np.where(flat, 1.0, (row + w - ua[seg, 1]) / np.where(flat, 1.0, dv))
    t_lo, t_hi = np.clip(np.minimum(t1, t2), 0.0, 1.0), np.clip(np.maximum(t1, t2), 0.0, 1.0)
    du = ub[seg, 0] - ua[seg, 0]
    u1, u2 = ua[seg, 0] + t_lo * du, ua[seg, 0] + t_hi * du
    i_lo = np.maximum(np.ceil(np.minimum(u1, u2) - w), i0).astype(np.int64)
    i_hi = np.minimum(np.floor(np.maximum(u1, u2) + w), i0 + ni - 1).astype(np.int64)
    pair, col = expand(i_lo, i_hi)
    vertex = (col - i0) * nj + (row[pair] - j0)
    s = seg[pair]
    near = np.full(ni * nj, np.inf)
    np.minimum.at(near, vertex, point_segment_distance(points[vertex], a[s], b[s]))

    # Inside: parity of the boundary crossings left of each vertex along its row.
    # Rows j with vlo <= j < vhi, the rows each segment crosses (a horizontal segment crosses none).
    crossing, j = expand(
        np.maximum(np.ceil(vlo), j0).astype(np.int64), np.minimum(np.ceil(vhi) - 1, j0 + nj - 1).astype(np.int64)
    )
    uc = ua[crossing, 0] + (j - ua[crossing, 1]) * (ub[crossing, 0] - ua[crossing, 0]) / (
        ub[crossing, 1] - ua[crossing, 1]
    )
    toggles = np.zeros((ni + 1, nj), dtype=np.int64)
    np.add.at(toggles, (np.clip(np.floor(uc).astype(np.int64) + 1 - i0, 0, ni), j - j0), 1)
    inside = (np.cumsum(toggles[:ni], axis=0) & 1).astype(bool).ravel()

    # Outside the doubtful window the band's distance is on the right side of the threshold.
    kept = inside & (near > threshold)
    doubt = np.flatnonzero(np.abs(near - threshold) <= DOUBT * threshold)
    if doubt.size:
        p = points[doubt]
        exact = shapely.contains_xy(shape, p[:, 0], p[:, 1])
        exact[exact] = at_least(shapely.distance(shapely.points(p[exact]), shape.boundary), distance)
        kept[doubt] = exact
    return kept.reshape(ni, nj)


__all__ = ["DOUBT", "clear_of_boundary"]
