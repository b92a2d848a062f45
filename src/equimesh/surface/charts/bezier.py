"""The tensor-product Bezier surface, the paper's example chart on [0, 1]^2 (Section 4, step 1).

:class:`BezierSurface` is a :class:`~equimesh.surface.charts.chart.Chart`: its domain
is the paper's parameter square and it gives X^s with its first and second
partial derivatives, all vectorised.
"""

import numpy as np

from ..._checks import real_array
from ..._jit import compiled
from ...errors import InvalidSurfaceError
from .chart import UNIT

#: Beyond the paper: the highest degree of a Bezier net in u and in v, by what evaluation costs.  A point costs about
#: ``(m + 1)^2 + (n + 1)^2 + (m + 1)(n + 1)`` products (the recurrence of :func:`_basis`, then the tensor sum).
#: Measured by ``python experiments/chart_timing.py`` (value and first partials): 0.15 ms a point at (100, 100), below
#: a NURBS surface at its own highest degree (25, 25) in the same run, 0.31 ms at (150, 150), above it, and 14.9 ms at
#: (1000, 1000), where a coarse run would spend 21 minutes evaluating (docs/decisions.md, "Charts
#: bounded by what evaluation costs").
MAX_DEGREE = 100


def bernstein(degree, t):
    """Bernstein basis polynomials ``B_i^degree(t)``, shape ``t.shape + (degree + 1,)``.

    ``B_i^n(t) = C(n, i) t^i (1 - t)^(n - i)``, by :func:`_basis`: exact at
    ``t = 0`` and ``t = 1``, and no binomial coefficient (which overflows a
    float from n = 1030 on) is formed.
    """
    t = np.asarray(t, dtype=float)
    flat = t.ravel()
    out = np.empty((len(flat), degree + 1))
    for k in range(len(flat)):
        _basis(degree, flat[k], out[k])
    return out.reshape(t.shape + (degree + 1,))


def _basis(degree, t, out):
    """``out[i] = B_i^degree(t)`` for ``i <= degree``, by the triangular recurrence ``B_i^j = (1 - t) B_i^(j-1) + t
    B_(i-1)^(j-1)``.

    Piegl and Tiller's ``AllBernstein`` (The NURBS Book, A1.3): only products
    and sums of numbers in [0, 1] (for t in [0, 1]), so no overflow at any
    degree, and at ``t = 0`` or ``1`` every term but one is an exact zero.
    """
    out[0] = 1.0
    s = 1.0 - t
    for j in range(1, degree + 1):
        saved = 0.0
        for i in range(j):
            temp = out[i]
            out[i] = saved + s * temp
            saved = t * temp
        out[j] = saved


_basis = compiled(_basis)


class BezierSurface:
    """Tensor-product Bezier surface ``X^s(u, v) = sum_ij B_i^m(u) B_j^n(v) P_ij``.

    Parameters
    ----------
    control_points : (m + 1, n + 1, 3) array_like
        The control net; the first axis runs over ``u`` (rows), the second over
        ``v`` (columns).  Degrees ``m, n >= 1``; every coordinate finite.

    Raises
    ------
    InvalidSurfaceError
        If the net has the wrong shape, fewer than 2 x 2 points, a degree
        above :data:`MAX_DEGREE`, or a non-finite coordinate.
    """

    #: The parameter square [0, 1]^2 of the paper.
    domain = UNIT

    def __init__(self, control_points):
        self.control_points = _validate_net(control_points)
        self.control_points.setflags(write=False)

    @property
    def degree(self):
        """``(m, n)``: the degrees in ``u`` and in ``v``."""
        rows, cols, _ = self.control_points.shape
        return rows - 1, cols - 1

    def __repr__(self):
        m, n = self.degree
        return f"BezierSurface(degree=({m}, {n}))"

    def evaluate(self, u, v):
        """Points ``X^s(u, v)``, shape ``broadcast(u, v).shape + (3,)`` (vectorised Bernstein sum)."""
        return _tensor_sum(self.control_points, u, v)

    def derivatives(self, u, v):
        """Analytic partials ``(X^s_u, X^s_v)``.

        ``X^s_u = m sum_ij B_i^{m-1}(u) B_j^n(v) (P_{i+1,j} - P_ij)`` and the
        same in ``v``: a Bezier surface of the difference net.
        """
        m, n = self.degree
        p = self.control_points
        su = _tensor_sum(m * np.diff(p, axis=0), u, v)
        sv = _tensor_sum(n * np.diff(p, axis=1), u, v)
        return su, sv

    def second_derivatives(self, u, v):
        """Analytic second partials ``(X^s_uu, X^s_uv, X^s_vv)``: Bezier surfaces of the twice-differenced net.

        A direction of degree 1 has a zero second derivative in it.
        """
        m, n = self.degree
        p = self.control_points
        shape = np.broadcast_shapes(np.shape(u), np.shape(v)) + (3,)
        suv = _tensor_sum(m * n * np.diff(np.diff(p, axis=0), axis=1), u, v)
        suu = _tensor_sum(m * (m - 1) * np.diff(p, 2, axis=0), u, v) if m > 1 else np.zeros(shape)
        svv = _tensor_sum(n * (n - 1) * np.diff(p, 2, axis=1), u, v) if n > 1 else np.zeros(shape)
        return suu, suv, svv


