"""Remapping plane nodes to the surface (Section 4, step 4, eqs. (2)-(3)).

A plane node X_i^p inside the flattened auxiliary triangle (q, r, s) is written

    X_i^p = X_q^p0 + alpha (X_r^p0 - X_q^p0) + beta (X_s^p0 - X_q^p0)      (2)

and the same alpha, beta interpolate its parameters

    u_i = u_q^0 + alpha (u_r^0 - u_q^0) + beta (u_s^0 - u_q^0)              (3)

before X_i = X^s(u_i, v_i).  Point location uses matplotlib's trapezoid map
(vectorised, O(log M) per query).

Boundary.  A node that is on the boundary of the plane polygon (given by the
caller), within ``snap_tol`` of it, or found in no triangle at all (rounding
put it just outside) is projected onto the nearest point of the nearest
*boundary segment*, and (u, v) is interpolated along that segment.  The
boundary is the flattened auxiliary triangulation's, or, for the nodes the
caller names, the polygon actually triangulated in step 3 (the resampled
:class:`~equimesh.surface.outline.Outline`, whose vertices carry their exact
(u, v)): :func:`equimesh.mesh_surface` passes it, so that its boundary nodes
take exactly the (u, v) of the outline vertices they sit on; nodes on a hole's
ring are projected onto that ring and interpolated between its vertices'
(u, v), which lie on the hole's polyline with every corner of it among them,
so the node lies on the polyline too.  Both ends of a
boundary segment share the side coordinate (exactly a bound of the chart's
domain, 0.0 or 1.0 on [0, 1]^2), which is then set explicitly: such nodes
land exactly on the boundary of the parameter rectangle.  No node ever fails
to map.
"""

from dataclasses import dataclass

import matplotlib.tri
import numpy as np

from .._checks import finite_rows
from .._geometry import between, nearest_segment
from ..errors import InternalError, InvalidSurfaceError, at
from .charts.chart import Domain
from .optimize.jacobian import signed_areas
from .regularity import evaluate


@dataclass(frozen=True)
class Remap:
    """Result of :func:`locate` / :func:`remap`.

    Attributes
    ----------
    uv : (K, 2) float array
        The parameters u_i of eq. (3), inside the grid's domain.
    triangle : (K,) int array
        The auxiliary triangle k of eq. (2), or -1 for a node projected onto
        the boundary.
    alpha, beta : (K,) float arrays
        The coefficients of eq. (2); ``nan`` for projected nodes.
    on_boundary : (K,) bool array
        Node mapped by boundary projection; its u or v is exactly a bound of the domain.
    segment, t : (K,) arrays
        For projected nodes, the boundary segment ``k`` (from
        ``grid.boundary[k]`` to ``grid.boundary[k + 1]``, or from outline
        vertex ``k`` to ``k + 1`` for the nodes placed on the outline) and the
        position ``t`` in [0, 1] along it; -1 and ``nan`` otherwise.
    points : (K, 3) float array or None
        X^s(u_i, v_i) (filled by :func:`remap`).
    """

    uv: np.ndarray
    triangle: np.ndarray
    alpha: np.ndarray
    beta: np.ndarray
    on_boundary: np.ndarray
    segment: np.ndarray
    t: np.ndarray
    points: np.ndarray | None = None


def remap(surface, plane_points, flat_points, grid, *, on_boundary=None, outline=None, snap_tol=None):
    """Step 4: plane nodes -> (u_i, v_i) by eqs. (2)-(3) -> X_i = X^s(u_i, v_i).

    Parameters
    ----------
    surface : Chart
    plane_points : (K, 2) array_like
        The nodes X_i^p of the plane triangulation (step 3).
    flat_points : (N, 2) array_like
        The flattened auxiliary nodes X_i^p0 (step 2).
    grid : AuxiliaryGrid
        The auxiliary triangulation (step 1): ``uv``, ``triangles``,
        ``boundary``, ``boundary_sides`` and ``domain`` are used.
    on_boundary : array_like of int or bool, optional
        Nodes known to lie on the boundary of the plane polygon, as indices
        or as a mask over the K nodes (e.g. the leading ``n_boundary`` nodes
        of a :class:`~equimesh.mesh.PlanarMesh`); they take the exact
        boundary path wherever they are.
    outline : Outline, optional
        The polygon of step 3 the plane triangulation was built on: the nodes
        of ``on_boundary`` are then projected onto its edges, (u, v)
        interpolated between the exact (u, v) of its vertices (a node on an
        outline vertex takes that vertex's (u, v) bit for bit).
    snap_tol : float, optional
        Nodes within this distance of the flattened boundary also take the
        boundary path; default ``1e-9`` times the diameter of the flattened
        triangulation.

    Returns
    -------
    Remap
        With ``points`` set.

    Raises
    ------
    InvalidSurfaceError
        If the surface is not finite at a remapped (u, v), or an argument is
        malformed: points not finite (K, 2) or (N, 2) rows, ``grid`` no
        auxiliary triangulation or of another size than ``flat_points``.
    """
    loc = locate(plane_points, flat_points, grid, on_boundary=on_boundary, outline=outline, snap_tol=snap_tol)
    points = evaluate(surface, loc.uv)
    return Remap(loc.uv, loc.triangle, loc.alpha, loc.beta, loc.on_boundary, loc.segment, loc.t, points)


