"""The structural guarantee: every planar mesh is checked before it is returned.

Theorem 1 (Problem 1) and Theorem 3 (Problem 2) prove that every edge lies in
``[l, 2l]``; with the tolerance of :mod:`equimesh.tolerance` the output
satisfies ``(1 - REL_TOL) l <= |e| <= 2 (1 + REL_TOL) l``.  Step 5 and
Section 3 output a triangulation of P, none of whose triangles is degenerate
(docs/decisions.md, "A triangle-quality floor").  The same proofs bound the
angles (docs/decisions.md, "Angles of Problems 1 and 2"): a triangle whose
circumcentre is seen from its vertices has circumradius below l and edges at
least l, so its smallest angle is at least 30 degrees (Chew's bound), and
one whose circumcentre is hidden behind a constraint of length c lies in
the cap that constraint cuts off, so its smallest angle is at least
``arccos(c / 2l)``.  :func:`verify_planar` checks all of these on the local
points (O(n), vectorised) and raises :class:`~equimesh.errors.InternalError`
instead of returning a mesh that breaks them: that would be a bug in
equimesh, never a fault of the input.
"""

import numpy as np

from .._geometry import signed_area
from .._jit import compiled
from ..errors import InternalError
from ..mesh import edge_lengths, triangle_orient
from ..tolerance import MIN_TRIANGLE_AREA, REL_TOL, at_least, at_most

_REPORT = "a bug in equimesh, please report it with the input"


def verify_planar(mesh):
    """Check Theorem 1/3 and the triangulation of ``mesh``; raise InternalError naming the first violation.

    * every triangle index in range, every triangle counter-clockwise with an
      area of at least ``MIN_TRIANGLE_AREA l^2`` (:mod:`equimesh.tolerance`:
      below it a triangle is degenerate in floating point);
    * Euler's formula for a triangulated disc with ``k`` holes:
      ``2 n - h - 2 + 2 k`` triangles for ``n`` points of which ``h`` on the
      boundary rings (``V - E + T = 1 - k`` and ``3 T = 2 E - h``);
    * the triangle areas sum to the area enclosed by the outer ring minus the
      holes' rings (to REL_TOL); the rings are the first ``n_boundary``
      points, ``info["boundary_rings"]`` points each (one ring without it);
    * every edge in ``[(1 - REL_TOL) l, 2 (1 + REL_TOL) l]``;
    * every angle at least :func:`angle_bound` of the longest edge of the
      boundary rings (the constraints; the lattice part's are l long).
    """
    points, scale = mesh.local
    l, lp = mesh.length, mesh.length * scale
    n, h, t = len(points), mesh.n_boundary, mesh.triangles
    if t.size and (t.min() < 0 or t.max() >= n):
        k = int(np.flatnonzero(np.any((t < 0) | (t >= n), axis=1))[0])
        raise InternalError(f"triangle {k} {tuple(map(int, t[k]))} refers to a point outside 0..{n - 1}: {_REPORT}")
    area = 0.5 * triangle_orient(points, t)
    flat = np.flatnonzero(~(area > 0))
    if flat.size:
        k = int(flat[0])
        raise InternalError(
            f"triangle {k} {tuple(map(int, t[k]))} is not counter-clockwise with positive area: {_REPORT}"
        )
    thin = np.flatnonzero(~(area >= MIN_TRIANGLE_AREA * lp * lp))
    if thin.size:
        k = int(thin[0])
        raise InternalError(
            f"triangle {k} {tuple(map(int, t[k]))} has area {area[k] / scale**2!r}, below the floor "
            f"{MIN_TRIANGLE_AREA!r} l^2 of a non-degenerate triangle for l = {l!r}: {_REPORT}"
        )
    sizes = mesh.info.get("boundary_rings", (h,))
    holes = len(sizes) - 1
    if len(t) != 2 * n - h - 2 + 2 * holes:
        raise InternalError(
            f"{len(t)} triangles on {n} points ({h} on the boundary, {holes} holes), Euler's formula needs "
            f"{2 * n - h - 2 + 2 * holes}: {_REPORT}"
        )
    ends = np.cumsum(sizes)
    ring = sum(signed_area(points[end - size : end]) for end, size in zip(ends, sizes))
    if not abs(float(np.sum(area)) - ring) <= REL_TOL * ring:
        raise InternalError(
            f"triangle areas sum to {float(np.sum(area)) / scale**2!r}, the polygon's area is {ring / scale**2!r}: "
            f"{_REPORT}"
        )
    lengths = edge_lengths(points, mesh.edges)
    bad = np.flatnonzero(~(at_least(lengths, lp) & at_most(lengths, 2.0 * lp)))
    if bad.size:
        k = int(bad[0])
        i, j = map(int, mesh.edges[k])
        raise InternalError(
            f"edge ({i}, {j}) has length {lengths[k] / scale!r}, outside [l, 2l] for l = {l!r} "
            f"(Theorems 1 and 3): {_REPORT}"
        )
    if t.size:
        ring = np.concatenate([np.roll(np.arange(end - size, end), -1) for end, size in zip(ends, sizes)])
        start = np.concatenate([np.arange(end - size, end) for end, size in zip(ends, sizes)])
        bound = angle_bound(float(np.max(np.linalg.norm(points[ring] - points[start], axis=1))) / lp)
        smallest = np.degrees(smallest_angles(points, t))
        low = np.flatnonzero(smallest < bound - ANGLE_ROUNDING)
        if low.size:
            k = int(low[0])
            raise InternalError(
                f"triangle {k} {tuple(map(int, t[k]))} has an angle of {smallest[k]!r} degrees, below the "
                f"{bound!r} its boundary parts allow: {_REPORT}"
            )
    return mesh


