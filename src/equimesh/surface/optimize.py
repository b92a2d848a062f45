"""Final optimisation of the nodes' parameters (Section 4, last paragraph, and beyond).

"Finally, the deviation of the edge lengths in G1 from the target value is
minimized by considering (u_i, v_i) of inner nodes as variables."  The
variables are the (u, v) of the free nodes, kept in the chart's parameter domain by
bounds (:func:`parameter_box`), for "sliding" boundary nodes the one
parameter along the side they lie on (the other stays on the side; corners
stay fixed), and for nodes sliding along a polyline (the flattened loops of a
triangle mesh, the openings' edges) their arc position ``s``
(:class:`~equimesh.surface._slide.Slide`, ``uv = loop(s)``, the Jacobian by
the chain rule through ``d uv / d s``, :meth:`UVProblem.chain`).  The least-squares problem is solved by the sparse bounded
Levenberg-Marquardt of :mod:`equimesh.surface._solver` with an analytic sparse
Jacobian (chain rule through the surface's first derivatives).

The seam.  What is minimised is looked up by name in :data:`OBJECTIVES`: a
builder ``builder(problem: UVProblem) -> Objective`` returning the residual
and sparse Jacobian functions of the variable vector, optionally a hard
constraint (``feasible``) and a continuation (``refine``).

* ``"paper"``: the paper's objective, ``(L - l) / l`` of the G1 members,
  boundary fixed;
* ``"bounded"`` (beyond the paper, the default of
  :func:`~equimesh.surface.pipeline.mesh_surface`): every member in [l, 2l]
  as a hard constraint, and as many members as possible at the target
  ``l (1 + BOUNDED_OFFSET)`` by rounds of reweighted (Cauchy) least squares
  that also pull the members outside the bounds in (:func:`bounded_objective`),
  boundary nodes sliding.

Fold-over.  Lengths do not see orientation, and the G1 edges do not see the
triangles between the lattice and the boundary at all: minimising the G1
deviation alone lets the lattice slide over the boundary nodes and flips
boundary-strip triangles (observed on doubly curved patches).  Two guards:

* a barrier (:class:`~equimesh.surface._jacobian.AreaBarrier`), zero unless a triangle's (u, v) area
  falls below ``area_floor`` (default 0.5) of its start area, heavy enough
  that a folded triangle costs more than the whole start; while no triangle
  is that squeezed the objective is exactly the paper's;
* the solver's acceptance test: a step that leaves any triangle that was
  counter-clockwise in (u, v) at the start not strictly counter-clockwise is
  refused, so no iterate, and no result, has a fold-over.
"""

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np
import scipy.optimize
import scipy.sparse

