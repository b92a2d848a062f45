"""The members of a final optimisation: their lengths on the surface, the band [l, 2l], and weighted residuals.

:func:`edge_length_terms` gives the surface lengths of a set of edges and their
sparse Jacobian over the variables of a :class:`~equimesh.surface.optimize.problem.UVProblem`;
:class:`Members` holds every member's length over l, the band [l, 2l] and the
weighted residuals towards goals that the rounds of
:func:`~equimesh.surface.optimize.objectives.bounded_stages` and
:func:`~equimesh.surface.optimize.objectives.classes_stages` solve.
"""

import numpy as np
import scipy.sparse

from ..._jit import compiled
from ...errors import number
from ...mesh import edge_lengths
from ...tolerance import BOUNDED_OFFSET, BOUNDED_PENALTY, BOUNDED_PULL, REACH_LENGTH, REACH_SHARE, at_least, at_most
from .jacobian import ElementJacobian


def edge_length_terms(problem, edges):
    """Surface lengths of ``edges`` and their sparse Jacobian over the variables.

    For an edge ``(a, b)`` with ``d = p_b - p_a`` and ``L = |d|``,
    the chain rule gives ``dL/du_b = d . p_u(b) / L``,
    ``dL/dv_b = d . p_v(b) / L`` and the negatives at ``a`` (``p_u = X^s_u``
    on the surface, :meth:`~.problem.UVProblem.tangents` off it), and with a
    surface tolerance ``dL/dh_b = d . N_b / L``.

    Returns
    -------
    lengths : callable ``x -> (K,)``
    jacobian : callable ``x -> (lengths (K,), csr_matrix (K, n_variables))``
    """
    e = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    assemble = ElementJacobian(e, len(problem.uv), 2, problem.moving)

    last = {}

    def points(x):
        """The nodes' points for ``x``; the last is kept: the solver evaluates the Jacobian where it last evaluated
        the residuals, and an objective's stages measure the lengths where the solve ended."""
        if "x" not in last or not np.array_equal(last["x"], x):
            last.clear()
            last.update(x=np.array(x), points=problem.points_of(x))
        return last["points"]

    def lengths(x):
        p = points(x)
        if "lengths" not in last:
            last["lengths"] = edge_lengths(p, e)
        return last["lengths"]

    def jacobian(x):
        p = points(x)
        jac = problem.chain(assemble(_length_gradients(p, *problem.tangents(x), e)), x)
        if len(problem.offset_nodes):
            d = (p[e[:, 1]] - p[e[:, 0]]) / np.maximum(lengths(x), np.finfo(np.float64).tiny)[:, None]
            jac = jac + problem.offset_columns(e, np.stack([-d, d], axis=1), x)
        return lengths(x), jac

    return lengths, jacobian


def _length_gradients(points, su, sv, edges):
    """Per edge ``(a, b)``, ``L = |d|`` with ``d = X^s(u_b) - X^s(u_a)``: ``dL/d(u_a, v_a, u_b, v_b)`` (a row).

    ``dL/du_b = d . X^s_u(u_b) / L``, ``dL/dv_b = d . X^s_v(u_b) / L``, minus
    the same at ``a`` (:func:`edge_length_terms`); a compiled loop over the
    edges (a zero-length edge has ``d = 0``, so zero gradients).
    """
    grads = np.empty((len(edges), 4))
    for k in range(len(edges)):
        a, b = edges[k, 0], edges[k, 1]
        d0, d1, d2 = points[b, 0] - points[a, 0], points[b, 1] - points[a, 1], points[b, 2] - points[a, 2]
        scale = max(np.sqrt(d0 * d0 + d1 * d1 + d2 * d2), np.finfo(np.float64).tiny)
        u0, u1, u2 = d0 / scale, d1 / scale, d2 / scale
        grads[k, 0] = -(u0 * su[a, 0] + u1 * su[a, 1] + u2 * su[a, 2])
        grads[k, 1] = -(u0 * sv[a, 0] + u1 * sv[a, 1] + u2 * sv[a, 2])
        grads[k, 2] = u0 * su[b, 0] + u1 * su[b, 1] + u2 * su[b, 2]
        grads[k, 3] = u0 * sv[b, 0] + u1 * sv[b, 1] + u2 * sv[b, 2]
    return grads


_length_gradients = compiled(_length_gradients)


