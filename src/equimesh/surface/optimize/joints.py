"""Sound joints: every triangle angle of the surface mesh at least a bound, kept by a barrier and a hard constraint.

A joint where two members meet at a small angle cannot be built (the
members' ends collide, the node plate grows, a weld cannot reach).  An
objective with ``sound_joints`` (``"bounded"``, ``"classes"``) keeps every triangle angle on the surface at least
:data:`~equimesh.tolerance.JOINT_ANGLE` (30 degrees), so at most
``180 - 2 * 30 = 120`` degrees too: Chew's bound for meshes whose edges lie
in [h, 2h] and whose circumradii are below h (``sin theta_min = e_min / 2R >= 1 / 2``),
which Problem 2 meets on the plane (:mod:`equimesh.planar.guarantees`).  Where
the input has a corner sharper than that bound, the angles of the triangles at
that corner node are bounded by the corner's own angle instead
(docs/decisions.md, "Sound joints").

:class:`Joints` holds the per-angle bounds and gives the two guards of
:func:`~equimesh.surface.optimize.driver.optimize_uv`: a barrier (residuals
zero while every angle is :data:`~equimesh.tolerance.JOINT_MARGIN` above its
bound, growing quadratically below that) and the test :meth:`Joints.sound`,
which the solver's acceptance keeps once an iterate meets it.
"""

import numpy as np

from ..._jit import compiled
from ...tolerance import JOINT_ANGLE, JOINT_DEFICIT, JOINT_MARGIN
from ..regularity import evaluate
from ..size import triangle_areas
from .jacobian import ElementJacobian


def surface_angles(points, triangles):
    """Interior angles in radians, (M, 3), angle k at vertex ``triangles[:, k]`` (``atan2(|u x v|, u . v)``)."""
    sines, cosines = _corner_products(
        np.ascontiguousarray(points, dtype=float), np.ascontiguousarray(triangles, dtype=np.int64).reshape(-1, 3)
    )
    return np.arctan2(sines, cosines)


def _corner_products(points, triangles):
    """``|u x v|`` and ``u . v`` at each corner (``u = p_b - p_a``, ``v = p_c - p_a`` at corner ``a``), compiled, in
    NumPy's order of operations (``np.cross``, then the sums over the coordinates in order, from 0), so the
    angles are NumPy's to the bit."""
    sines, cosines = np.empty(triangles.shape), np.empty(triangles.shape)
    for t in range(len(triangles)):
        for k in range(3):
            a, b, c = triangles[t, k], triangles[t, (k + 1) % 3], triangles[t, (k + 2) % 3]
            u0, u1, u2 = points[b, 0] - points[a, 0], points[b, 1] - points[a, 1], points[b, 2] - points[a, 2]
            v0, v1, v2 = points[c, 0] - points[a, 0], points[c, 1] - points[a, 1], points[c, 2] - points[a, 2]
            w0, w1, w2 = u1 * v2 - u2 * v1, u2 * v0 - u0 * v2, u0 * v1 - u1 * v0
            sines[t, k] = np.sqrt(w0 * w0 + w1 * w1 + w2 * w2)
            cosines[t, k] = 0.0 + u0 * v0 + u1 * v1 + u2 * v2  # from +0, as NumPy's sum: the sign of a zero
    return sines, cosines


_corner_products = compiled(_corner_products)


def _angle_gradients(points, triangles, corner, scale):
    """``scale_t d theta / d p`` of the angle at ``corner`` of each triangle ``(a, b, c)``, (M, 3, 3).

    The derivatives by the three nodes' points, in the triangle's vertex order.

    With ``e = p_b - p_a`` and ``f = p_c - p_a`` (``a`` the corner, ``b`` and
    ``c`` the next two), ``d theta / d p_b = -w_e / |e|`` where ``w_e`` is the
    unit vector in the triangle's plane perpendicular to ``e`` towards ``c``,
    likewise at ``c``, and ``d theta / d p_a`` is minus their sum.
    """
    grads = np.zeros((len(triangles), 3, 3))
    g = np.empty((3, 3))
    for t in range(len(triangles)):
        if scale[t] == 0.0:
            continue
        nodes = (triangles[t, corner], triangles[t, (corner + 1) % 3], triangles[t, (corner + 2) % 3])
        ee = ff = ef = 0.0
        for i in range(3):
            e_i = points[nodes[1], i] - points[nodes[0], i]
            f_i = points[nodes[2], i] - points[nodes[0], i]
            ee += e_i * e_i
            ff += f_i * f_i
            ef += e_i * f_i
        ne = nf = 0.0
        for i in range(3):  # g[1]: f minus its part along e (towards c), g[2]: e minus its part along f
            e_i = points[nodes[1], i] - points[nodes[0], i]
            f_i = points[nodes[2], i] - points[nodes[0], i]
            g[1, i] = f_i - e_i * (ef / ee)
            g[2, i] = e_i - f_i * (ef / ff)
            ne += g[1, i] * g[1, i]
            nf += g[2, i] * g[2, i]
        if ne == 0.0 or nf == 0.0:
            continue
        ne, nf = np.sqrt(ne) * np.sqrt(ee), np.sqrt(nf) * np.sqrt(ff)
        for i in range(3):
            g[1, i] = -g[1, i] / ne
            g[2, i] = -g[2, i] / nf
            g[0, i] = -(g[1, i] + g[2, i])
        for k in range(3):
            for i in range(3):
                grads[t, (corner + k) % 3, i] = scale[t] * g[k, i]
    return grads