from .._jit import compiled
from ._jacobian import AreaBarrier, ElementJacobian, signed_areas
from ._solver import NormalEquations, inner, least_squares
from ..errors import EquimeshError, InvalidSurfaceError
from ..mesh import G1, edge_lengths
from .chart import domain_of
from .regularity import derivatives, evaluate
from ..tolerance import (
    BOUNDED_BAND, BOUNDED_FTOL, BOUNDED_LOSS_TOL, BOUNDED_OFFSET, BOUNDED_PENALTY, BOUNDED_PULL, BOUNDED_ROUND_ITERATIONS, BOUNDED_ROUNDS,
    BOUNDED_SCALE, BOUNDED_STEP, LM_INITIAL_DAMPING, PAPER_FTOL,
)


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
    free : (N,) or (N, 2) bool array
        True for the variable nodes (both parameters), or per parameter
        (a sliding boundary node varies one of u and v).
    slides : tuple of :class:`~equimesh.surface._slide.Slide`
        Nodes that slide along a polyline by their arc position (their
        ``free`` entries False): one variable each, after the free parameters.
    """

    surface: object
    uv: np.ndarray
    edges: np.ndarray
    edge_groups: np.ndarray
    length: float
    free: np.ndarray
    slides: tuple = ()

    @property
    def variables(self):
        """(2N,) bool mask of the entries of ``uv.ravel()`` that are variables themselves."""
        return np.broadcast_to(np.asarray(self.free, dtype=bool).reshape(len(self.uv), -1), self.uv.shape).ravel()

    @property
    def moving(self):
        """(2N,) bool mask of the entries of ``uv.ravel()`` that depend on the variables (the Jacobians' columns)."""
        moving = self.variables.copy()
        for slide in self.slides:
            moving[2 * slide.nodes] = moving[2 * slide.nodes + 1] = True
        return moving

    @property
    def sliding_variables(self):
        """Bool mask of the variables that move boundary nodes: the free parameter of a node on a side, the arc positions."""
        variables = self.variables
        one = np.repeat(variables.reshape(len(self.uv), 2).sum(axis=1) == 1, 2)
        return np.concatenate([one[variables], *(np.ones(len(slide.nodes), dtype=bool) for slide in self.slides)])

    @property
    def x0(self):
        """The start as a variable vector: ``(u_0, v_0, u_1, v_1, ...)`` over free nodes, then the arc positions."""
        return np.concatenate([self.uv.ravel()[self.variables], *(slide.s for slide in self.slides)])

    def uv_of(self, x):
        """All nodes' (u, v) with the free ones taken from the variable vector ``x``."""
        variables = self.variables
        full = self.uv.ravel().copy()
        n = int(variables.sum())
        full[variables] = x[:n]
        full = full.reshape(-1, 2)
        for slide in self.slides:
            full[slide.nodes] = slide.uv(x[n : n + len(slide.nodes)])
            n += len(slide.nodes)
        return full

    def chain(self, jacobian, x):
        """``jacobian`` over the :attr:`moving` entries as one over the variables ``x`` (chain rule).

        A sliding node's column pair ``(d/du, d/dv)`` becomes one column, its
        dot product with the loop's direction ``d uv / d s`` at its ``s``.
        """
        if not self.slides:
            return jacobian
        moving, variables = self.moving, self.variables
        n = int(variables.sum())
        row = np.cumsum(moving) - 1  # column of each moving entry in ``jacobian``
        rows, cols, vals = [row[variables]], [np.arange(n)], [np.ones(n)]
        for slide in self.slides:
            k = len(slide.nodes)
            rows += [row[2 * slide.nodes], row[2 * slide.nodes + 1]]
            cols += [np.arange(n, n + k)] * 2
            vals += list(slide.direction(x[n : n + k]).T)
            n += k
        chain = scipy.sparse.csr_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(int(moving.sum()), n)
        )
        return (jacobian @ chain).tocsr()

    def step_limit(self, radius):
        """A trust region per node: ``direction -> step`` with every node's move on the surface at most ``radius``.

        A node's move is taken to first order at its start (the tangent
        lengths ``|X_u|``, ``|X_v|`` at :attr:`uv` times its steps in u and v,
        or ``max(|X_u|, |X_v|)`` times its step along its loop, which is in
        (u, v) arc length), and the steps of a node that would move further
        are scaled down together (its direction in (u, v) is kept).
        """
        su, sv = derivatives(self.surface, self.uv)
        tangent = np.column_stack([np.linalg.norm(su, axis=1), np.linalg.norm(sv, axis=1)])
        variables = self.variables
        node = np.concatenate([np.repeat(np.arange(len(self.uv)), 2)[variables], *(s.nodes for s in self.slides)])
        scale = np.concatenate([tangent.ravel()[variables], *(tangent[s.nodes].max(axis=1) for s in self.slides)])

        def limit(direction):
            move = np.sqrt(np.bincount(node, (scale * direction) ** 2, len(self.uv)))
            factor = np.ones_like(move)
            far = move > radius
            factor[far] = radius / move[far]
            return direction * factor[node]

        return limit

    @property
    def bounds(self):
        """``(lower, upper)`` of the variables: the parameter domain, and each sliding node's range of arc positions."""
        lower, upper = parameter_box(self.surface)
        variables = self.variables
        return (
            np.concatenate([np.tile(lower, len(self.uv))[variables], *(slide.lower for slide in self.slides)]),
            np.concatenate([np.tile(upper, len(self.uv))[variables], *(slide.upper for slide in self.slides)]),
        )


