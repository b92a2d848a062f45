"""A piecewise-linear chart on the flattening of a triangle mesh (Section 4, steps 2 and 4).

When the auxiliary triangulation is the user's own mesh
(:class:`~equimesh.surface.charts.triangulated.TriangulatedSurface`) there is no
parameter rectangle; the flattened mesh of step 2 is the parameter plane.
:class:`MeshChart` is the map from it back to the mesh: a point ``(u, v)`` of
the flattened triangle ``(q, r, s)`` with the coefficients ``alpha, beta`` of
eq. (2) goes to ``X_q + alpha (X_r - X_q) + beta (X_s - X_q)``, a point of the
input triangle.  Eq. (3) is then the identity (a plane node's parameters are
its plane coordinates) and X^s(u, v) is eq. (2) applied to the 3-D vertices:
every remapped node lies on the input surface.  The derivatives are the
constant Jacobian of each triangle (second derivatives zero).

Outside the flattened mesh the chart is continued by the nearest point of its
boundary, so that it is defined on the whole plane and every value is a point
of the input surface.  The final optimisation keeps the boundary fixed and
refuses fold-over, so its inner nodes stay inside the polygon of the boundary
nodes (docs/decisions.md, "The flattening of a mesh is its chart").

:func:`flattening_start` chooses the start of eq. (1): the projection onto
the best-fit plane, or where that folds the least-squares conformal map, or
where that folds too Tutte's embedding with the longest boundary loop on a
circle, which never folds a disc.
"""

import matplotlib.tri
import numpy as np
import scipy.sparse
import scipy.sparse.linalg
import shapely

from ..._geometry import nearest_segment as nearest_segment
from ..._geometry import orient
from ...errors import InvalidSurfaceError
from ...mesh import triangle_orient, unique_edges
from ...planar.insertion.region import constrained_delaunay
from ...tolerance import REL_TOL
from ..flatten import flatten, plane_start
from ..remap import barycentric
from .chart import Domain


