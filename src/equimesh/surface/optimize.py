"""Final optimisation of the inner nodes' parameters (Section 4, last paragraph).

"Finally, the deviation of the edge lengths in G1 from the target value is
minimized by considering (u_i, v_i) of inner nodes as variables."  The
variables are the (u_i, v_i) of the free (inner) nodes, kept in the chart's
domain (:func:`~equimesh.surface.chart.domain_of`, [0, 1]^2 for the paper) by
bounds; boundary nodes stay where remapping put them.  The problem is solved
with :func:`scipy.optimize.least_squares` (trust region reflective with
bounds, LSMR sub-problems) and an analytic sparse Jacobian obtained by the
chain rule through the surface's first derivatives.

The seam.  What is minimised is looked up by name in :data:`OBJECTIVES`: a
builder ``builder(problem: UVProblem) -> Objective`` returning the residual
and sparse Jacobian functions of the variable vector.  ``"paper"`` is the
paper's objective; further objectives (e.g. keeping every member in [l, 2l]
with as many as possible exactly l) are added beside it with the same
signature, reusing :func:`edge_length_terms`.

Fold-over.  Lengths do not see orientation, and the G1 edges do not see the
triangles between the lattice and the boundary at all: minimising the G1
deviation alone lets the lattice slide over the fixed boundary nodes and flips
boundary-strip triangles (observed on doubly curved patches).  Two guards:

* a barrier (:class:`~equimesh.surface._jacobian.AreaBarrier`), zero unless a triangle's (u, v) area
  falls below ``area_floor`` (default 0.5) of its start area, heavy enough
  that a folded triangle costs more than the whole start, so that ``trf``,
  which only accepts cost-decreasing steps, can never end on a fold-over;
  while no triangle is that squeezed the objective is exactly the paper's;
* a check after solving: every triangle counter-clockwise in (u, v) at the
  start must still be; otherwise (only possible with the barrier disabled)
  the step is shortened (``x0 + t (x* - x0)``, ``t`` halved) until no
  triangle flips and the cost is no larger than at the start (``t = 0``, the
  start itself, always qualifies).  The fraction ``t`` kept is reported.
"""

from dataclasses import dataclass, field
from typing import Callable

import numpy as np
import scipy.optimize
import scipy.sparse

from ._jacobian import AreaBarrier, ElementJacobian, signed_areas
from ..errors import EquimeshError
from ..mesh import G1
from .chart import domain_of
from .regularity import derivatives, evaluate


@dataclass(frozen=True)
class UVProblem:
    """The data every objective builder sees.

    Attributes
    ----------
    surface : Chart
    uv : (N, 2) float array
        Start parameters of all nodes (after remapping, step 4).
    edges : (E, 2) int array
    edge_groups : (E,) int array
        :data:`~equimesh.mesh.G1` or :data:`~equimesh.mesh.OTHER` per edge.
    length : float
        The target length l.
    free : (N,) bool array
        True for the variable (inner) nodes.
    """

    surface: object
    uv: np.ndarray
    edges: np.ndarray
    edge_groups: np.ndarray
    length: float
    free: np.ndarray

    @property
    def variables(self):
        """(2N,) bool mask of the variable entries of ``uv.ravel()`` (u and v of free nodes)."""
        return np.repeat(self.free, 2)

    @property
    def x0(self):
        """The start as a variable vector ``(u_0, v_0, u_1, v_1, ...)`` over free nodes."""
        return self.uv.ravel()[self.variables]

    def uv_of(self, x):
        """All nodes' (u, v) with the free ones taken from the variable vector ``x``."""
        full = self.uv.ravel().copy()
        full[self.variables] = x
        return full.reshape(-1, 2)


@dataclass(frozen=True)
class Objective:
    """Residuals ``r(x)`` and their sparse Jacobian ``J(x)`` over the variable vector; cost is ``|r|^2 / 2``."""

    residuals: Callable[[np.ndarray], np.ndarray]
    jacobian: Callable[[np.ndarray], object]
    description: str = ""