@dataclass(frozen=True)
class Objective:
    """Residuals ``r(x)`` and their sparse Jacobian ``J(x)`` over the variable vector; cost is ``|r|^2 / 2``.

    ``feasible(x)`` (optional) is a hard constraint: once an iterate satisfies
    it every later one does, and the result must (else :func:`optimize_uv`
    raises ``InvalidSurfaceError`` with ``violation(x)``, a phrase naming what
    is violated).  ``refine(x)`` (optional) gives the next objective of a
    continuation from the solution ``x`` of this one, or None when done.
    ``ftol`` is the solver's relative-reduction tolerance for this objective and
    ``max_iterations`` its iteration limit (a round of a continuation need not converge).
    ``start`` (optional) restarts the solve there, with the initial damping,
    instead of at the previous objective's solution (a second path).
    ``hold`` (optional) is a bool mask of variables kept at their start value
    by this objective's solve.  ``final(x)`` (optional, on the objective that
    ends a continuation) gives the point returned instead of its solution ``x``
    (an earlier iterate the continuation kept as its best) and the objective
    whose solve ended there (its costs are reported).  ``limit`` (optional)
    is applied to every step of this objective's solve (a trust region,
    :meth:`UVProblem.step_limit`).
    """

    residuals: Callable[[np.ndarray], np.ndarray]
    jacobian: Callable[[np.ndarray], object]
    description: str = ""
    feasible: Callable[[np.ndarray], bool] = None
    violation: Callable[[np.ndarray], str] = None
    refine: Callable[[np.ndarray], object] = None
    ftol: float = PAPER_FTOL
    max_iterations: int = 500
    start: np.ndarray = None
    hold: np.ndarray = None
    final: Callable[[np.ndarray], tuple] = None
    limit: Callable[[np.ndarray], np.ndarray] = None


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
    assemble = ElementJacobian(e, len(problem.uv), 2, problem.moving)
    surface = problem.surface

    last = {}

    def points(x):
        """``X^s`` at every node for ``x``; the last is kept: the solver evaluates the Jacobian where it last evaluated
        the residuals, and an objective's stages measure the lengths where the solve ended."""
        if "x" not in last or not np.array_equal(last["x"], x):
            last.clear()
            last.update(x=np.array(x), points=evaluate(surface, problem.uv_of(x)))
        return last["points"]

    def lengths(x):
        p = points(x)
        if "lengths" not in last:
            last["lengths"] = edge_lengths(p, e)
        return last["lengths"]

    def jacobian(x):
        grads = _length_gradients(points(x), *derivatives(surface, problem.uv_of(x)), e)
        return lengths(x), problem.chain(assemble(grads), x)

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