#: What :func:`remap` reads of the auxiliary triangulation.
_GRID = ("uv", "triangles", "boundary", "boundary_sides", "domain")


def locate(plane_points, flat_points, grid, *, on_boundary=None, outline=None, snap_tol=None):
    """Eqs. (2)-(3) without the surface: parameters (u_i, v_i) of plane nodes.

    See :func:`remap` for the parameters; ``points`` of the result is None.
    """
    x = finite_rows(plane_points, 2, "plane_points", "plane point {}", InvalidSurfaceError)
    if not all(hasattr(grid, name) for name in _GRID):
        raise InvalidSurfaceError(
            f"grid must be the auxiliary triangulation of step 1 (with {', '.join(_GRID)}), got {type(grid).__name__}"
        )
    per = (len(grid.uv), "node of the grid")
    flat = finite_rows(flat_points, 2, "flat_points", "flattened node {}", InvalidSurfaceError, per)
    tri = np.asarray(grid.triangles)
    k = len(x)
    boundary_path = np.zeros(k, dtype=bool)
    if on_boundary is not None:
        boundary_path[np.asarray(on_boundary)] = True  # indices or a mask
    on_outline = boundary_path.copy() if outline is not None else np.zeros(k, dtype=bool)

    triangulation = matplotlib.tri.Triangulation(flat[:, 0], flat[:, 1], tri)
    found = np.asarray(matplotlib.tri.TrapezoidMapTriFinder(triangulation)(x[:, 0], x[:, 1]), dtype=np.int64)
    boundary_path |= found < 0

    loop = Loop(flat[grid.boundary], grid.uv[grid.boundary], grid.boundary_segment_side, grid.domain)
    if snap_tol is None:
        snap_tol = 1e-9 * float(np.linalg.norm(flat.max(axis=0) - flat.min(axis=0)))
    if snap_tol > 0:
        near = ~boundary_path
        if np.any(near):
            dist = loop.distance(x[near])
            boundary_path[np.flatnonzero(near)[dist <= snap_tol]] = True

    uv = np.empty((k, 2))
    alpha = np.full(k, np.nan)
    beta = np.full(k, np.nan)
    segment = np.full(k, -1, dtype=np.int64)
    t = np.full(k, np.nan)
    triangle = np.where(boundary_path, -1, found)

    inside = ~boundary_path
    if np.any(inside):
        a, b = barycentric(x[inside], flat[tri[found[inside]]])
        alpha[inside], beta[inside] = a, b
        q, r, s = (grid.uv[tri[found[inside], j]] for j in range(3))
        uv[inside] = q + a[:, None] * (r - q) + b[:, None] * (s - q)  # eq. (3)

    paths = [(boundary_path & ~on_outline, loop)]
    if outline is not None:
        paths.append((on_outline, outline.loop()))
    for nodes, ring in paths:
        if np.any(nodes):
            segment[nodes], t[nodes], uv[nodes] = ring.project(x[nodes])
    uv = grid.domain.clip(uv)
    return Remap(uv, triangle, alpha, beta, boundary_path, segment, t)