def edge_length_terms(problem, edges):
    """Surface lengths of ``edges`` and their sparse Jacobian over the variables.

    For an edge ``(a, b)`` with ``d = X^s(u_b) - X^s(u_a)`` and ``L = |d|``,
    the chain rule gives ``dL/du_b = d . X^s_u(u_b) / L``,
    ``dL/dv_b = d . X^s_v(u_b) / L`` and the negatives at ``a``.

    Returns
    -------
    lengths : callable ``x -> (K,)``
    jacobian : callable ``x -> (lengths (K,), csr_matrix (K, n_variables))``
    """
    e = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    assemble = ElementJacobian(e, len(problem.uv), 2, problem.variables)
    surface = problem.surface

    def lengths(x):
        p = evaluate(surface, problem.uv_of(x))
        return np.linalg.norm(p[e[:, 1]] - p[e[:, 0]], axis=1)

    def jacobian(x):
        uv = problem.uv_of(x)
        p = evaluate(surface, uv)
        su, sv = derivatives(surface, uv)
        d = p[e[:, 1]] - p[e[:, 0]]
        length = np.linalg.norm(d, axis=1)
        unit = d / np.maximum(length, np.finfo(float).tiny)[:, None]
        a, b = e[:, 0], e[:, 1]
        grad_b = np.column_stack([np.sum(unit * su[b], axis=1), np.sum(unit * sv[b], axis=1)])
        grad_a = -np.column_stack([np.sum(unit * su[a], axis=1), np.sum(unit * sv[a], axis=1)])
        return length, assemble(grad_a, grad_b)

    return lengths, jacobian


def paper_objective(problem):
    """The paper's objective: ``r_e = (L_e - l) / l`` for every G1 edge ``e``."""
    l = problem.length
    g1 = problem.edges[problem.edge_groups == G1]
    lengths, jacobian = edge_length_terms(problem, g1)

    def residuals(x):
        return (lengths(x) - l) / l

    def jac(x):
        return jacobian(x)[1] / l

    return Objective(residuals, jac, "relative deviation (L - l) / l of the G1 edges")


#: Objective builders by name, each ``builder(problem: UVProblem) -> Objective``.
OBJECTIVES = {"paper": paper_objective}


@dataclass(frozen=True)
class UVOptimization:
    """Result of :func:`optimize_uv`.

    Attributes
    ----------
    uv : (N, 2) float array
        Optimised parameters; fixed nodes bit-identical to the start.
    cost_before, cost_after : float
        ``|r|^2 / 2`` of the objective at the start and at ``uv``.
    nfev, njev : int
        Residual and Jacobian evaluations of the solver.
    status : int, message : str
        From :func:`scipy.optimize.least_squares`.
    step_fraction : float
        ``t`` of the fold-over guard: 1.0 when the solver's result was kept.
    objective : str
    """

    uv: np.ndarray
    cost_before: float
    cost_after: float
    nfev: int
    njev: int
    status: int
    message: str
    step_fraction: float
    objective: str
    info: dict = field(default_factory=dict, compare=False)