def bounded_objective(problem):
    """Beyond the paper: every member in [l, 2l], and as many as possible at one length.

    Counting (the issue's argument): each free node has 2 parameters and each
    member is one equation, so on a doubly curved surface about 2 of every 3
    members can be exact, on a developable one all lattice members can.  Which
    ones is not known in advance, so the objective seeks a sparse deviation
    from the target ``t = 1 + BOUNDED_OFFSET`` (in units of l):

    * the hard constraint ``l <= L_e <= 2 l`` for every member (Theorems 1 and
      3 kept on the surface): the result must satisfy it (checked here, and
      again by the pipeline);
    * rounds of iteratively reweighted least squares, each ``r_e = w_e (L_e / l - t_e)``
      with weights and targets frozen at the round's start: a member outside
      ``[t, 2 - BOUNDED_OFFSET]`` is pulled to the nearer end with the weight
      :data:`~equimesh.tolerance.BOUNDED_PULL`, a member inside is pulled to
      ``t`` with the Cauchy weight ``1 / sqrt(1 + (d_e / s)^2)``,
      ``d_e = L_e / l - t``, ``s = BOUNDED_SCALE`` (majorise-minimise for the
      Cauchy loss ``sum log(1 + (d_e / s)^2)``).  A member that cannot be
      made exact ends far outside ``s`` with a small weight and stops pulling
      on the others; a member pushed below ``t`` is pulled back up, ten times
      harder, next round.  Each round takes at most
      :data:`~equimesh.tolerance.BOUNDED_ROUND_ITERATIONS` solver iterations
      (the damping warm-started from the previous round), each step moving
      every node by at most :data:`~equimesh.tolerance.BOUNDED_STEP` l on
      the surface (:meth:`UVProblem.step_limit`, a trust region per node:
      where the model fails, the line search shortens the step of every
      node, so one bad region slowed the whole mesh, more so the larger it was).  The rounds do not
      lock the bounds in (a step may push a member out, the next round pulls
      it back; locking them in stalled the sparsity, docs/decisions.md).  A
      series of rounds ends at the first round whose Cauchy loss is within
      :data:`~equimesh.tolerance.BOUNDED_LOSS_TOL` (relative) of its start's
      and that ends with every member in [l, 2l], or that stalls (its own
      cost changes by no more than that either: the next round would pose
      the same problem; if its solve began with a damping carried over, one
      more round starts with the initial one), or after
      :data:`~equimesh.tolerance.BOUNDED_ROUNDS` rounds;
    * two starts, because the rounds are a local method: first the remapped
      mesh; then the optimum of the paper's objective (Section 4's last step,
      :func:`paper_objective`, solved from the remapped mesh with the
      boundary nodes held, so that it is the paper's problem).  If its share
      of members within :data:`~equimesh.tolerance.BOUNDED_BAND` of l beats
      every point in [l, 2l] kept so far, the boundary nodes are released
      (the paper's objective solved on) and a second series of rounds starts
      there: it begins with the exact members the paper reaches.  On steep
      surfaces (where the paper's optimum leaves many members far outside
      [l, 2l]) the first start wins, on mild ones often the second
      (docs/decisions.md);
    * the result is the iterate in [l, 2l] with the largest share of members
      within :data:`~equimesh.tolerance.BOUNDED_BAND` of l seen at the end of
      any round (:attr:`Objective.final`);
    * if no round of either series ended in [l, 2l], a last stage restarts
      from the remapped mesh (a member the rounds cannot pull in was
      observed): Cauchy terms plus a smoothed one-sided penalty of slope
      ``BOUNDED_PENALTY`` below ``1 + BOUNDED_OFFSET / 2`` and above
      ``2 - BOUNDED_OFFSET``, solved to convergence with the bounds locked in
      once reached; if it ends outside [l, 2l] too, :func:`optimize_uv`
      refuses the surface.

    The target is ``l (1 + BOUNDED_OFFSET)``, not ``l``: exact members sit at
    the lower bound otherwise, where any rounding would put them outside [l, 2l].
    """
    l = problem.length
    lengths, length_jacobian = edge_length_terms(problem, problem.edges)
    target, high = 1.0 + BOUNDED_OFFSET, 2.0 - BOUNDED_OFFSET
    limit = problem.step_limit(BOUNDED_STEP * l)  # every round's trust region

    def inside(ratio):
        return bool(np.all((ratio >= 1.0) & (ratio <= 2.0)))

    def share(ratio):
        """The issue's measure: the share of members within ``BOUNDED_BAND`` of l."""
        return float(np.mean(np.abs(ratio - 1.0) <= BOUNDED_BAND))

    def feasible(x):
        return inside(lengths(x) / l)

    def violation(x):
        ratio = lengths(x) / l
        out = int(np.count_nonzero((ratio < 1.0) | (ratio > 2.0)))
        return f"{out} of {len(ratio)} members outside [l, 2l] (lengths from {ratio.min():.6g} l to {ratio.max():.6g} l)"

    def cauchy_loss(ratio):
        """The loss that the rounds decrease (majorise-minimise): ``sum log(1 + (d_e / s)^2)``."""
        return float(np.sum(np.log1p(((ratio - target) / BOUNDED_SCALE) ** 2)))

    def cauchy_weight(ratio):
        return 1.0 / np.sqrt(1.0 + ((ratio - target) / BOUNDED_SCALE) ** 2)

    def weighted(weight, goal, extra=None):
        """Residuals ``weight (L / l - goal)`` (and ``extra(ratio)``: values, slopes) with their Jacobian."""

        def residuals(x):
            ratio = lengths(x) / l
            r = weight * (ratio - goal)
            return r if extra is None else np.concatenate([r, extra(ratio)[0]])

        def jacobian(x):
            length, jac = length_jacobian(x)
            jac = jac / l
            rows = _scale_rows(weight, jac)
            return rows if extra is None else scipy.sparse.vstack(
                [rows, _scale_rows(extra(length / l)[1], jac)], format="csr"
            )

        return residuals, jacobian

    best = {"x": None, "share": -1.0}

    def keep_best(x, ratio, objective):
        """Remember ``x`` (``ratio = L / l``), where ``objective``'s solve ended, if in [l, 2l] with the largest share so far."""
        if inside(ratio) and share(ratio) > best["share"]:
            best.update(x=np.array(x), share=share(ratio), objective=objective)

    def round_(k, x_start, then, start=None):
        """Round ``k + 1`` of a series from ``x_start`` (restarted there if ``start`` is given); ``then(x)`` follows it."""
        ratio = lengths(x_start) / l
        goal = np.clip(ratio, target, high)
        weight = np.where(goal == ratio, cauchy_weight(ratio), BOUNDED_PULL)
        goal = np.where(goal == ratio, target, goal)
        residuals, jacobian = weighted(weight, goal)
        loss, cost = cauchy_loss(ratio), float(np.sum((weight * (ratio - goal)) ** 2))

        def refine(x):
            end = lengths(x) / l
            keep_best(x, end, objective)
            settled = abs(cauchy_loss(end) - loss) <= BOUNDED_LOSS_TOL * loss
            stalled = settled and cost - float(np.sum((weight * (end - goal)) ** 2)) <= BOUNDED_LOSS_TOL * cost
            if k + 1 >= BOUNDED_ROUNDS or (settled and inside(end)) or (stalled and start is not None):
                return then(x)
            # A stalled round poses the next one the same problem: it ends the series, unless its solve began with
            # a damping left large by earlier solves; then the next round starts afresh.
            return round_(k + 1, x, then, start=x if stalled else None)

        objective = Objective(
            residuals, jacobian, f"members into [l, 2l] and to {target:g} l, round {k + 1}", None, None, refine,
            BOUNDED_FTOL, BOUNDED_ROUND_ITERATIONS, start=start, final=chosen, limit=limit,
        )
        return objective

    def last_stage():
        low, smooth = 1.0 + 0.5 * BOUNDED_OFFSET, 0.25 * BOUNDED_OFFSET

        def penalty(ratio):
            """Smoothed hinge ``psi(h)`` of the depth ``h`` outside ``[low, high]`` and its derivative in ``ratio``."""
            depth = np.maximum(0.0, low - ratio) + np.maximum(0.0, ratio - high)
            side = np.where(ratio > high, 1.0, -1.0)
            inner = depth < smooth
            value = np.where(inner, depth**2 / (2 * smooth), depth - smooth / 2)
            slope = np.where(inner, depth / smooth, 1.0) * side
            return BOUNDED_PENALTY * value, BOUNDED_PENALTY * slope

        return Objective(
            *weighted(cauchy_weight(lengths(problem.x0) / l), target, penalty),
            f"members in [l, 2l] by a penalty, Cauchy loss on L / l - {target:g}", feasible, violation, None,
            BOUNDED_FTOL, start=problem.x0,
        )

    def chosen(x):
        return best["x"], best["objective"]

    def finish(x):
        return None if best["x"] is not None else last_stage()

    def paper_stage(x):
        """The paper's optimum (boundary held, as ``optimize="paper"``), then rounds from it if it has the larger share."""

        def refine(x):
            if share(lengths(x) / l) <= best["share"]:
                return finish(x)
            return replace(paper_objective(problem), refine=lambda y: round_(0, y, finish), final=chosen)

        held = problem.sliding_variables
        return replace(paper_objective(problem), refine=refine, start=problem.x0, hold=held, final=chosen)

    return round_(0, problem.x0, paper_stage)