_angle_gradients = compiled(_angle_gradients)


def joint_bounds(surface, uv, triangles):
    """(M, 3) lower bounds in radians: :data:`~equimesh.tolerance.JOINT_ANGLE` at every angle, except at a node whose
    angles on the surface sum to less than that at ``uv`` (a corner of the input sharper than the bound), where
    it is that sum less :data:`~equimesh.tolerance.JOINT_MARGIN`."""
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    angles = surface_angles(evaluate(surface, uv), triangles)
    total = np.bincount(triangles.ravel(), angles.ravel(), len(uv))
    return np.minimum(np.radians(JOINT_ANGLE), total - JOINT_MARGIN)[triangles]


def joint_spacing(points, triangles, l):
    """Problem 2's spacing over ``l`` that gives sound joints room: ``1 + D`` if ``D`` exceeds
    :data:`~equimesh.tolerance.JOINT_DEFICIT`, else 1 (the paper's).

    ``D`` is the area the ``triangles`` at ``points`` (the remapped mesh)
    lack, summed, over their count times ``sqrt(3) / 4 l^2``: a triangle
    whose members are at least l and whose angles are at most
    ``180 - 2 JOINT_ANGLE = 120`` degrees has at least that area
    (``a b sin C / 2`` with ``C``, its largest angle, in [60, 120]), so under
    sound joints no thin triangle can absorb what a shrunk part of the
    remapped mesh lacks; the plane meshed at ``(1 + D) l`` gives each
    triangle about ``1 + 2 D`` times the area, room for the deficit twice
    over (``sqrt(1 + D) l``, once over, left the reference dome refused at
    l = 1.24 and 0.88; docs/decisions.md, "Sound joints").
    """
    t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    area = triangle_areas(np.asarray(points, dtype=float), t)
    need = np.sqrt(3.0) / 4.0 * float(l) ** 2
    deficit = float(np.sum(np.maximum(0.0, need - area)) / (max(len(t), 1) * need))
    return 1.0 + deficit if deficit > JOINT_DEFICIT else 1.0


class Joints:
    """Lower bounds on the triangle angles of a surface mesh, in radians, and the guards that keep them.

    Parameters
    ----------
    problem : UVProblem
        The variables (``uv_of(x)``) and the surface.
    triangles : (M, 3) int array
    bounds : (M, 3) float array
        The smallest angle allowed at each corner of each triangle, in radians.
    """

    def __init__(self, problem, triangles, bounds):
        self.problem = problem
        self.triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
        self.bounds = np.asarray(bounds, dtype=float).reshape(-1, 3)
        self._elements = np.tile(self.triangles, (3, 1))  # one barrier residual per angle, corner-major
        self._assemble = ElementJacobian(self._elements, len(problem.uv), 2, problem.moving)

    def angles(self, x):
        """(M, 3) angles in radians at the variables ``x`` (once per ``x``: the barrier and the guard share them)."""
        return self.problem.at(x, "angles", lambda y: surface_angles(self.problem.points_of(y), self.triangles))

    def sound(self, x):
        """Every angle at least its bound."""
        return bool(np.all(self.angles(x) >= self.bounds))

    def violation(self, x):
        """A phrase naming how many angles are below their bounds, and the smallest."""
        angles = self.angles(x)
        low = angles < self.bounds
        return (
            f"{int(np.count_nonzero(np.any(low, axis=1)))} of {len(angles)} triangles with an angle below "
            f"{np.degrees(self.bounds[low].max(initial=0.0)):.4g} degrees (smallest {np.degrees(angles.min()):.4g})"
        )

    def barrier(self, weight):
        """``(residuals(x), jacobian(x))``: per angle ``weight * max(0, 1 - (theta - bound) / JOINT_MARGIN)^2``.

        Zero while the angle is :data:`~equimesh.tolerance.JOINT_MARGIN` above
        its bound, ``weight`` at the bound, continuously differentiable.
        """
        problem = self.problem

        def depth(x):
            return np.maximum(0.0, 1.0 - (self.angles(x) - self.bounds) / JOINT_MARGIN).T.ravel()

        def residuals(x):
            return weight * depth(x) ** 2

        def jacobian(x):
            points = problem.points_of(x)
            su, sv = problem.tangents(x)
            slope = (-2.0 * weight / JOINT_MARGIN) * depth(x)
            m = len(self.triangles)
            grads = np.concatenate(
                [_angle_gradients(points, self.triangles, k, slope[k * m : (k + 1) * m]) for k in range(3)]
            )
            # The chain rule to (u, v) for the active angles only: an inactive one's row is zero (slope 0).
            active, elements = np.flatnonzero(slope), self._elements
            uv_grads = np.zeros((len(elements), 3, 2))
            for d, tangent in enumerate((su, sv)):
                uv_grads[active, :, d] = np.einsum("jcd,jcd->jc", grads[active], tangent[elements[active]])
            jac = problem.chain(self._assemble(uv_grads.reshape(len(elements), 6)), x)
            return jac + problem.offset_columns(elements, grads, x) if len(problem.offset_nodes) else jac

        return residuals, jacobian