def optimize_uv(
    surface,
    uv,
    edges,
    edge_groups,
    length,
    *,
    fixed,
    triangles=None,
    objective="paper",
    area_floor=0.5,
    ftol=1e-10,
    xtol=1e-10,
    gtol=1e-10,
    max_nfev=200,
):
    """Optimise the (u, v) of the free nodes (Section 4, final step).

    Parameters
    ----------
    surface : Chart
    uv : (N, 2) array_like
        Start parameters of every node, in the surface's domain (step 4's output).
    edges : (E, 2) int array_like
    edge_groups : (E,) int array_like
        G1 / OTHER label per edge.
    length : float
        The target length l.
    fixed : array_like of int or (N,) bool
        Nodes that stay put (the boundary nodes).
    triangles : (M, 3) int array_like, optional
        For the fold-over guard (recommended): without them neither the
        barrier nor the backtracking is applied.
    area_floor : float
        Fold-over barrier threshold ``tau`` in [0, 1): a triangle is penalised
        once its (u, v) area falls below ``tau`` times its start area (see
        :class:`~equimesh.surface._jacobian.AreaBarrier`).  0 disables the barrier (the backtracking
        guard still applies).  The default 0.5 keeps the strip between the
        lattice and the boundary well shaped at a negligible cost in the G1
        deviation.
    objective : str
        Key of :data:`OBJECTIVES`.
    ftol, xtol, gtol, max_nfev
        Passed to :func:`scipy.optimize.least_squares`.

    Returns
    -------
    UVOptimization
    """
    try:
        builder = OBJECTIVES[objective]
    except (KeyError, TypeError):
        raise EquimeshError(f"unknown objective {objective!r}; choose from {sorted(OBJECTIVES)}") from None
    domain = domain_of(surface)
    uv = domain.clip(np.array(uv, dtype=float).reshape(-1, 2))
    free = np.ones(len(uv), dtype=bool)
    fixed = np.asarray(fixed)
    free[fixed if fixed.dtype != bool else np.flatnonzero(fixed)] = False
    problem = UVProblem(surface, uv, np.asarray(edges, dtype=np.int64), np.asarray(edge_groups), float(length), free)
    obj = builder(problem)
    x0 = problem.x0

    def cost(x):
        r = obj.residuals(x)
        return 0.5 * float(r @ r)

    cost0 = cost(x0)
    if len(x0) == 0:
        return UVOptimization(uv, cost0, cost0, 0, 0, 0, "no free nodes", 1.0, objective)
    tri = None if triangles is None else np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    if tri is None or area_floor <= 0:
        solve = obj
    else:
        # weight^2 / 2 > cost0: a folded triangle alone costs more than the start
        solve = _with_barrier(problem, obj, tri, 1.0 + 2.0 * np.sqrt(cost0), float(area_floor))
    result = scipy.optimize.least_squares(
        solve.residuals,
        x0,
        jac=solve.jacobian,
        bounds=tuple(np.broadcast_to(b, uv.shape).ravel()[problem.variables] for b in (domain.lower, domain.upper)),
        method="trf",
        tr_solver="lsmr",
        tr_options={"atol": 1e-12, "btol": 1e-12},
        x_scale=1.0,
        ftol=ftol,
        xtol=xtol,
        gtol=gtol,
        max_nfev=max_nfev,
    )
    x, t = result.x, 1.0
    if tri is not None:
        x, t = _backtrack_fold_over(problem, tri, x0, result.x, cost, cost0)
    return UVOptimization(
        problem.uv_of(x),
        cost0,
        cost(x),
        int(result.nfev),
        int(result.njev or 0),
        int(result.status),
        str(result.message),
        t,
        objective,
    )


def _with_barrier(problem, obj, triangles, weight, fraction):
    """Append the fold-over barrier (:class:`~equimesh.surface._jacobian.AreaBarrier`) on (u, v) areas."""
    barrier = AreaBarrier(triangles, problem.uv, fraction, weight, problem.variables)

    def residuals(x):
        return np.concatenate([obj.residuals(x), barrier.residuals(problem.uv_of(x))])

    def jacobian(x):
        return scipy.sparse.vstack([obj.jacobian(x), barrier.jacobian(problem.uv_of(x))], format="csr")

    return Objective(residuals, jacobian, obj.description + " + fold-over barrier")


def flipped_triangles(uv_before, uv_after, triangles):
    """Triangles counter-clockwise in (u, v) before but not strictly after (fold-over)."""
    triangles = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    before, after = signed_areas(uv_before, triangles), signed_areas(uv_after, triangles)
    return np.flatnonzero((before > 0) & (after <= 0))


def _backtrack_fold_over(problem, triangles, x0, x1, cost, cost0, halvings=30):
    """Shorten the step ``x0 -> x1`` until no triangle flips and the cost does not rise."""
    uv0 = problem.uv
    t = 1.0
    for _ in range(halvings):
        x = x0 + t * (x1 - x0)
        if not len(flipped_triangles(uv0, problem.uv_of(x), triangles)) and cost(x) <= cost0:
            return x, t
        t *= 0.5
    return x0, 0.0
