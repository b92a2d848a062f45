"""What the final optimisation minimises: one record per objective (Section 4, last paragraph, and beyond).

An objective is an :class:`Objective` in :data:`OBJECTIVES`: its name, what it
promises (members bounded to [l, 2l] or not), whether the boundary nodes
slide, its default node limit (per factorisation of the normal equations), and its *stages*: a generator that yields one
:class:`Stage` (a least-squares problem over the variables) at a time,
receives the point where that stage's solve ended, and returns the point the
optimisation ends at with the stage whose costs are reported.
:func:`~equimesh.surface.optimize.driver.optimize_uv` drives it.

* ``"paper"``: the paper's objective, ``(L - l) / l`` of the G1 members,
  boundary fixed (:func:`paper_stages`);
* ``"bounded"`` (beyond the paper): every member in [l, 2l] as a hard
  constraint, and as many members as possible at one length by rounds of
  reweighted (Cauchy) least squares, boundary nodes sliding
  (:func:`bounded_stages`).
"""

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np
import scipy.sparse

from ..._jit import compiled
from ...errors import number
from ...mesh import G1, edge_lengths
from ...tolerance import (
    BOUNDED_BAND,
    BOUNDED_FTOL,
    BOUNDED_LOSS_TOL,
    BOUNDED_OFFSET,
    BOUNDED_PENALTY,
    BOUNDED_PULL,
    BOUNDED_ROUND_ITERATIONS,
    BOUNDED_ROUNDS,
    BOUNDED_SCALE,
    BOUNDED_STEP,
    PAPER_FTOL,
)
from ..regularity import derivatives, evaluate
from .jacobian import ElementJacobian
from .solver import factorisation_name


@dataclass(frozen=True)
class Stage:
    """One least-squares solve: residuals ``r(x)`` and their sparse Jacobian ``J(x)``; its cost is ``|r|^2 / 2``.

    Attributes
    ----------
    residuals, jacobian : callables of the variable vector
    description : str
    ftol : float
        The solver's relative-reduction tolerance.
    max_iterations : int
        The solver's iteration limit (a round of a series need not converge).
    start : array or None
        Restart the solve there with the initial damping, instead of going on
        from where the previous stage ended with its damping.
    hold : bool array or None
        Variables kept at their start value by this solve.
    limit : callable or None
        Applied to every step (a trust region, :meth:`~.problem.UVProblem.step_limit`).
    feasible : callable or None
        A hard constraint ``x -> bool``: once an iterate satisfies it every
        later one does, and a stage that ends outside it is solved on to
        ``PAPER_FTOL``; if the point the optimisation ends at is outside, the
        surface is refused with ``violation(x)``, a phrase naming what is violated.
    """

    residuals: Callable[[np.ndarray], np.ndarray]
    jacobian: Callable[[np.ndarray], object]
    description: str = ""
    ftol: float = PAPER_FTOL
    max_iterations: int = 500
    start: np.ndarray = None
    hold: np.ndarray = None
    limit: Callable[[np.ndarray], np.ndarray] = None
    feasible: Callable[[np.ndarray], bool] = None
    violation: Callable[[np.ndarray], str] = None


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


def paper_stage(problem):
    """The paper's objective as one stage: ``r_e = (L_e - l) / l`` for every G1 edge ``e``."""
    l = problem.length
    g1 = problem.edges[problem.edge_groups == G1]
    lengths, jacobian = edge_length_terms(problem, g1)

    def residuals(x):
        return (lengths(x) - l) / l

    def jac(x):
        return jacobian(x)[1] / l

    return Stage(residuals, jac, "relative deviation (L - l) / l of the G1 edges")


def paper_stages(problem):
    """Section 4's last step: the paper's objective solved once from the remapped mesh (:func:`paper_stage`)."""
    stage = paper_stage(problem)
    x = yield stage
    return x, stage


