"""A sparse, bounded Levenberg-Marquardt solver for the (u, v) optimisation of Section 4.

The paper's final step ("the deviation of the edge lengths ... is minimized by
considering (u_i, v_i) of inner nodes as variables") is a nonlinear least-squares
problem ``min |r(x)|^2 / 2`` whose Jacobian has a few entries per row (one
residual per member or triangle).  :func:`least_squares` solves it by
Levenberg-Marquardt with a sparse direct factorisation of the damped normal
equations, so that one iteration costs about as much as one sparse LU of a
mesh-Laplacian-like matrix (near-linear in the node count on surface meshes)
instead of an inner iterative solve:

* step: ``(J_F^T J_F + lambda D_F) s_F = -g_F`` over the free variables ``F``,
  ``D = diag(J^T J)`` (Marquardt's scaling, floored at :data:`~equimesh.tolerance.LM_DIAGONAL_FLOOR`
  of its largest entry so that a variable no residual sees stays regular),
  factorised by SuperLU in symmetric mode, in a minimum-degree order of the
  normal matrix's structure computed once (:class:`_Ordering`: the
  structure is the mesh's at every iteration);
* a rejected step is retried with a larger ``lambda`` (a new factorisation);
* bounds by projection: a variable on a bound whose gradient points outwards is
  held there for the step (it leaves ``F``), and the step is clipped to the box;
* acceptance: the gain ratio ``rho = actual / predicted reduction`` of the
  projected step; ``rho > 0`` and ``accept(x_new)`` (a caller's predicate, e.g.
  "no triangle folds over", "every member stays in [l, 2l]") are required;
  ``lambda`` follows Nielsen's rule;
* convergence, not an evaluation cap: the infinity norm of the projected
  gradient below ``gtol``, or a step below ``xtol (xtol + |x|)``, or actual
  and predicted relative reductions below ``ftol``.  ``max_iterations`` is
  only a guard against a bug and is reported when it is hit.

Deterministic: no randomness, and SuperLU runs single-threaded with a fixed
ordering, so the same input gives the same bits.
"""

from dataclasses import dataclass

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

from ..tolerance import (
    LM_DIAGONAL_FLOOR, LM_INITIAL_DAMPING,
)


@dataclass(frozen=True)
class Solution:
    """Result of :func:`least_squares`: the point, its cost, why the solver stopped and its last damping ``lambda``."""

    x: np.ndarray
    cost: float
    iterations: int
    evaluations: int
    converged: bool
    message: str
    damping: float


def least_squares(residuals, jacobian, x0, lower, upper, *, accept=None, gtol=1e-10, xtol=1e-10, ftol=1e-12,
                  max_iterations=500, damping=LM_INITIAL_DAMPING):
    """Minimise ``|residuals(x)|^2 / 2`` over the box ``[lower, upper]`` (see the module docstring).

    ``x0`` must lie in the box and satisfy ``accept`` (if given); every
    iterate, and so the result, then does too.  ``damping`` is the initial
    ``lambda``; a continuation passes the previous solve's final
    :attr:`Solution.damping` so that it does not pay again for rejected steps.
    """
    x = np.clip(np.asarray(x0, dtype=float), lower, upper)
    r = residuals(x)
    cost = 0.5 * float(r @ r)
    evaluations, nu, lam = 1, 2.0, damping
    ordering = _Ordering()
    for iteration in range(max_iterations):
        jac = jacobian(x)
        g = jac.T @ r
        projected = x - np.clip(x - g, lower, upper)
        if np.all(np.abs(projected) <= gtol):
            return Solution(x, cost, iteration, evaluations, True, "projected gradient below gtol", lam)
        held = ((x <= lower) & (g > 0)) | ((x >= upper) & (g < 0))
        free = np.flatnonzero(~held)
        order = ordering.of(jac, free)
        permuted = jac[:, free[order]]
        normal = (permuted.T @ permuted).tocsc()
        diag = normal.diagonal()
        diag = np.maximum(diag, LM_DIAGONAL_FLOOR * max(float(diag.max()), 1.0))
        rhs = -g[free[order]]
        retried = False
        while True:
            step = np.zeros_like(x)
            step[free[order]] = _factorise((normal + scipy.sparse.diags(lam * diag)).tocsc(), "NATURAL").solve(rhs)
            x_new = np.clip(x + step, lower, upper)
            s = x_new - x
            js = jac @ s
            predicted = -(float(g @ s) + 0.5 * float(js @ js))
            r_new = residuals(x_new)
            evaluations += 1
            cost_new = 0.5 * float(r_new @ r_new)
            actual = cost - cost_new
            small_step = np.linalg.norm(s) <= xtol * (xtol + np.linalg.norm(x))
            if predicted > 0 and actual > 0 and (accept is None or accept(x_new)):
                rho = actual / predicted
                lam *= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
                nu = 2.0
                x, r, old, cost = x_new, r_new, cost, cost_new
                if small_step and not retried:
                    return Solution(x, cost, iteration + 1, evaluations, True, "step below xtol", lam)
                if actual <= ftol * old and predicted <= ftol * old and not retried:
                    return Solution(x, cost, iteration + 1, evaluations, True, "relative reduction below ftol", lam)
                break
            if small_step and lam >= 1.0 / LM_DIAGONAL_FLOOR:
                return Solution(x, cost, iteration + 1, evaluations, True, "no further reduction: step below xtol", lam)
            lam *= nu
            nu *= 2.0
            retried = True
    return Solution(x, cost, max_iterations, evaluations, False, f"stopped after {max_iterations} iterations", lam)


class _Ordering:
    """A fill-reducing order of the free variables, computed once and reused.

    The normal matrix ``J_F^T J_F`` has the sparsity of the mesh (two
    variables per node, coupled through the residuals' elements), the same
    at every iteration up to entries that happen to vanish (an inactive
    barrier row), so one minimum-degree ordering of its structure (SuperLU's
    ``MMD_AT_PLUS_A``) serves every iteration; it is recomputed only when
    the set of free variables changes (a bound becomes held or released).
    Measured on the reference dome at 101,654 members: the ordering was
    about a third of each factorisation's time.
    """

    def __init__(self):
        self._free, self._order = None, None

    def of(self, jac, free):
        """Positions of ``free`` in elimination order, for the Jacobian ``jac`` (structure only)."""
        if self._free is None or not np.array_equal(free, self._free):
            structure = abs(jac[:, free]).tocsc()
            structure.data[:] = 1.0
            pattern = (structure.T @ structure + scipy.sparse.identity(len(free))).tocsc()
            self._free, self._order = free, np.argsort(_factorise(pattern, "MMD_AT_PLUS_A").perm_c)
        return self._order


def _factorise(matrix, ordering):
    """SuperLU of a symmetric positive definite CSC ``matrix`` in symmetric mode (diagonal pivots), ``ordering`` its ``permc_spec``."""
    return scipy.sparse.linalg.splu(matrix, permc_spec=ordering, diag_pivot_thresh=0.0, options={"SymmetricMode": True})