class Members:
    """Every member's length over l, the band [l, 2l] and weighted residuals towards goals (the rounds of
    :func:`bounded_stages` and :func:`classes_stages`).

    ``target = 1 + BOUNDED_OFFSET`` and ``high = 2 - BOUNDED_OFFSET`` (in
    units of l) are the ends a member outside them is pulled to.
    """

    target = 1.0 + BOUNDED_OFFSET
    high = 2.0 - BOUNDED_OFFSET

    def __init__(self, problem):
        self.l = problem.length
        self.lengths, self.length_jacobian = edge_length_terms(problem, problem.edges)

    def ratio(self, x):
        return self.lengths(x) / self.l

    @staticmethod
    def inside(ratio):
        """Every member in [l, 2l], up to ``REL_TOL`` (the pipeline's check, :func:`~equimesh.tolerance.at_least`)."""
        return bool(np.all(at_least(ratio, 1.0) & at_most(ratio, 2.0)))

    def feasible(self, x):
        return self.inside(self.ratio(x))

    def violation(self, x):
        """A phrase naming the members outside [l, 2l]."""
        ratio = self.ratio(x)
        out = int(np.count_nonzero(~(at_least(ratio, 1.0) & at_most(ratio, 2.0))))
        return (
            f"{out} of {len(ratio)} members outside [l, 2l] "
            f"(lengths from {number(ratio.min())} l to {number(ratio.max())} l)"
        )

    def reach(self, x):
        """A phrase saying how far the members are from [l, 2l] at ``x`` (:func:`out_of_reach`)."""
        ratio = self.ratio(x)
        return (
            f"{number(100.0 * short_share(ratio))} % of its {len(ratio)} members shorter than "
            f"{number(REACH_LENGTH)} l on the surface (the flattening stretched it), "
            f"lengths from {number(ratio.min())} l to {number(ratio.max())} l"
        )

    def band_penalty(self):
        """The smoothed one-sided penalty of slope ``BOUNDED_PENALTY`` below ``1 + BOUNDED_OFFSET / 2`` and above
        ``high`` (``extra`` of :meth:`weighted`), pressing every member into [l, 2l]: ``ratio -> (values, slopes)``."""
        low, high, smooth = 1.0 + 0.5 * BOUNDED_OFFSET, self.high, 0.25 * BOUNDED_OFFSET

        def penalty(ratio):
            """Smoothed hinge ``psi(h)`` of the depth ``h`` outside ``[low, high]`` and its derivative in ``ratio``."""
            depth = np.maximum(0.0, low - ratio) + np.maximum(0.0, ratio - high)
            side = np.where(ratio > high, 1.0, -1.0)
            inner = depth < smooth
            value = np.where(inner, depth**2 / (2 * smooth), depth - smooth / 2)
            slope = np.where(inner, depth / smooth, 1.0) * side
            return BOUNDED_PENALTY * value, BOUNDED_PENALTY * slope

        return penalty

    def pulled(self, ratio, weight, goal):
        """``(weight, goal)`` per member: a member outside ``[target, high]`` pulled to the nearer end with the weight
        ``BOUNDED_PULL``, the others to ``goal`` with ``weight``."""
        end = np.clip(ratio, self.target, self.high)
        outside = end != ratio
        return np.where(outside, BOUNDED_PULL, weight), np.where(outside, end, goal)

    def weighted(self, weight, goal, extra=None):
        """Residuals ``weight (L / l - goal)`` (and ``extra(ratio)``: values, slopes) with their Jacobian."""
        l, lengths, length_jacobian = self.l, self.lengths, self.length_jacobian

        def residuals(x):
            ratio = lengths(x) / l
            r = weight * (ratio - goal)
            return r if extra is None else np.concatenate([r, extra(ratio)[0]])

        def jacobian(x):
            length, jac = length_jacobian(x)
            jac = scipy.sparse.csr_matrix((jac.data * (1.0 / l), jac.indices, jac.indptr), shape=jac.shape)  # jac / l
            rows = scale_rows(weight, jac)
            return (
                rows
                if extra is None
                else scipy.sparse.vstack([rows, scale_rows(extra(length / l)[1], jac)], format="csr")
            )

        return residuals, jacobian


def cauchy(deviation, scale):
    """The Cauchy weight ``1 / sqrt(1 + (d / s)^2)`` of each deviation ``d``: majorise-minimise for the loss
    ``log(1 + (d / s)^2)``."""
    return 1.0 / np.sqrt(1.0 + (deviation / scale) ** 2)


def scale_rows(scale, jac):
    """``diag(scale) @ jac`` for a CSR ``jac``, on its structure (a product ``diags @ jac`` drops the entries that
    become zero: a new structure, so a new analysis of the normal equations, whenever a weight or slope is 0)."""
    data = np.repeat(scale, np.diff(jac.indptr)) * jac.data
    return scipy.sparse.csr_matrix((data, jac.indices, jac.indptr), shape=jac.shape)


def short_share(ratio):
    """The share of members shorter than ``REACH_LENGTH`` l (``ratio = L / l``)."""
    return float(np.mean(ratio < REACH_LENGTH)) if len(ratio) else 0.0


def out_of_reach(ratio):
    """Whether members at ``ratio = L / l`` are too far from [l, 2l] for the optimisation to bring them in:
    more than ``REACH_SHARE`` of them shorter than ``REACH_LENGTH`` l (a measured bound, docs/decisions.md,
    "A work bound for the optimisation")."""
    return short_share(ratio) > REACH_SHARE
