"""The tensor-product Bezier surface, the paper's example chart on [0, 1]^2 (Section 4, step 1).

:class:`BezierSurface` is a :class:`~equimesh.surface.chart.Chart`: its domain
is the paper's parameter square and it gives X^s with its first and second
partial derivatives, all vectorised.
"""

import math

import numpy as np

from ..errors import InvalidSurfaceError
from .chart import UNIT


#: Beyond the paper: the highest degree of a Bezier net in u or in v.  The
#: Bernstein basis uses the binomial coefficients C(n, i) as floats, and
#: C(n, n / 2) exceeds the largest float from n = 1030 on (a 3000-row net
#: ended in an OverflowError).  Test: tests/test_hardening_surface.py.
MAX_DEGREE = 1000


def bernstein(degree, t):
    """Bernstein basis polynomials ``B_i^degree(t)``, shape ``t.shape + (degree + 1,)``.

    ``B_i^n(t) = C(n, i) t^i (1 - t)^(n - i)``; ``0**0 == 1`` so the basis is
    exact at ``t = 0`` and ``t = 1``.
    """
    t = np.asarray(t, dtype=float)[..., None]
    i = np.arange(degree + 1)
    binom = np.array([math.comb(degree, k) for k in i], dtype=float)
    return binom * t**i * (1.0 - t) ** (degree - i)


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
    """``sum_ij B_i(u) B_j(v) net_ij`` for a net of shape (a, b, 3), vectorised over ``u, v``."""
    u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
    a, b, _ = net.shape
    bu = bernstein(a - 1, u)  # (..., a)
    bv = bernstein(b - 1, v)  # (..., b)
    rows = (bu @ net.reshape(a, b * 3)).reshape(u.shape + (b, 3))  # sum over i first
    return np.einsum("...j,...jk->...k", bv, rows)


def _validate_net(control_points):
    try:
        p = np.array(control_points, dtype=float)
    except (TypeError, ValueError):
        raise InvalidSurfaceError(
            "control points must form an (m+1, n+1, 3) array of numbers with equal row lengths"
        ) from None
    if p.ndim != 3 or p.shape[2] != 3:
        raise InvalidSurfaceError(f"control net must have shape (m+1, n+1, 3), got {p.shape}")
    if p.shape[0] < 2 or p.shape[1] < 2:
        raise InvalidSurfaceError(f"control net needs at least 2 x 2 points, got {p.shape[0]} x {p.shape[1]}")
    if max(p.shape[:2]) > MAX_DEGREE + 1:
        raise InvalidSurfaceError(
            f"control net has {p.shape[0]} x {p.shape[1]} points, degree {p.shape[0] - 1} x {p.shape[1] - 1}; "
            f"at most degree {MAX_DEGREE} in u and in v is supported"
        )
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