#: Degrees by which an angle may fall below :func:`angle_bound` in rounding: the
#: bound holds for edges at least ``(1 - REL_TOL) l`` and circumradii at most
#: ``(1 + REL_TOL) l``, which move it by about ``2 REL_TOL`` radians.
ANGLE_ROUNDING = 1e-6


def angle_bound(longest_constraint):
    """The smallest angle Problems 1 and 2 guarantee, in degrees, when the longest constraint is
    ``longest_constraint`` l: ``min(30, arccos(c / 2))`` (30 degrees for constraints up to ``sqrt(3) l``)."""
    return float(min(30.0, np.degrees(np.arccos(min(1.0, 0.5 * longest_constraint)))))


def smallest_angles(points, triangles):
    """The smallest interior angle of each plane triangle in radians, (M,).

    The angle opposite the shortest edge (law of sines), ``arctan2(|u x v|, u . v)`` with ``u`` and ``v`` the edges
    from its corner: one ``arctan2`` per triangle, in a compiled loop without the temporaries of gathered rows (those
    cost a tenth of a Problem 1 run at a million points).  Where two edges are equal to rounding, either corner gives
    the same angle to a few ulps, as does numpy's vectorised ``arctan2`` against the C library's: far inside
    :data:`ANGLE_ROUNDING`.
    """
    return _smallest_angles(np.asarray(points, dtype=float), np.asarray(triangles, dtype=np.int64).reshape(-1, 3))


def _smallest_angles(points, triangles):
    out = np.empty(len(triangles))
    for t in range(len(triangles)):
        k, shortest = 0, np.inf
        for j in range(3):  # the edge opposite corner j
            b, c = triangles[t, (j + 1) % 3], triangles[t, (j + 2) % 3]
            dx, dy = points[c, 0] - points[b, 0], points[c, 1] - points[b, 1]
            if dx * dx + dy * dy < shortest:
                k, shortest = j, dx * dx + dy * dy
        a, b, c = triangles[t, k], triangles[t, (k + 1) % 3], triangles[t, (k + 2) % 3]
        ux, uy = points[b, 0] - points[a, 0], points[b, 1] - points[a, 1]
        vx, vy = points[c, 0] - points[a, 0], points[c, 1] - points[a, 1]
        out[t] = np.arctan2(abs(ux * vy - uy * vx), ux * vx + uy * vy)
    return out


_smallest_angles = compiled(_smallest_angles)