def _scale_rows(scale, jac):
    """``diag(scale) @ jac`` for a CSR ``jac``, on its structure (a product ``diags @ jac`` drops the entries that
    become zero: a new structure, so a new analysis of the normal equations, whenever a weight or slope is 0)."""
    data = np.repeat(scale, np.diff(jac.indptr)) * jac.data
    return scipy.sparse.csr_matrix((data, jac.indices, jac.indptr), shape=jac.shape)


#: Objective builders by name, each ``builder(problem: UVProblem) -> Objective``.
OBJECTIVES = {"paper": paper_objective, "bounded": bounded_objective}


@dataclass(frozen=True)
class UVOptimization:
    """Result of :func:`optimize_uv`.

    Attributes
    ----------
    uv : (N, 2) float array
        Optimised parameters; fixed nodes bit-identical to the start.
    cost_before, cost_after : float
        ``|r|^2 / 2`` of the last objective (the one whose solve ended at ``uv``) at the start and at ``uv``.
    nfev, njev : int
        Residual and Jacobian evaluations of the solver (all stages).
    converged : bool, message : str
        Whether the last stage met a convergence test, and which.
    objective : str
    """

    uv: np.ndarray
    cost_before: float
    cost_after: float
    nfev: int
    njev: int
    converged: bool
    message: str
    objective: str


