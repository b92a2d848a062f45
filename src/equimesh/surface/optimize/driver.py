"""Final optimisation of the nodes' parameters (Section 4, last paragraph, and beyond): :func:`optimize_uv`.

"Finally, the deviation of the edge lengths in G1 from the target value is
minimized by considering (u_i, v_i) of inner nodes as variables."  The
variables (:class:`~equimesh.surface.optimize.problem.UVProblem`) are the
(u, v) of the free nodes, kept in the chart's parameter domain by bounds, and
the arc position of each node that slides along a closed polyline in (u, v)
(the parameter rectangle, an opening, a triangle mesh's flattened loop).  An
objective (:data:`~equimesh.surface.optimize.objectives.OBJECTIVES`) is a
sequence of stages, each a least-squares problem solved by the sparse bounded
Levenberg-Marquardt of :mod:`equimesh.surface.optimize.solver` with an
analytic sparse Jacobian (chain rule through the surface's first
derivatives); the damping and the normal equations' analysis carry over
from one stage to the next.  A stage that does not depend on the ones
before it is solved beside them on a second thread
(:attr:`~equimesh.surface.optimize.stage.Stage.beside`), with the same end.

Fold-over.  Lengths do not see orientation, and the G1 edges do not see the
triangles between the lattice and the boundary at all: minimising the G1
deviation alone lets the lattice slide over the boundary nodes and flips
boundary-strip triangles (observed on doubly curved patches).  Two guards,
on every stage:

* a barrier (:class:`~equimesh.surface.optimize.jacobian.AreaBarrier`), zero
  unless a triangle's (u, v) area falls below ``area_floor`` (default 0.5)
  of its start area, heavy enough that a folded triangle costs more than the
  whole start; while no triangle is that squeezed the objective is exactly
  the stage's;
* the solver's acceptance test: a step that leaves any triangle that was
  counter-clockwise in (u, v) at the start not strictly counter-clockwise is
  refused, so no iterate, and no result, has a fold-over.
"""

from dataclasses import dataclass, replace

import numpy as np
import scipy.optimize
import scipy.sparse

from ..._checks import check_length, finite_rows, index_rows
from ...classes import DEFAULT_TOLERANCE
from ...errors import EquimeshError, InvalidSurfaceError
from ...tolerance import JOINT_ANGLE, JOINT_WEIGHT, LM_INITIAL_DAMPING, PAPER_FTOL
from .beside import Beside
from .jacobian import AreaBarrier, signed_areas
from .joints import joint_bounds
from .members import Members, out_of_reach
from .objectives import OBJECTIVES
from .problem import UVProblem, free_nodes, parameter_box
from .solver import NormalEquations, inner, least_squares
from .stage import Stage, WorkSpent


@dataclass(frozen=True)
class UVOptimization:
    """Result of :func:`optimize_uv`.

    Attributes
    ----------
    uv : (N, 2) float array
        Optimised parameters; fixed nodes bit-identical to the start.
    offsets : (N,) float array
        Each node's offset along the surface's unit normal (zero without a surface tolerance).
    cost_before, cost_after : float
        ``|r|^2 / 2`` of the last objective (the one whose solve ended at ``uv``) at the start and at ``uv``.
    nfev, njev : int
        Residual and Jacobian evaluations of the solver (all stages).
    converged : bool, message : str
        Whether the last stage met a convergence test, and which; False where the work bound ended the
        optimisation at the objective's best point found before it.
    objective : str
    work_bound_reached : bool
        The work bound ended the optimisation, at that point.
    """

    uv: np.ndarray
    offsets: np.ndarray
    cost_before: float
    cost_after: float
    nfev: int
    njev: int
    converged: bool
    message: str
    objective: str
    work_bound_reached: bool = False


