"""Sparse Jacobians of per-element residuals, and the fold-over barrier, for Section 4.

Both least-squares problems of Section 4 (eq. (1) and the final (u, v)
optimisation) have residuals that each depend on the coordinates of a few
nodes only: one per edge ``(a, b)``, or one per triangle ``(a, b, c)`` for the
fold-over barrier.  :class:`ElementJacobian` fixes the CSR structure once; each
call only fills in the values.
"""

import copy

import numpy as np
import scipy.sparse

from ..._jit import compiled
from ...mesh import triangle_orient


class ElementJacobian:
    """CSR assembly of ``d r_j / d x`` for residuals ``r_j`` of the nodes of element ``j``.

    Parameters
    ----------
    elements : (E, k) int array
        One row of node indices per residual (k = 2 for edges, 3 for triangles).
    n_nodes : int
    dim : int
        Coordinates per node (2 for plane points and for (u, v)).
    free : (dim * n_nodes,) bool array, optional
        Which entries of ``x.ravel()`` (node-major) are variables, i.e.
        Jacobian columns, in order; all by default.  Derivatives with respect
        to fixed entries are dropped.
    """

    def __init__(self, elements, n_nodes, dim, free=None):
        e = np.asarray(elements, dtype=np.int64)
        free = np.ones(dim * n_nodes, dtype=bool) if free is None else np.asarray(free, dtype=bool)
        column = np.full(dim * n_nodes, -1, dtype=np.int64)
        column[free] = np.arange(int(free.sum()))
        cols = column[(dim * e[:, :, None] + np.arange(dim)).reshape(len(e), e.shape[1] * dim)]
        keep = cols >= 0
        # The index arrays in the type scipy would convert them to at every call (after a scan of them to decide).
        index = np.int32 if max(cols.size, len(column)) <= np.iinfo(np.int32).max else np.int64
        self._keep = None if keep.all() else np.flatnonzero(keep.ravel())
        self._indices = cols[keep].astype(index)
        self._indptr = np.concatenate([[0], np.cumsum(keep.sum(axis=1))]).astype(index)
        self.shape = (len(e), int(free.sum()))

    def __call__(self, *grads):
        """The Jacobian from ``grads[c] = d r / d x_{corner c}``, each (E, dim), or from one (E, k dim) array of them
        side by side."""
        data = (np.concatenate(grads, axis=1) if len(grads) > 1 else np.ascontiguousarray(grads[0])).ravel()
        data = data if self._keep is None else data[self._keep]
        return scipy.sparse.csr_matrix((data, self._indices, self._indptr), shape=self.shape)


def signed_areas(points, triangles):
    """Signed areas of ``triangles`` over 2D ``points`` (> 0 counter-clockwise): half of
    :func:`~equimesh.mesh.triangle_orient`."""
    return 0.5 * triangle_orient(points, triangles)


def _area_gradients(points, triangles, scale):
    """``scale_t dA_t/dp_k = scale_t / 2 perp(p_{k+2} - p_{k+1})``, ``perp(x, y) = (-y, x)``, per triangle ``t`` and
    corner ``k`` (a row)."""
    grads = np.empty((len(triangles), 6))
    for t in range(len(triangles)):
        half = 0.5 * scale[t]
        for k in range(3):
            p, q = triangles[t, (k + 2) % 3], triangles[t, (k + 1) % 3]
            grads[t, 2 * k] = half * -(points[p, 1] - points[q, 1])
            grads[t, 2 * k + 1] = half * (points[p, 0] - points[q, 0])
    return grads


_area_gradients = compiled(_area_gradients)


class AreaBarrier:
    """Fold-over barrier: residuals ``w * max(0, 1 - A / (tau A0))^p`` per triangle.

    ``A`` is a triangle's signed area in a 2D coordinate array (the plane in
    eq. (1), (u, v) in the final optimisation), ``A0 > 0`` its area at the
    start and ``tau`` the ``fraction``.  The residual is zero, and the
    objective it is appended to unchanged, while the triangle keeps at least
    ``tau`` of its start area; it grows linearly as the triangle shrinks
    further.  A folded triangle (``A <= 0``) contributes at least ``w^2 / 2``
    to the cost.  With ``w^2 / 2`` above the start's cost a solver that only
    accepts cost-decreasing steps (``trf``) can therefore never end on a
    fold-over.  Triangles without positive area at the start are ignored.

    The power ``p`` is 1 (eq. (1), a kink at the floor) or 2: the residual
    is then continuously differentiable, so a Gauss-Newton model that does
    not see a triangle yet is not surprised by a cost jump when a step takes
    it just below the floor (the final optimisation, whose tiny boundary-strip
    triangles otherwise stall Levenberg-Marquardt for hundreds of steps).
    """

    def __init__(self, triangles, start, fraction, weight, free=None, power=1):
        start = np.asarray(start, dtype=float)
        tri = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
        area = signed_areas(start, tri)
        self.triangles = tri[area > 0]
        self._floor = fraction * area[area > 0]
        self._weight = float(weight)
        self._power = power
        self._assemble = ElementJacobian(self.triangles, len(start), 2, free)

    def weighted(self, weight):
        """This barrier with the weight ``w``: the triangles, start areas and Jacobian structure are shared."""
        barrier = copy.copy(self)
        barrier._weight = float(weight)
        return barrier

    def _depth(self, area):
        return np.maximum(0.0, 1.0 - area / self._floor)

    def residuals(self, points):
        return self._weight * self._depth(signed_areas(points, self.triangles)) ** self._power

    def jacobian(self, points):
        """``dA/dp_k = 1/2 perp(p_{k+2} - p_{k+1})`` for each corner, scaled where the barrier is active."""
        points = np.asarray(points, dtype=float)
        area = signed_areas(points, self.triangles)
        slope = self._power * self._depth(area) ** (self._power - 1) if self._power > 1 else 1.0
        scale = np.where(area < self._floor, -self._weight * slope / self._floor, 0.0)
        return self._assemble(_area_gradients(points, self.triangles, scale))