def optimize_uv(
    surface,
    uv,
    edges,
    edge_groups,
    length,
    *,
    fixed,
    sliding=(),
    slides=(),
    triangles=None,
    objective="paper",
    area_floor=0.5,
    ftol=None,
    xtol=1e-10,
    gtol=1e-10,
):
    """Optimise the (u, v) of the free nodes (Section 4, final step).

    Parameters
    ----------
    surface : Chart
    uv : (N, 2) array_like
        Start parameters of every node, in the parameter domain (step 4's output).
    edges : (E, 2) int array_like
    edge_groups : (E,) int array_like
        G1 / OTHER label per edge.
    length : float
        The target length l.
    fixed : array_like of int or (N,) bool
        Nodes that stay put (the boundary nodes for ``"paper"``).
    sliding : array_like of int
        Nodes on the boundary of the parameter domain that move along it:
        the parameter(s) at a side of :func:`parameter_box` stay, the other
        varies (a node at a corner stays put).
    slides : sequence of :class:`~equimesh.surface._slide.Slide`
        Nodes that slide along a polyline in (u, v) by their arc position,
        within their bounds (the boundary loops of a triangle-mesh chart).
    triangles : (M, 3) int array_like, optional
        For the fold-over guards (recommended): without them neither the
        barrier nor the acceptance test is applied.
    objective : str
        Key of :data:`OBJECTIVES`.
    area_floor : float
        Fold-over barrier threshold ``tau`` in [0, 1): a triangle is penalised
        once its (u, v) area falls below ``tau`` times its start area (see
        :class:`~equimesh.surface._jacobian.AreaBarrier`).  0 disables the
        barrier (the acceptance test still applies).
    ftol, xtol, gtol
        Convergence tolerances of :func:`equimesh.surface._solver.least_squares`;
        ``ftol=None`` takes the objective's (:attr:`Objective.ftol`).

    Returns
    -------
    UVOptimization

    Raises
    ------
    InvalidSurfaceError
        The objective has a hard constraint (``"bounded"``: every member in
        [l, 2l]) and no point satisfying it was found; the message suggests a
        smaller l, a finer grid (``surface.finer`` names what refines a chart,
        "a finer auxiliary grid" by default) or ``optimize='paper'``.
    """
    try:
        builder = OBJECTIVES[objective]
    except (KeyError, TypeError):
        raise EquimeshError(f"unknown objective {objective!r}; choose from {sorted(OBJECTIVES)}") from None
    lower, upper = parameter_box(surface)
    uv = np.clip(np.array(uv, dtype=float).reshape(-1, 2), lower, upper)
    slides = tuple(slides)
    free = _free_parameters(uv, fixed, sliding, lower, upper)
    for slide in slides:
        free[slide.nodes] = False
    problem = UVProblem(
        surface, uv, np.asarray(edges, dtype=np.int64), np.asarray(edge_groups), float(length), free, slides
    )
    obj = builder(problem)
    x0 = problem.x0
    if len(x0) == 0:
        cost0 = _cost(obj, x0)
        return UVOptimization(uv, cost0, cost0, 0, 0, True, "no free nodes", objective)
    tri = None if triangles is None else np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    x, nfev, njev, damping = x0, 0, 0, LM_INITIAL_DAMPING
    normal_equations = NormalEquations()  # one pattern for every stage: analysed once
    barrier = None if tri is None or area_floor <= 0 else _fold_over_barrier(problem, tri, area_floor)
    while True:
        if obj.start is not None:  # a restart is a fresh solve: its own start and the initial damping
            x, damping = obj.start, LM_INITIAL_DAMPING
        guard = _Guard(problem, tri, obj.feasible, x)
        solve = obj if barrier is None else _with_barrier(problem, obj, barrier, x)
        tol = obj.ftol if ftol is None else ftol
        box = problem.bounds if obj.hold is None else tuple(np.where(obj.hold, x, bound) for bound in problem.bounds)
        while True:
            solution = least_squares(
                solve.residuals, solve.jacobian, x, *box, accept=guard, gtol=gtol, xtol=xtol, ftol=tol,
                max_iterations=obj.max_iterations, damping=damping, normal_equations=normal_equations,
                limit=obj.limit,
            )
            x, nfev, njev = solution.x, nfev + solution.evaluations, njev + solution.iterations + 1
            damping = solution.damping  # warm start: the next solve begins where this one's damping ended
            if obj.feasible is None or obj.refine is not None or obj.feasible(x) or tol <= PAPER_FTOL:
                break
            tol = PAPER_FTOL  # a last stage that ends outside the hard constraint goes on to the tight tolerance
        following = None if obj.refine is None else obj.refine(x)
        if following is None:
            break
        obj = following
    if obj.final is not None:
        x, obj = obj.final(x)
    if obj.feasible is not None and not obj.feasible(x):
        raise InvalidSurfaceError(
            f"optimisation ({objective}): no mesh with every member in [l, 2l] found, {obj.violation(x)}; "
            f"use a smaller l, {getattr(surface, 'finer', 'a finer auxiliary grid')}, or optimize='paper' "
            "(which does not bound the members on the surface)"
        )
    return UVOptimization(
        problem.uv_of(x), _cost(obj, x0), _cost(obj, x), nfev, njev, solution.converged, solution.message, objective
    )


