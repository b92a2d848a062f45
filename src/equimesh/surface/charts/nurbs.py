"""NURBS surfaces: a chart on the span of their knot vectors (Section 4, step 1, beyond the paper).

A NURBS surface of degree ``(p, q)`` with control points ``P_ij`` (``i < n_u``,
``j < n_v``), positive weights ``w_ij`` and non-decreasing knot vectors ``U``
(``n_u + p + 1`` knots) and ``V`` (``n_v + q + 1``) is

    X^s(u, v) = A(u, v) / w(u, v),   A = sum_ij N_i,p(u) N_j,q(v) w_ij P_ij,   w = sum_ij N_i,p(u) N_j,q(v) w_ij,

on the domain ``[U[p], U[n_u]] x [V[q], V[n_v]]`` (Piegl and Tiller, *The NURBS
Book*, eq. (4.2)).  Evaluation is vectorised over all parameter pairs: the
knot span of each parameter is found by binary search, the ``p + 1`` non-zero
B-splines of every degree up to ``p`` by the Cox-de Boor recursion
(:func:`basis_functions`), their derivatives by the derivative formula
``N'_i,k = k (N_i,k-1 / (U[i+k] - U[i]) - N_i+1,k-1 / (U[i+k+1] - U[i+1]))``
applied once or twice; the derivatives of X^s follow exactly from those of
the homogeneous sums ``A`` and ``w`` by the quotient rule (Piegl and Tiller,
eq. (4.20)).
"""

import numpy as np

from ..._checks import plain_integer, real_array
from ...errors import InvalidSurfaceError
from .chart import Domain

#: Beyond the paper: the highest degree in u and in v.  Evaluating a point costs time and memory growing with the
#: square of the degree (the Cox-de Boor table of every degree up to p).  Measured by
#: ``python experiments/chart_timing.py --length 1`` (value and first partials, one knot span): 0.20 ms and 23 kB a
#: point at (25, 25), 11.7 ms and 664 kB at (399, 2); a coarse run (l = 1 over 20 x 15, 334 nodes) evaluates 85,130
#: points, 17 s at (25, 25), 17 minutes at (399, 2).  25 is also the highest degree of OpenCASCADE's B-spline
#: surfaces (docs/decisions.md, "Charts bounded by what evaluation costs").
MAX_DEGREE = 25

#: Beyond the paper: the most control points of a net.  Reading and checking a JSON net of 316 x 316 points (10.3 MB,
#: every digit) takes 2.5 s (``python experiments/chart_timing.py``); the JSON schema refuses a larger net on its shape,
#: before its points are read.
MAX_NET_POINTS = 100_000