def optimize_uv(
    surface,
    uv,
    edges,
    edge_groups,
    length,
    *,
    fixed,
    slides=(),
    triangles=None,
    objective="paper",
    area_floor=0.5,
    ftol=None,
    xtol=1e-10,
    gtol=1e-10,
    surface_tolerance=0.0,
    tolerance=DEFAULT_TOLERANCE,
    catalogue=None,
    factorisation=None,
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
    slides : sequence of :class:`~equimesh.surface.optimize.slide.Slide`
        Nodes that slide along a closed polyline in (u, v) by their arc
        position, within their bounds (the sides of the parameter rectangle,
        an opening's edges, the boundary loops of a triangle-mesh chart).
    triangles : (M, 3) int array_like, optional
        For the fold-over guards (recommended): without them neither the
        barrier nor the acceptance test is applied.
    objective : str
        Key of :data:`OBJECTIVES`.
    area_floor : float
        Fold-over barrier threshold ``tau`` in [0, 1): a triangle is penalised
        once its (u, v) area falls below ``tau`` times its start area (see
        :class:`~equimesh.surface.optimize.jacobian.AreaBarrier`).  0 disables the
        barrier (the acceptance test still applies).
    ftol, xtol, gtol
        Convergence tolerances of :func:`equimesh.surface.optimize.solver.least_squares`;
        ``ftol=None`` takes each stage's (:attr:`~equimesh.surface.optimize.stage.Stage.ftol`).
    surface_tolerance : float
        ``D >= 0``: every moving node may leave the surface by at most ``D``
        along its unit normal (:class:`~equimesh.surface.optimize.problem.UVProblem`).
    tolerance : float
        The fabrication tolerance of a length class, relative to ``length`` (the ``"classes"`` objective).
    catalogue : (k,) float array or None
        Stock lengths (absolute, in [l, 2l]) the ``"classes"`` objective cuts members from.
    factorisation : str, optional
        The factorisation of the normal equations, one of
        :data:`~equimesh.surface.optimize.solver.INSTALLED` (checked before any
        work); by default :data:`~equimesh.surface.optimize.solver.DEFAULT_FACTORISATION`.

    Returns
    -------
    UVOptimization

    Raises
    ------
    EquimeshError
        An argument is malformed, each named: ``length`` outside the
        supported range (:class:`~equimesh.errors.InvalidLengthError`), ``uv``
        not finite (N, 2) rows or so far outside the parameter range that
        clipping joins an edge's nodes, an edge, triangle or fixed node that
        is no node, ``edge_groups`` not one label per edge.
    InvalidSurfaceError
        The objective has a hard constraint (``bounds_members``: every member in
        [l, 2l]; ``sound_joints``: every triangle angle at least its bound,
        :mod:`~equimesh.surface.optimize.joints`) and no point satisfying it was
        found, or its start is out of reach of [l, 2l]
        (:func:`~equimesh.surface.optimize.members.out_of_reach`);
        the message suggests a smaller l, a finer grid (``surface.finer`` names
        what refines a chart, "a finer auxiliary grid" by default) or
        ``optimize='paper'``.  Also when the solver's Jacobian evaluations would
        exceed the objective's work bound
        (:attr:`~equimesh.surface.optimize.objectives.Objective.max_jacobians`)
        before its stages kept a point meeting its constraints (bounded's best
        round end in [l, 2l], the classes objective's fewest classes): such a
        point is the result, not converged.
    """
    try:
        record = OBJECTIVES[objective]
    except (KeyError, TypeError):
        raise EquimeshError(f"unknown objective {objective!r}; choose from {sorted(OBJECTIVES)}") from None
    normal_equations = NormalEquations(factorisation)  # one pattern for every stage: analysed once
    length = check_length(length)
    lower, upper = parameter_box(surface)
    uv = finite_rows(uv, 2, "uv", "the (u, v) of node {}", EquimeshError)
    edges = index_rows(edges, 2, len(uv), "edges", "edge {}", "node", EquimeshError)
    uv = _start(uv, edges, lower, upper)
    edge_groups = np.asarray(edge_groups)
    if edge_groups.shape != (len(edges),):
        raise EquimeshError(f"edge_groups must hold one label per edge ({len(edges)}), got shape {edge_groups.shape}")
    slides = tuple(slides)
    free = free_nodes(len(uv), fixed, slides)
    problem = UVProblem(
        surface,
        uv,
        edges,
        edge_groups,
        length,
        free,
        slides,
        surface_tolerance=float(surface_tolerance),
        tolerance=float(tolerance),
        catalogue=None if catalogue is None else np.asarray(catalogue, dtype=float) / float(length),
    )
    tri = (
        None
        if triangles is None
        else index_rows(triangles, 3, len(uv), "triangles", "triangle {}", "node", EquimeshError)
    )
    if record.sound_joints and tri is not None:
        problem = problem.with_joints(tri, joint_bounds(surface, uv, tri))
    barrier = None if tri is None or area_floor <= 0 else fold_over_barrier(problem, tri, area_floor)
    concurrent = len(problem.x0) > 0
    beside = Beside(_alone(problem, tri, barrier, factorisation, (ftol, xtol, gtol)), concurrent=concurrent)
    try:
        return _optimize(problem, record, surface, uv, tri, barrier, normal_equations, beside, ftol, xtol, gtol)
    finally:
        beside.close()


def _optimize(problem, record, surface, uv, tri, barrier, normal_equations, beside, ftol, xtol, gtol):
    """:func:`optimize_uv`'s work on its checked ``problem``: ``record``'s stages solved in turn (those carried
    by another, :attr:`~.stage.Stage.beside`, by ``beside``), the result checked against the objective's promises."""
    objective = record.name
    stages = record.stages(problem)
    stage = _advance(stages, None, beside)
    x0 = problem.x0
    members = Members(problem) if record.bounds_members else None
    if len(x0) == 0:  # nothing moves: the start is the end, held to the objective's promises as any end is
        if members is not None and not members.feasible(x0):
            raise _refusal(objective, surface, f"found, no node free to move, {members.violation(x0)}")
        if not problem.sound(x0):
            raise _unsound(objective, surface, problem, x0)
        cost0 = _cost(stage, x0)
        return UVOptimization(uv, np.zeros(len(uv)), cost0, cost0, 0, 0, True, "no free nodes", objective)
    if members is not None:
        if out_of_reach(members.ratio(x0)):  # docs/decisions.md, "A work bound for the optimisation"
            raise _refusal(objective, surface, f"within reach of the remapped mesh: {members.reach(x0)}")
    x, nfev, work, damping = x0, 0, _Work(record.max_jacobians), LM_INITIAL_DAMPING
    while True:
        if stage.start is not None:  # a restart is a fresh solve: its own start and the initial damping
            x, damping = stage.start, LM_INITIAL_DAMPING
        try:
            if beside.holds(stage):
                solution = beside.take(stage, work)
            else:
                solution = _solve(problem, stage, x, damping, tri, barrier, normal_equations, ftol, xtol, gtol, work)
        except _OutOfWork as spent:
            within = f"within {record.max_jacobians} Jacobian evaluations (its work bound)"
            kept = _kept(stages)
            if kept is not None:  # the objective's best point meeting its constraints, found before the bound
                (x, stage), converged, message, reached = kept, False, f"the best point found {within}", True
                break
            if not record.bounds_members:
                raise InvalidSurfaceError(
                    f"optimisation ({objective}): not converged {within}; use a larger l or {_finer(surface)}"
                ) from None
            raise _refusal(objective, surface, f"found {within}, {Members(problem).violation(spent.x)}") from None
        x, nfev, damping = solution.x, nfev + solution.evaluations, solution.damping  # damping: the next solve's start
        converged, message, reached = solution.converged, solution.message, False
        try:
            stage = _advance(stages, x, beside)
        except StopIteration as done:
            x, stage = done.value
            break
    if stage.feasible is not None and not stage.feasible(x):
        raise _refusal(objective, surface, f"found, {stage.violation(x)}")
    if not problem.sound(x):
        raise _unsound(objective, surface, problem, x)
    return UVOptimization(
        np.array(problem.uv_of(x)),  # a copy: the problem keeps the one it shares
        problem.offsets_of(x),
        _cost(stage, x0),
        _cost(stage, x),
        nfev,
        work.spent,
        converged,
        message,
        objective,
        reached,
    )


def _solve(problem, stage, x, damping, triangles, barrier, normal_equations, ftol, xtol, gtol, work):
    """One stage solved from ``x`` with the fold-over guards; a stage with a hard constraint that ends outside it is
    solved on at ``PAPER_FTOL``.  Every solve's Jacobians are counted in ``work`` (a :class:`_Work`), which ends the
    stage with :class:`_OutOfWork` when they would exceed its bound."""
    joints = problem.joints
    guard = _Guard(problem, triangles, (stage.feasible, None if joints is None else joints.sound), x)
    solve = with_barriers(problem, stage, barrier, joints, x)
    tol = stage.ftol if ftol is None else ftol
    box = problem.bounds if stage.hold is None else tuple(np.where(stage.hold, x, bound) for bound in problem.bounds)
    evaluations = 0
    while True:
        cap = work.cap(stage.max_iterations, x)
        solution = least_squares(
            solve.residuals,
            solve.jacobian,
            x,
            *box,
            accept=guard,
            gtol=gtol,
            xtol=xtol,
            ftol=tol,
            max_iterations=cap,
            damping=damping,
            normal_equations=normal_equations,
            limit=stage.limit,
        )
        x, damping, evaluations = solution.x, solution.damping, evaluations + solution.evaluations
        work.spend(solution, cap < stage.max_iterations)
        if stage.feasible is None or stage.feasible(x) or tol <= PAPER_FTOL:
            return replace(solution, evaluations=evaluations)
        tol = PAPER_FTOL


def _advance(stages, value, beside):
    """The next stage to solve, ``stages.send(value)``, the stages it carries (:attr:`~.stage.Stage.beside`) handed to
    ``beside``."""
    stage = stages.send(value)
    for later in stage.beside:
        beside.start(later)
    return stage


def _alone(problem, triangles, barrier, factorisation, tolerances):
    """``solve(stage, work=None)`` for :class:`~.beside.Beside`: ``stage`` from its own start with the initial
    damping, normal equations of its own and the fold-over guards (``barrier``, read only, shared with the other
    stages), counted in ``work`` (a :class:`_Work`; by default its own iterations bound it alone)."""

    def solve(stage, work=None):
        work = _Work(stage.max_iterations + 1) if work is None else work
        equations = NormalEquations(factorisation)
        return _solve(problem, stage, stage.start, LM_INITIAL_DAMPING, triangles, barrier, equations, *tolerances, work)

    return solve


def _kept(stages):
    """Where the work bound is reached: the end ``(x, stage)`` the objective's ``stages`` keep (their best point
    meeting its constraints; :class:`~equimesh.surface.optimize.stage.WorkSpent` thrown in until they return),
    or None if they keep none."""
    try:
        while True:  # a stage yielded instead of an end (classes after bounded's rounds) gets the bound too
            stages.throw(WorkSpent())
    except StopIteration as done:
        return done.value
    except WorkSpent:
        return None


class _OutOfWork(Exception):
    """The optimisation's Jacobians would exceed its work bound; ``x`` is where the last solve ended."""

    def __init__(self, x):
        super().__init__()
        self.x = x


class _Work:
    """The Jacobian evaluations of one optimisation, against its work bound
    (:attr:`~equimesh.surface.optimize.objectives.Objective.max_jacobians`; docs/decisions.md, "A work bound for
    the optimisation").

    A solve of ``k`` iterations counts ``k + 1`` (as the result's ``njev``), so a solve is given at most the
    iterations left; one that stops there unconverged, or one the bound leaves no iteration, would need more:
    :class:`_OutOfWork`.  A capped solve that converges ends where the uncapped one does, so a run within the bound
    keeps its bits.
    """

    def __init__(self, bound):
        self.bound, self.spent = bound, 0

    def cap(self, iterations, x):
        """The iterations the next solve (from ``x``) may take, at most its stage's ``iterations``."""
        left = self.bound - self.spent - 1
        if left < min(iterations, 1):
            raise _OutOfWork(x)
        return min(iterations, left)

    def spend(self, solution, capped):
        """Count ``solution``'s Jacobians; ``capped``: its solve was given fewer iterations than its stage's."""
        self.spent += solution.iterations + 1
        if capped and not solution.converged:
            raise _OutOfWork(solution.x)


def _start(uv, edges, lower, upper):
    """The start parameters ``uv`` (N, 2) clipped into the parameter box ``[lower, upper]`` (a remap's rounding),
    refused by name where an edge then joins two nodes at one (u, v) (a start far outside the box)."""
    uv = np.clip(uv, lower, upper)
    same = np.flatnonzero(np.all(uv[edges[:, 0]] == uv[edges[:, 1]], axis=1))
    if same.size:
        a, b = map(int, edges[same[0]])
        raise EquimeshError(
            f"edge {int(same[0])} joins nodes {a} and {b} at one point, (u, v) = {uv[a].tolist()} in the surface's "
            "parameter range"
        )
    return uv


def _finer(surface):
    """What refines ``surface``'s chart, for a refusal's advice."""
    return getattr(surface, "finer", "a finer auxiliary grid")


def _refusal(objective, surface, why):
    """The refusal of an objective that bounds the members: ``why`` no mesh with every member in [l, 2l] was found."""
    return InvalidSurfaceError(
        f"optimisation ({objective}): no mesh with every member in [l, 2l] {why}; use a smaller l, {_finer(surface)}, "
        "or optimize='paper' (which does not bound the members on the surface)"
    )


def _unsound(objective, surface, problem, x):
    """The refusal of an objective that keeps the joints sound, ending at ``x`` with an angle below its bound."""
    return InvalidSurfaceError(
        f"optimisation ({objective}): no mesh with every triangle angle at least {JOINT_ANGLE:g} degrees found, "
        f"{problem.joints.violation(x)}; use a smaller l, {_finer(surface)}, "
        "or optimize='paper' (which does not bound the angles)"
    )


def _cost(obj, x):
    r = obj.residuals(x)
    return 0.5 * inner(r, r)


class _Guard:
    """The solver's acceptance test: no fold-over in (u, v), and every reached hard constraint kept.

    :func:`~equimesh.surface.optimize.solver.least_squares` calls it only on
    cost-reducing steps and takes the step exactly when it returns True, so
    it tracks which hard constraints (a stage's ``feasible``, the sound
    joints) the current iterate meets; each one met stays met.
    """

    def __init__(self, problem, triangles, constraints, x):
        self.problem, self.triangles = problem, triangles
        self.constraints = [constraint for constraint in constraints if constraint is not None]
        self.inside = [constraint(x) for constraint in self.constraints]
        if triangles is not None:  # the triangles counter-clockwise at the start, which must stay so
            self.triangles = triangles[signed_areas(problem.uv, triangles) > 0]

    def __call__(self, x):
        if self.triangles is not None and np.any(signed_areas(self.problem.uv_of(x), self.triangles) <= 0):
            return False
        now = [constraint(x) for constraint in self.constraints]
        if any(was and not met for was, met in zip(self.inside, now)):
            return False
        self.inside = now
        return True


def fold_over_barrier(problem, triangles, fraction):
    """The fold-over barrier (:class:`~equimesh.surface.optimize.jacobian.AreaBarrier`) on the (u, v) areas of
    ``triangles``, weight 1."""
    return AreaBarrier(triangles, problem.uv, fraction, 1.0, problem.moving, power=2)


def with_barriers(problem, obj, barrier, joints, x):
    """Append the fold-over ``barrier`` (:func:`fold_over_barrier`, if any) and the joints' angle barrier
    (:meth:`~equimesh.surface.optimize.joints.Joints.barrier`, if the problem has joints) to ``obj``.

    Their weight ``w`` has ``w^2 / 2`` above the objective's cost at ``x``: a
    folded triangle, or an angle at its bound, alone costs more than the start of the solve.  Once every angle at
    ``x`` meets its bound the acceptance test keeps them all (:class:`_Guard`), so the angle barrier only has to
    show the model where the bounds are, with the weight :data:`~equimesh.tolerance.JOINT_WEIGHT`.
    """
    weight = 1.0 + 2.0 * np.sqrt(_cost(obj, x))
    terms = [(obj.residuals, obj.jacobian)]
    if barrier is not None:
        folds = barrier.weighted(weight)
        terms.append(
            (lambda y: folds.residuals(problem.uv_of(y)), lambda y: problem.chain(folds.jacobian(problem.uv_of(y)), y))
        )
    if joints is not None:
        terms.append(joints.barrier(JOINT_WEIGHT if joints.sound(x) else weight))
    if len(terms) == 1:
        return obj

    def residuals(y):
        return np.concatenate([r(y) for r, _ in terms])

    def jacobian(y):
        return scipy.sparse.vstack([j(y) for _, j in terms], format="csr")

    return Stage(residuals, jacobian, obj.description + " + barriers")