def bounded_stages(problem):
    """Beyond the paper: every member in [l, 2l], and as many as possible at one length.

    Counting: each free node has 2 parameters and each
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
      it back; locking them in stalled the sparsity, docs/decisions.md, "The bounded objective").  A
      series of rounds ends at the first round whose Cauchy loss is within
      :data:`~equimesh.tolerance.BOUNDED_LOSS_TOL` (relative) of its start's
      and that ends with every member in [l, 2l], or that stalls (its own
      cost changes by no more than that either: the next round would pose
      the same problem; if its solve began with a damping carried over, one
      more round starts with the initial one), or after
      :data:`~equimesh.tolerance.BOUNDED_ROUNDS` rounds;
    * two starts, because the rounds are a local method: first the remapped
      mesh; then the optimum of the paper's objective (Section 4's last step,
      :func:`paper_stage`, solved from the remapped mesh with the
      boundary nodes held, so that it is the paper's problem).  If its share
      of members within :data:`~equimesh.tolerance.BOUNDED_BAND` of l beats
      every point in [l, 2l] kept so far, the boundary nodes are released
      (the paper's objective solved on) and a second series of rounds starts
      there: it begins with the exact members the paper reaches.  On steep
      surfaces (where the paper's optimum leaves many members far outside
      [l, 2l]) the first start wins, on mild ones often the second
      (docs/decisions.md, "Two starts for bounded, and the best point kept");
    * the result is the iterate in [l, 2l] with the largest share of members
      within :data:`~equimesh.tolerance.BOUNDED_BAND` of l seen at the end of
      any round;
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
        """The share of members within ``BOUNDED_BAND`` of l (what the rounds keep the best of)."""
        return float(np.mean(np.abs(ratio - 1.0) <= BOUNDED_BAND))

    def feasible(x):
        return inside(lengths(x) / l)

    def violation(x):
        ratio = lengths(x) / l
        out = int(np.count_nonzero((ratio < 1.0) | (ratio > 2.0)))
        return (
            f"{out} of {len(ratio)} members outside [l, 2l] "
            f"(lengths from {number(ratio.min())} l to {number(ratio.max())} l)"
        )

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
            return (
                rows
                if extra is None
                else scipy.sparse.vstack([rows, _scale_rows(extra(length / l)[1], jac)], format="csr")
            )

        return residuals, jacobian

    best = {"x": None, "share": -1.0, "stage": None}

    def keep_best(x, ratio, stage):
        """Remember ``x`` (``ratio = L / l``), where ``stage``'s solve ended, if in [l, 2l] with the largest share so
        far."""
        if inside(ratio) and share(ratio) > best["share"]:
            best.update(x=np.array(x), share=share(ratio), stage=stage)

    def round_stage(k, x_start, restart):
        """Round ``k + 1`` of a series from ``x_start`` (restarted there if ``restart``), and its loss and cost
        there."""
        ratio = lengths(x_start) / l
        goal = np.clip(ratio, target, high)
        weight = np.where(goal == ratio, cauchy_weight(ratio), BOUNDED_PULL)
        goal = np.where(goal == ratio, target, goal)
        residuals, jacobian = weighted(weight, goal)
        stage = Stage(
            residuals,
            jacobian,
            f"members into [l, 2l] and to {target:g} l, round {k + 1}",
            BOUNDED_FTOL,
            BOUNDED_ROUND_ITERATIONS,
            start=x_start if restart else None,
            limit=limit,
        )
        return stage, weight, goal, cauchy_loss(ratio), float(np.sum((weight * (ratio - goal)) ** 2))

    def series(x):
        """Rounds from ``x`` until one settles in [l, 2l], stalls, or :data:`BOUNDED_ROUNDS` are done; ends where the
        last round did."""
        restart = False
        for k in range(BOUNDED_ROUNDS):
            stage, weight, goal, loss, cost = round_stage(k, x, restart)
            x = yield stage
            end = lengths(x) / l
            keep_best(x, end, stage)
            settled = abs(cauchy_loss(end) - loss) <= BOUNDED_LOSS_TOL * loss
            stalled = settled and cost - float(np.sum((weight * (end - goal)) ** 2)) <= BOUNDED_LOSS_TOL * cost
            if (settled and inside(end)) or (stalled and restart):
                break
            # A stalled round poses the next one the same problem: it ends the series, unless its solve began with
            # a damping left large by earlier solves; then the next round starts afresh.
            restart = stalled
        return x

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

        return Stage(
            *weighted(cauchy_weight(lengths(problem.x0) / l), target, penalty),
            f"members in [l, 2l] by a penalty, Cauchy loss on L / l - {target:g}",
            BOUNDED_FTOL,
            start=problem.x0,
            feasible=feasible,
            violation=violation,
        )

    yield from series(problem.x0)
    # The paper's optimum, boundary held (the paper's problem, as optimize="paper"), then rounds from it if it has
    # the larger share: the boundary released (the paper's objective solved on) first.
    x = yield replace(paper_stage(problem), start=problem.x0, hold=problem.sliding_variables)
    if share(lengths(x) / l) > best["share"]:
        x = yield paper_stage(problem)
        yield from series(x)
    if best["x"] is not None:
        return best["x"], best["stage"]
    stage = last_stage()
    x = yield stage
    return x, stage


def _scale_rows(scale, jac):
    """``diag(scale) @ jac`` for a CSR ``jac``, on its structure (a product ``diags @ jac`` drops the entries that
    become zero: a new structure, so a new analysis of the normal equations, whenever a weight or slope is 0)."""
    data = np.repeat(scale, np.diff(jac.indptr)) * jac.data
    return scipy.sparse.csr_matrix((data, jac.indices, jac.indptr), shape=jac.shape)


@dataclass(frozen=True)
class Objective:
    """One objective of the final optimisation: how it is solved and what it promises.

    Attributes
    ----------
    name : str
        Its key in :data:`OBJECTIVES`, what ``optimize=`` and ``--optimize`` name.
    stages : callable
        ``stages(problem)``: a generator of :class:`Stage` (module docstring).
    description : str
    slides : bool
        The boundary nodes slide along the boundary (between its corners);
        otherwise they stay fixed.
    bounds_members : bool
        Every member of the result lies in [l, 2l] (the pipeline checks it on
        every mesh it returns).
    max_nodes : dict
        The default node limit of :func:`~equimesh.surface.pipeline.mesh_surface`
        with this objective, per factorisation of
        :data:`~equimesh.surface.optimize.solver.FACTORISATIONS`
        (docs/performance.md, "The final optimisation"); :meth:`node_limit`
        gives the one that applies.
    """

    name: str
    stages: Callable
    description: str
    slides: bool
    bounds_members: bool
    max_nodes: dict

    def node_limit(self, factorisation=None):
        """The default node limit with ``factorisation`` (by default the one the optimisation uses,
        :data:`~equimesh.surface.optimize.solver.DEFAULT_FACTORISATION`)."""
        return self.max_nodes[factorisation_name(factorisation)]


#: Every objective's record: what ``optimize=`` names.  The default node limits keep the optimisation of a default
#: run to about two minutes on a 2-core machine with each factorisation, measured by
#: ``EQUIMESH_FACTORISATION=F python experiments/optimisation_timing.py --length L --objective bounded`` on the
#: reference dome (docs/performance.md, "The final optimisation"; CPU seconds, the machine shared): "bounded" took
#: 46 s (CHOLMOD) and 40 s (PARDISO) at 34,031 nodes, 165 s and 207 s at 67,371 nodes, so 50,000 nodes for
#: both; SuperLU 201 s at 34,031 and 125 s at 23,916 nodes, so 24,000.  "paper" took 59.2 s with SuperLU, the
#: slowest, at 34,031 nodes, so 34,000 with each.
_PAPER_MAX_NODES = {"pardiso": 34_000, "cholmod": 34_000, "superlu": 34_000}
_BOUNDED_MAX_NODES = {"pardiso": 50_000, "cholmod": 50_000, "superlu": 24_000}
OBJECTIVES = {
    objective.name: objective
    for objective in (
        Objective(
            "paper",
            paper_stages,
            "the paper's: the G1 members' relative deviation from l, boundary fixed",
            slides=False,
            bounds_members=False,
            max_nodes=_PAPER_MAX_NODES,
        ),
        Objective(
            "bounded",
            bounded_stages,
            "every member in [l, 2l], as many as possible at l; boundary nodes slide along the boundary",
            slides=True,
            bounds_members=True,
            max_nodes=_BOUNDED_MAX_NODES,
        ),
    )
}