def _tensor_sum(net, u, v):
    """``sum_ij B_i(u) B_j(v) net_ij`` for a net of shape (a, b, 3), over ``broadcast(u, v)`` (a compiled loop per
    point)."""
    u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
    out = _tensor_sum_points(np.ascontiguousarray(net, dtype=float), u.ravel(), v.ravel())
    return out.reshape(u.shape + (3,))


def _tensor_sum_points(net, u, v):
    """``out[k] = sum_ij B_i(u_k) B_j(v_k) net_ij`` for 1-D ``u, v``: the basis of each point (:func:`_basis`), then the
    double sum."""
    a, b = net.shape[0], net.shape[1]
    out = np.zeros((len(u), 3))
    bu, bv = np.empty(a), np.empty(b)
    for k in range(len(u)):
        _basis(a - 1, u[k], bu)
        _basis(b - 1, v[k], bv)
        for i in range(a):
            for j in range(b):
                w = bu[i] * bv[j]
                for c in range(3):
                    out[k, c] += w * net[i, j, c]
    return out


_tensor_sum_points = compiled(_tensor_sum_points)


def check_net_shape(rows, cols):
    """Refuse a net of ``rows x cols`` points whose degree is above :data:`MAX_DEGREE` (called before the net is
    read)."""
    if max(rows, cols) > MAX_DEGREE + 1:
        raise InvalidSurfaceError(
            f"control net has {rows} x {cols} points, degree {rows - 1} x {cols - 1}; at most degree {MAX_DEGREE} in "
            "u and in v is supported, as evaluating the surface costs time growing with the square of the degree"
        )


def _validate_net(control_points):
    p = real_array(control_points, "control points (an (m+1, n+1, 3) net with equal row lengths)", InvalidSurfaceError)
    if p.ndim != 3 or p.shape[2] != 3:
        raise InvalidSurfaceError(f"control net must have shape (m+1, n+1, 3), got {p.shape}")
    if p.shape[0] < 2 or p.shape[1] < 2:
        raise InvalidSurfaceError(f"control net needs at least 2 x 2 points, got {p.shape[0]} x {p.shape[1]}")
    check_net_shape(*p.shape[:2])
    bad = np.argwhere(~np.isfinite(p))
    if len(bad):
        i, j, k = (int(x) for x in bad[0])
        raise InvalidSurfaceError(f"control point [{i}][{j}] has a non-finite coordinate {p[i, j, k]!r}")
    return p


def de_casteljau(control_points, u, v):
    """Reference evaluator: repeated linear interpolation of the control net.

    Scalar ``u, v``; reads like the textbook construction and serves as the
    oracle for :meth:`BezierSurface.evaluate` in the tests.
    """
    p = np.array(control_points, dtype=float)
    while p.shape[0] > 1:  # collapse rows (u)
        p = (1.0 - u) * p[:-1] + u * p[1:]
    q = p[0]
    while q.shape[0] > 1:  # collapse the remaining row (v)
        q = (1.0 - v) * q[:-1] + v * q[1:]
    return q[0]