class NurbsSurface:
    """A tensor-product NURBS surface; a :class:`~equimesh.surface.charts.chart.Chart`.

    Parameters
    ----------
    degree : (int, int)
        ``(p, q)``, each at least 1 and at most :data:`MAX_DEGREE`.
    knots_u, knots_v : array_like
        Non-decreasing, ``n_u + p + 1`` and ``n_v + q + 1`` finite knots; no
        value inside the domain repeated more than ``p`` (``q``) times (the
        surface would be discontinuous there).
    control_points : (n_u, n_v, 3) array_like
        The first axis runs over ``u``, the second over ``v``; finite; at most
        :data:`MAX_NET_POINTS` points.
    weights : (n_u, n_v) array_like, optional
        Positive and finite; all ones (a polynomial B-spline) by default.

    Raises
    ------
    InvalidSurfaceError
        naming the field and the index at fault.
    """

    def __init__(self, degree, knots_u, knots_v, control_points, weights=None):
        p, q = _degrees(degree)
        net = _array("control_points", control_points)
        if net.ndim != 3 or net.shape[2] != 3 or net.shape[0] < p + 1 or net.shape[1] < q + 1:
            raise InvalidSurfaceError(
                f"control_points must have shape (n_u, n_v, 3) with n_u >= p + 1 = {p + 1} and "
                f"n_v >= q + 1 = {q + 1}, got {net.shape}"
            )
        check_net_shape(*net.shape[:2])
        _finite("control_points", net)
        w = np.ones(net.shape[:2]) if weights is None else _array("weights", weights)
        if w.shape != net.shape[:2]:
            raise InvalidSurfaceError(f"weights must have shape {net.shape[:2]} like the control net, got {w.shape}")
        _finite("weights", w)
        bad = np.argwhere(~(w > 0))
        if len(bad):
            i, j = (int(k) for k in bad[0])
            raise InvalidSurfaceError(f"weights[{i}][{j}] must be positive, got {float(w[i, j])!r}")
        self.degree = (p, q)
        self.knots_u = _knots("knots_u", knots_u, p, net.shape[0])
        self.knots_v = _knots("knots_v", knots_v, q, net.shape[1])
        self.control_points = net
        self.weights = w
        self._homogeneous = np.concatenate([net * w[..., None], w[..., None]], axis=2)
        for a in (self.knots_u, self.knots_v, self.control_points, self.weights, self._homogeneous):
            a.setflags(write=False)
        self.domain = Domain(
            (self.knots_u[p], self.knots_u[net.shape[0]]), (self.knots_v[q], self.knots_v[net.shape[1]])
        )

    def __repr__(self):
        n_u, n_v, _ = self.control_points.shape
        return (
            f"NurbsSurface(degree={self.degree}, control net {n_u} x {n_v}, domain {self.domain.u} x {self.domain.v})"
        )

    def evaluate(self, u, v):
        """Points ``X^s(u, v)``, shape ``broadcast(u, v).shape + (3,)``."""
        return self._rational(u, v, 0)[0]

    def derivatives(self, u, v):
        """Exact first partials ``(X^s_u, X^s_v)`` (quotient rule on the homogeneous sums)."""
        return tuple(self._rational(u, v, 1)[1:3])

    def second_derivatives(self, u, v):
        """Exact second partials ``(X^s_uu, X^s_uv, X^s_vv)``."""
        return tuple(self._rational(u, v, 2)[3:6])

    def _rational(self, u, v, order):
        """``[X, X_u, X_v, X_uu, X_uv, X_vv]`` up to ``order`` (Piegl and Tiller, eq. (4.20))."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        shape = u.shape
        (p, q), h = self.degree, self._homogeneous
        iu, bu = _basis_derivatives(self.knots_u, p, u.ravel(), order)
        iv, bv = _basis_derivatives(self.knots_v, q, v.ravel(), order)
        block = h[iu[:, :, None], iv[:, None, :]]  # (K, p+1, q+1, 4)

        def homogeneous(a, b):  # d^(a+b) (A, w) / du^a dv^b
            return np.einsum("ki,kj,kijc->kc", bu[a], bv[b], block)

        a0 = homogeneous(0, 0)
        w0 = a0[:, 3:]
        x = a0[:, :3] / w0
        out = [x]
        if order >= 1:
            au, av = homogeneous(1, 0), homogeneous(0, 1)
            xu = (au[:, :3] - au[:, 3:] * x) / w0
            xv = (av[:, :3] - av[:, 3:] * x) / w0
            out += [xu, xv]
        if order >= 2:
            auu, auv, avv = homogeneous(2, 0), homogeneous(1, 1), homogeneous(0, 2)
            xuu = (auu[:, :3] - 2 * au[:, 3:] * xu - auu[:, 3:] * x) / w0
            xuv = (auv[:, :3] - au[:, 3:] * xv - av[:, 3:] * xu - auv[:, 3:] * x) / w0
            xvv = (avv[:, :3] - 2 * av[:, 3:] * xv - avv[:, 3:] * x) / w0
            out += [xuu, xuv, xvv]
        return [o.reshape(shape + (3,)) for o in out]


def basis_functions(knots, degree, span, t):
    """The non-zero B-splines of every degree ``k <= degree`` at ``t`` (Cox-de Boor).

    ``span`` (K,) holds the knot span ``knots[span] <= t < knots[span + 1]``
    of each ``t`` (K,).  Entry ``k`` of the result is a (K, k + 1) array whose
    column ``r`` is ``N_(span - k + r), k (t)``.
    """
    table = [np.ones((len(t), 1))]
    for k in range(1, degree + 1):
        i = span[:, None] - k + np.arange(k + 1)  # the functions N_i,k that do not vanish
        prev = np.pad(table[-1], ((0, 0), (1, 1)))  # N_i,k-1 at column r, N_i+1,k-1 at column r + 1
        left = _ratio(t[:, None] - knots[i], knots[i + k] - knots[i])
        right = _ratio(knots[i + k + 1] - t[:, None], knots[i + k + 1] - knots[i + 1])
        table.append(left * prev[:, :-1] + right * prev[:, 1:])
    return table


def _basis_derivatives(knots, degree, t, order):
    """Control indices (K, degree + 1) and the derivatives ``d^a N_i,degree / dt^a`` for ``a <= order``."""
    n = len(knots) - degree - 1
    last = np.flatnonzero(knots[degree:n] < knots[degree + 1 : n + 1])[-1] + degree  # last non-empty span
    span = np.clip(np.searchsorted(knots, t, side="right") - 1, degree, last)
    table = basis_functions(knots, degree, span, t)
    derivatives = []
    for a in range(order + 1):
        if a > degree:
            derivatives.append(np.zeros((len(t), degree + 1)))
            continue
        values = table[degree - a]
        for k in range(degree - a + 1, degree + 1):  # lift the derivative from degree k - 1 to k
            i = span[:, None] - k + np.arange(k + 1)
            prev = np.pad(values, ((0, 0), (1, 1)))
            values = k * (
                _ratio(prev[:, :-1], knots[i + k] - knots[i]) - _ratio(prev[:, 1:], knots[i + k + 1] - knots[i + 1])
            )
        derivatives.append(values)
    return span[:, None] - degree + np.arange(degree + 1), derivatives


def _ratio(num, den):
    """``num / den`` with ``0 / 0 = 0`` (a zero-length knot interval carries a zero B-spline)."""
    num, den = np.broadcast_arrays(num, den)
    return np.divide(num, den, out=np.zeros(num.shape), where=den != 0)


def check_net_shape(n_u, n_v):
    """Refuse a control net of ``n_u x n_v`` points above :data:`MAX_NET_POINTS` (called before the net is read)."""
    if n_u * n_v > MAX_NET_POINTS:
        raise InvalidSurfaceError(
            f"the control net has {n_u} x {n_v} = {n_u * n_v} points, more than the {MAX_NET_POINTS} that are read "
            "within seconds; refit the surface with fewer control points"
        )


def _degrees(degree):
    try:
        p, q = degree
    except (TypeError, ValueError):
        raise InvalidSurfaceError(f"degree must be a pair [p, q] of integers, got {degree!r}") from None
    for name, d in (("degree[0]", p), ("degree[1]", q)):
        if isinstance(d, bool) or not isinstance(d, (int, np.integer)):
            raise InvalidSurfaceError(f"{name} must be an integer, got {d!r}")
        if d < 1:
            raise InvalidSurfaceError(f"{name} must be at least 1, got {plain_integer(d)}")
        if d > MAX_DEGREE:
            raise InvalidSurfaceError(
                f"{name} = {plain_integer(d)} is above {MAX_DEGREE}, the highest degree supported: evaluating the "
                "surface costs time and memory growing with the square of the degree; rebuild the surface at a lower "
                "degree"
            )
    return int(p), int(q)


def _array(name, values):
    return real_array(values, name, InvalidSurfaceError)


def _finite(name, a):
    bad = np.argwhere(~np.isfinite(a))
    if len(bad):
        index = "".join(f"[{int(k)}]" for k in bad[0])
        raise InvalidSurfaceError(f"{name}{index} is not a finite number: {float(a[tuple(bad[0])])!r}")


def _knots(name, values, degree, count):
    """The knot vector ``values`` of ``count`` control points: ``count + degree + 1`` finite, non-decreasing knots."""
    knots = _array(name, values)
    want = count + degree + 1
    if knots.ndim != 1 or len(knots) != want:
        raise InvalidSurfaceError(
            f"{name} must hold {want} knots ({count} control points + degree {degree} + 1), got "
            f"{knots.shape[0] if knots.ndim else 0}"
        )
    _finite(name, knots)
    down = np.flatnonzero(np.diff(knots) < 0)
    if len(down):
        k = int(down[0])
        raise InvalidSurfaceError(
            f"{name} must be non-decreasing, but {name}[{k + 1}] = {float(knots[k + 1])!r} < {name}[{k}] = "
            f"{float(knots[k])!r}"
        )
    lo, hi = knots[degree], knots[count]
    if not lo < hi:
        raise InvalidSurfaceError(
            f"{name} spans no domain: {name}[{degree}] = {name}[{count}] = {float(lo)!r} (the domain runs from knot p "
            "to knot n)"
        )
    values, counts = np.unique(knots[(knots > lo) & (knots < hi)], return_counts=True)
    if np.any(counts > degree):
        k = int(np.argmax(counts > degree))
        raise InvalidSurfaceError(
            f"{name} repeats {float(values[k])!r} {int(counts[k])} times inside the domain, more than the degree "
            f"{degree} "
            "(the surface would be discontinuous there)"
        )
    return knots