@dataclass(frozen=True)
class Loop:
    """Closed boundary polylines on the plane whose vertices carry their exact (u, v).

    Segment ``k`` runs from vertex ``k`` to vertex ``succ[k]`` (the next one
    around its ring; default: one ring, ``k + 1``).  ``side[k]`` is the side
    (index into :data:`~equimesh.surface.charts.chart.SIDES`) of ``domain`` that
    segment lies on, or -1 for a segment inside the domain (on a hole).
    """

    xy: np.ndarray
    uv: np.ndarray
    side: np.ndarray
    domain: Domain
    succ: np.ndarray | None = None

    @property
    def successors(self):
        """``succ``, or by default ``k + 1`` around one ring: the vertex that ends each segment."""
        return np.roll(np.arange(len(self.xy)), -1) if self.succ is None else self.succ

    def distance(self, x):
        """Distance of points ``x`` to their nearest segment."""
        return nearest_segment(x, self.xy, self.xy[self.successors])[2]

    def project(self, x):
        """Nearest segment, position ``t`` on it and (u, v) there (eq. (3) on a boundary edge) for points ``x``.

        ``(1 - t) uv_a + t uv_b`` is exact at both ends; on a side of the
        domain the side coordinate is then set to exactly the domain's bound.
        """
        succ = self.successors
        seg, tt, _ = nearest_segment(x, self.xy, self.xy[succ])
        uv = between(self.uv[seg], self.uv[succ[seg]], tt)
        side = self.side[seg]  # index into SIDES = (u=u0, u=u1, v=v0, v=v1), -1 inside
        on = np.flatnonzero(side >= 0)
        uv[on, side[on] // 2] = self.domain.side_values[side[on]]
        return seg, tt, uv


def to_plane(uv, flat_points, grid):
    """Eqs. (2)-(3) forward: (u, v) points to the flattened plane, by their barycentric coordinates in the auxiliary
    triangles.

    A point on an auxiliary edge has the same image from both triangles
    (the map is continuous and linear on each triangle).

    Raises
    ------
    InternalError
        A point outside the auxiliary triangulation (callers pass points of the domain).
    """
    uv = np.asarray(uv, dtype=float).reshape(-1, 2)
    tri = np.asarray(grid.triangles)
    triangulation = matplotlib.tri.Triangulation(grid.uv[:, 0], grid.uv[:, 1], tri)
    found = np.asarray(matplotlib.tri.TrapezoidMapTriFinder(triangulation)(uv[:, 0], uv[:, 1]), dtype=np.int64)
    if np.any(found < 0):
        k = int(np.flatnonzero(found < 0)[0])
        raise InternalError(f"{at(uv[k])} is in no auxiliary triangle")
    a, b = barycentric(uv, grid.uv[tri[found]])
    q, r, s = (flat_points[tri[found, j]] for j in range(3))
    return q + a[:, None] * (r - q) + b[:, None] * (s - q)


def barycentric(x, corners):
    """Coefficients (alpha, beta) of eq. (2) for points ``x`` (K, 2) in triangles ``corners`` (K, 3, 2).

    Solved by Cramer's rule and clamped to the closed triangle (``alpha,
    beta >= 0``, ``alpha + beta <= 1``), which only moves a point that
    rounding placed a hair outside the triangle reported by point location.
    """
    q, r, s = corners[:, 0], corners[:, 1], corners[:, 2]
    e1, e2, d = r - q, s - q, x - q
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    a = (d[:, 0] * e2[:, 1] - d[:, 1] * e2[:, 0]) / det
    b = (e1[:, 0] * d[:, 1] - e1[:, 1] * d[:, 0]) / det
    a, b = np.maximum(a, 0.0), np.maximum(b, 0.0)
    over = a + b > 1.0
    total = a[over] + b[over]
    a[over], b[over] = a[over] / total, b[over] / total
    return a, b


__all__ = ["Loop", "Remap", "barycentric", "locate", "remap", "to_plane"]


def check_remapped(uv, plane, length):
    """Refuse a plane triangle that eqs. (2)-(3) map to a flat or inverted triangle in (u, v), naming the spacing
    ``length`` (a :class:`~equimesh.surface.plane_length.PlaneLength`) the plane was meshed at.

    Eqs. (2)-(3) map each node through the flattening's piecewise-linear
    inverse, which keeps every auxiliary triangle's orientation, but a mesh
    triangle spans several auxiliary ones: where the flattening's distortion
    turns within about l, its straight image in (u, v) can fold.  Boundary
    nodes are remapped onto the boundary, which is straight in (u, v) along a
    chart's side (and along each edge of a mesh's loop) while its flattened
    image bends: where it bends within a few l, Problem 2 joins three nodes of
    one straight stretch in a triangle (an ear of the strip), flat in (u, v).
    Either is the surface's shape at this l and grid, not a fault of a stage,
    and is refused naming where (docs/decisions.md, "A remapped triangle that
    folds is refused").
    """
    triangles = plane.triangles
    bad = ~(signed_areas(uv, triangles) > 0)
    ears = np.flatnonzero(bad & np.all(triangles < plane.n_boundary, axis=1))
    if ears.size:
        raise InvalidSurfaceError(
            f"the flattened boundary bends so sharply near {at(uv[triangles[ears[0]]].mean(axis=0))} that Problem 2 "
            f"joins three boundary nodes there in a triangle ({ears.size} such in all), flat in (u, v), where the "
            f"boundary is straight, at {length}; use a finer auxiliary grid or another l"
        )
    bad = np.flatnonzero(bad)
    if bad.size:
        raise InvalidSurfaceError(
            f"mapping the plane mesh back onto the surface (eqs. 2-3) folds {bad.size} of {len(triangles)} triangles, "
            f"first near {at(uv[triangles[bad[0]]].mean(axis=0))}: the flattening's distortion turns there within a "
            f"member's length at {length}; use a smaller l or a finer auxiliary grid"
        )