def parameter_box(surface):
    """The chart's parameter domain as ``(lower, upper)``, each ``(u, v)`` (:func:`~equimesh.surface.chart.domain_of`)."""
    domain = domain_of(surface)
    return np.asarray(domain.lower, dtype=float), np.asarray(domain.upper, dtype=float)


def _free_parameters(uv, fixed, sliding, lower, upper):
    """(N, 2) mask of the variable parameters: all but the fixed nodes', and a sliding node's only off its sides."""
    free = np.ones(uv.shape, dtype=bool)
    fixed = np.asarray(fixed)
    free[np.flatnonzero(fixed) if fixed.dtype == bool else fixed.astype(np.int64)] = False
    slide = np.asarray(sliding, dtype=np.int64)
    free[slide] &= (uv[slide] > lower) & (uv[slide] < upper)
    return free


def _cost(obj, x):
    r = obj.residuals(x)
    return 0.5 * inner(r, r)


class _Guard:
    """The solver's acceptance test: no fold-over in (u, v), and a reached hard constraint kept.

    :func:`~equimesh.surface._solver.least_squares` calls it only on
    cost-reducing steps and takes the step exactly when it returns True, so
    it tracks whether the current iterate is feasible.
    """

    def __init__(self, problem, triangles, feasible, x):
        self.problem, self.triangles, self.feasible = problem, triangles, feasible
        self.inside = feasible is not None and feasible(x)
        if triangles is not None:  # the triangles counter-clockwise at the start, which must stay so
            self.triangles = triangles[signed_areas(problem.uv, triangles) > 0]

    def __call__(self, x):
        if self.triangles is not None and np.any(signed_areas(self.problem.uv_of(x), self.triangles) <= 0):
            return False
        if self.feasible is None:
            return True
        now = self.feasible(x)
        if self.inside and not now:
            return False
        self.inside = now
        return True


def _fold_over_barrier(problem, triangles, fraction):
    """The fold-over barrier (:class:`~equimesh.surface._jacobian.AreaBarrier`) on the (u, v) areas of ``triangles``, weight 1."""
    return AreaBarrier(triangles, problem.uv, fraction, 1.0, problem.moving, power=2)


def _with_barrier(problem, obj, barrier, x):
    """Append the fold-over ``barrier`` (:func:`_fold_over_barrier`) to ``obj``.

    Its weight ``w`` has ``w^2 / 2`` above the objective's cost at ``x``: a
    folded triangle alone costs more than the start of the solve.
    """
    barrier = barrier.weighted(1.0 + 2.0 * np.sqrt(_cost(obj, x)))

    def residuals(y):
        return np.concatenate([obj.residuals(y), barrier.residuals(problem.uv_of(y))])

    def jacobian(y):
        return scipy.sparse.vstack([obj.jacobian(y), problem.chain(barrier.jacobian(problem.uv_of(y)), y)], format="csr")

    return Objective(residuals, jacobian, obj.description + " + fold-over barrier")