class MeshChart:
    """The chart X^s of a :class:`~equimesh.surface.charts.triangulated.TriangulatedSurface` on its flattening.

    Parameters
    ----------
    surface : TriangulatedSurface
    plane : (N, 2) array_like
        The flattened vertices (step 2), every triangle counter-clockwise, no
        two triangles overlapping.

    Attributes
    ----------
    domain : Domain
        The bounding box of the flattening (the bounds of the optimisation).
    outer : int
        The index in ``surface.loops`` of the outer boundary on the plane.
    surface, plane
    finer : str
        What refines this chart, for refusals (:func:`~equimesh.surface.optimize.optimize_uv`):
        the input mesh, where a parametric chart has its auxiliary grid.

    Raises
    ------
    InvalidSurfaceError
        The flattening overlaps itself (:func:`check_one_to_one`).
    """

    finer = "a finer input mesh"

    def __init__(self, surface, plane):
        self.surface = surface
        self.plane = np.asarray(plane, dtype=float)
        self.outer = check_one_to_one(surface, self.plane)
        lo, hi = self.plane.min(axis=0), self.plane.max(axis=0)
        self.domain = Domain((lo[0], hi[0]), (lo[1], hi[1]))
        tri = surface.triangles
        self._finder = matplotlib.tri.TrapezoidMapTriFinder(
            matplotlib.tri.Triangulation(self.plane[:, 0], self.plane[:, 1], tri)
        )
        x, p = surface.vertices[tri], self.plane[tri]
        e3 = np.stack([x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]], axis=2)  # (M, 3, 2)
        e2 = np.stack([p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]], axis=2)  # (M, 2, 2)
        self._jacobian = e3 @ np.linalg.inv(e2)  # (M, 3, 2): columns X_u, X_v
        loops = surface.loops
        self._seg_a = np.concatenate([loop for loop in loops])
        self._seg_b = np.concatenate([np.roll(loop, -1) for loop in loops])
        # The triangle carrying each boundary segment (its half-edge a -> b).
        he = {(int(a), int(b)): k for k, row in enumerate(tri) for a, b in zip(row, np.roll(row, -1))}
        self._seg_triangle = np.array([he[(int(a), int(b))] for a, b in zip(self._seg_a, self._seg_b)], dtype=np.int64)

    def locate(self, u, v):
        """Triangle and coefficients ``(alpha, beta)`` of eq. (2) for each point (outside: at its nearest boundary
        point)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        x = np.column_stack([u.ravel(), v.ravel()])
        found = np.asarray(self._finder(x[:, 0], x[:, 1]), dtype=np.int64)
        out = np.flatnonzero(found < 0)
        if out.size:
            seg, t, _ = nearest_segment(x[out], self.plane[self._seg_a], self.plane[self._seg_b])
            x = x.copy()
            a, b = self.plane[self._seg_a[seg]], self.plane[self._seg_b[seg]]
            x[out] = a + t[:, None] * (b - a)
            found[out] = self._seg_triangle[seg]
        alpha, beta = barycentric(x, self.plane[self.surface.triangles[found]])
        return found, alpha, beta, u.shape

    def evaluate(self, u, v):
        """Points of the input surface by eq. (2) in the flattened triangle holding ``(u, v)``."""
        k, alpha, beta, shape = self.locate(u, v)
        x = self.surface.vertices[self.surface.triangles[k]]
        points = x[:, 0] + alpha[:, None] * (x[:, 1] - x[:, 0]) + beta[:, None] * (x[:, 2] - x[:, 0])
        return points.reshape(shape + (3,))

    def derivatives(self, u, v):
        """(X_u, X_v): the Jacobian of the triangle holding ``(u, v)``, constant on it."""
        k, _, _, shape = self.locate(u, v)
        jac = self._jacobian[k]
        return jac[:, :, 0].reshape(shape + (3,)), jac[:, :, 1].reshape(shape + (3,))


def check_one_to_one(surface, plane):
    """The index of the loop enclosing all others on the plane; refuse a flattening that overlaps itself.

    Every flattened triangle is counter-clockwise (:func:`~equimesh.surface.flatten.flatten`
    checks it).  The flattening is then one-to-one exactly when, in addition,
    the loops bound a valid polygon with holes (the largest loop outside, the
    others inside it and apart) whose area is the triangles' total (up to
    ``REL_TOL``): eq. (1) can squeeze an opening of a strongly curved mesh
    until its rim crosses itself, with every triangle still counter-clockwise.
    """
    loops = [plane[loop] for loop in surface.loops]
    outer = int(np.argmax([shapely.Polygon(xy).area for xy in loops]))
    region = shapely.Polygon(loops[outer], [xy for k, xy in enumerate(loops) if k != outer])
    p = plane[surface.triangles]
    total = 0.5 * float(orient(p[:, 0], p[:, 1], p[:, 2]).sum())
    if not region.is_valid or abs(region.area - total) > REL_TOL * total:
        crossing = [k for k, xy in enumerate(loops) if not shapely.LinearRing(xy).is_simple]
        which = (
            f"boundary loop {crossing[0]} of {len(loops)} crosses itself" if crossing else "its boundary loops cross"
        )
        raise InvalidSurfaceError(
            f"the flattened triangle mesh overlaps itself ({which} on the plane): the surface is too strongly curved "
            "to flatten by eq. (1) in one piece; cut it into flatter pieces"
        )
    return outer


def flatten_mesh(surface):
    """Step 2 for a triangle mesh: eq. (1) on its edges from :func:`flattening_start`, its openings capped.

    Eq. (1) alone keeps every triangle counter-clockwise (its fold-over
    barrier) but not an opening open: on a doubly curved mesh it can squeeze
    an opening until its rim crosses itself (a 20 x 14 vault rising 5 on 40 x
    28 cells: its 4 x 2 opening crossed, the smallest triangle at 6 % of its
    start area).  Each opening whose rim is simple in the start is therefore
    covered by triangles of its rim vertices (:func:`opening_caps`), which
    take part in the fold-over barrier and the orientation check but not in
    the energy (``edges`` are the mesh's own): eq. (1) is minimised as
    written, and the opening cannot close or turn over.
    """
    start = flattening_start(surface)
    caps = opening_caps(surface, start)
    return flatten(
        surface.vertices, np.vstack([surface.triangles, caps]), x0=start, edges=unique_edges(surface.triangles)
    )


def opening_caps(surface, start):
    """Triangles (counter-clockwise in ``start``) filling every loop but the outer one whose rim is simple in
    ``start``."""
    loops = [start[loop] for loop in surface.loops]
    outer = int(np.argmax([shapely.Polygon(xy).area for xy in loops]))
    caps = [np.empty((0, 3), dtype=np.int64)]
    for k, loop in enumerate(surface.loops):
        if k == outer or not shapely.LinearRing(start[loop]).is_simple:
            continue
        ring = np.column_stack([np.arange(len(loop)), np.roll(np.arange(len(loop)), -1)])
        caps.append(loop[constrained_delaunay(start[loop], ring, np.empty((0, 2)))])
    return np.vstack(caps)


def flattening_start(surface):
    """The start of eq. (1): the first of these that folds no triangle.

    The projection onto the best-fit plane (right for a roof over its plan),
    else the least-squares conformal map (:func:`conformal_start`: exact up to
    scale on a developable surface), else Tutte's embedding
    (:func:`harmonic_start`, which never folds a disc).
    """
    tri = surface.triangles
    projected = plane_start(surface.vertices, tri)
    if _unfolded(projected, tri):
        return projected
    conformal = conformal_start(surface)
    return conformal if conformal is not None else harmonic_start(surface)


def _unfolded(x, tri):
    return bool(np.all(triangle_orient(x, tri) > 0))


def conformal_start(surface):
    """Least-squares conformal map (Levy et al. 2002), scaled to the mesh's edge lengths; None if it folds.

    Each triangle, in an orthonormal frame of its plane with corners
    ``(x_j, y_j)``, contributes ``|sum_j W_j (u_j + i v_j)|^2 / (2 A)`` with
    ``W_j = (x_{j+2} - x_{j+1}) + i (y_{j+2} - y_{j+1})``, zero exactly for a
    similarity of the triangle.  Two boundary vertices (the first of the
    longest loop and the loop vertex farthest from it) are pinned; the rest
    is a sparse linear least-squares problem.
    """
    x, tri = surface.vertices, surface.triangles
    n, m = len(x), len(tri)
    p = x[tri]
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    ax = e1 / np.linalg.norm(e1, axis=1, keepdims=True)
    normal = np.cross(e1, e2)
    ay = np.cross(normal / np.linalg.norm(normal, axis=1, keepdims=True), ax)
    local = np.stack(
        [
            np.zeros((m, 2)),
            np.column_stack([np.linalg.norm(e1, axis=1), np.zeros(m)]),
            np.column_stack([np.einsum("ij,ij->i", e2, ax), np.einsum("ij,ij->i", e2, ay)]),
        ],
        axis=1,
    )
    w = np.roll(local, -2, axis=1) - np.roll(local, -1, axis=1)  # (m, 3, 2): W_j = corner j+2 - corner j+1
    scale = 1.0 / np.sqrt(np.abs(orient(local[:, 0], local[:, 1], local[:, 2])))[:, None]
    a, b = w[:, :, 0] * scale, w[:, :, 1] * scale
    rows = np.repeat(np.arange(m), 3)
    cols = tri.ravel()
    # Real part: sum a_j u_j - b_j v_j; imaginary part: sum b_j u_j + a_j v_j.  Unknowns (u_0..u_n-1, v_0..v_n-1).
    matrix = scipy.sparse.coo_matrix(
        (
            np.concatenate([a.ravel(), -b.ravel(), b.ravel(), a.ravel()]),
            (np.concatenate([rows, rows, rows + m, rows + m]), np.concatenate([cols, cols + n, cols, cols + n])),
        ),
        shape=(2 * m, 2 * n),
    ).tocsc()
    loop = surface.loops[0]
    first = int(loop[0])
    second = int(loop[np.argmax(np.linalg.norm(x[loop] - x[first], axis=1))])
    pinned = np.array([first, second, first + n, second + n])
    values = np.array([0.0, float(np.linalg.norm(x[second] - x[first])), 0.0, 0.0])
    free = np.setdiff1d(np.arange(2 * n), pinned)
    lhs = matrix[:, free]
    rhs = -(matrix[:, pinned] @ values)
    solution = np.empty(2 * n)
    solution[pinned] = values
    solution[free] = scipy.sparse.linalg.splu((lhs.T @ lhs).tocsc()).solve(lhs.T @ rhs)
    start = solution.reshape(2, n).T
    if not _unfolded(start, tri):
        start[:, 1] = -start[:, 1]
        if not _unfolded(start, tri):
            return None
    e = unique_edges(tri)
    return start * (
        np.linalg.norm(x[e[:, 1]] - x[e[:, 0]], axis=1).sum()
        / np.linalg.norm(start[e[:, 1]] - start[e[:, 0]], axis=1).sum()
    )


def harmonic_start(surface):
    """Tutte's embedding: the longest boundary loop on a circle by arc length, every other vertex the mean of its
    neighbours.

    The circle has the loop's length as circumference and runs
    counter-clockwise along the loop (surface on its left), so the
    triangles come out counter-clockwise.  For a disc (one loop) no triangle
    folds (Tutte, Floater); the vertices of other loops are averaged like
    inner vertices.
    """
    x, loop = surface.vertices, surface.loops[0]
    n = len(x)
    seg = np.linalg.norm(x[np.roll(loop, -1)] - x[loop], axis=1)
    arc = np.concatenate([[0.0], np.cumsum(seg)[:-1]])
    angle = 2.0 * np.pi * arc / seg.sum()
    radius = seg.sum() / (2.0 * np.pi)
    fixed = np.zeros(n, dtype=bool)
    fixed[loop] = True
    start = np.zeros((n, 2))
    start[loop] = radius * np.column_stack([np.cos(angle), np.sin(angle)])
    e = unique_edges(surface.triangles)
    adjacency = scipy.sparse.coo_matrix(
        (np.ones(2 * len(e)), (np.r_[e[:, 0], e[:, 1]], np.r_[e[:, 1], e[:, 0]])), shape=(n, n)
    ).tocsr()
    laplacian = (scipy.sparse.diags(np.asarray(adjacency.sum(axis=1)).ravel()) - adjacency).tocsr()
    free = np.flatnonzero(~fixed)
    if free.size:
        rhs = -laplacian[free][:, np.flatnonzero(fixed)] @ start[fixed]
        solve = scipy.sparse.linalg.factorized(laplacian[free][:, free].tocsc())
        start[free] = np.column_stack([solve(rhs[:, 0]), solve(rhs[:, 1])])
    return start
