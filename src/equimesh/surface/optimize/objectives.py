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
  reweighted (Cauchy) least squares, boundary nodes sliding, joints sound
  (:func:`bounded_stages`);
* ``"classes"`` (beyond the paper): from bounded's result, the fewest length
  classes at the fabrication tolerance (:func:`classes_stages`).
"""

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from ...mesh import G1
from ...metrics import share_within
from ...tolerance import (
    BOUNDED_BAND,
    BOUNDED_FTOL,
    BOUNDED_LOSS_TOL,
    BOUNDED_ROUND_ITERATIONS,
    BOUNDED_ROUNDS,
    BOUNDED_SCALE,
    BOUNDED_START_FTOL,
    BOUNDED_STEP,
    CLASSES_REMAP_SHARE,
)
from .class_rounds import class_key, class_rounds, class_scale, half_tolerance
from .members import Members, cauchy, edge_length_terms
from .solver import factorisation_name
from .stage import Stage, WorkSpent


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
    * sound joints (the record's ``sound_joints``): every triangle angle on the
      surface at least its bound (:mod:`~equimesh.surface.optimize.joints`), kept
      in every solve by the driver's barrier and acceptance test, the paper's
      objective below included, and a round end is kept only with them
      (:meth:`UVProblem.sound`);
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
      boundary nodes held, as the paper does, but under sound joints, to
      :data:`~equimesh.tolerance.BOUNDED_START_FTOL`: only a start; it does
      not depend on the first series, so the driver solves it beside that
      series, :attr:`Stage.beside`).  If its share
      of members within :data:`~equimesh.tolerance.BOUNDED_BAND` of l beats
      every point in [l, 2l] kept so far, the boundary nodes are released
      (the paper's objective solved on) and a second series of rounds starts
      there: it begins with the exact members the paper reaches.  On steep
      surfaces (where the paper's optimum leaves many members far outside
      [l, 2l]) the first start wins, on mild ones often the second
      (docs/decisions.md, "Two starts for bounded, and the best point kept");
    * the result is the iterate in [l, 2l] with the largest share of members
      within :data:`~equimesh.tolerance.BOUNDED_BAND` of l seen at the end of
      any round, also where the work bound ends the rounds (:class:`WorkSpent`);
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
    members = Members(problem)
    lengths, target = members.lengths, members.target
    limit = problem.step_limit(BOUNDED_STEP * l)  # every round's trust region
    inside, feasible, violation, weighted = members.inside, members.feasible, members.violation, members.weighted

    def share(ratio):
        """The share of members within ``BOUNDED_BAND`` of l (what the rounds keep the best of)."""
        return share_within(ratio, 1.0, BOUNDED_BAND)

    def cauchy_loss(ratio):
        """The loss that the rounds decrease (majorise-minimise): ``sum log(1 + (d_e / s)^2)``."""
        return float(np.sum(np.log1p(((ratio - target) / BOUNDED_SCALE) ** 2)))

    def cauchy_weight(ratio):
        return cauchy(ratio - target, BOUNDED_SCALE)

    best = {"x": None, "share": -1.0, "stage": None}

    def keep_best(x, ratio, stage):
        """Remember ``x`` (``ratio = L / l``), where ``stage``'s solve ended, if in [l, 2l] with the largest share so
        far."""
        if inside(ratio) and share(ratio) > best["share"] and problem.sound(x):
            best.update(x=np.array(x), share=share(ratio), stage=stage)

    def round_stage(k, x_start, restart):
        """Round ``k + 1`` of a series from ``x_start`` (restarted there if ``restart``), and its loss and cost
        there."""
        ratio = lengths(x_start) / l
        weight, goal = members.pulled(ratio, cauchy_weight(ratio), target)
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

    def series(x, beside=()):
        """Rounds from ``x`` until one settles in [l, 2l], stalls, or :data:`BOUNDED_ROUNDS` are done (each round's
        end offered to :func:`keep_best`); the first round carries the stages ``beside`` (:attr:`Stage.beside`)."""
        restart = False
        for k in range(BOUNDED_ROUNDS):
            stage, weight, goal, loss, cost = round_stage(k, x, restart)
            stage = replace(stage, beside=beside) if k == 0 else stage
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

    def last_stage():
        return Stage(
            *weighted(cauchy_weight(lengths(problem.x0) / l), target, members.band_penalty()),
            f"members in [l, 2l] by a penalty, Cauchy loss on L / l - {target:g}",
            BOUNDED_FTOL,
            start=problem.x0,
            feasible=feasible,
            violation=violation,
        )

    # The paper's optimum under sound joints, boundary held (as optimize="paper" holds it), then rounds from it if it
    # has the larger share: the boundary released (the paper's objective solved on) first.  It starts from the
    # remapped mesh, as the first series does: carried by the first round, the driver solves it beside that series.
    second = replace(paper_stage(problem), start=problem.x0, hold=problem.sliding_variables, ftol=BOUNDED_START_FTOL)
    try:
        yield from series(problem.x0, (second,))
        x = yield second
        if share(lengths(x) / l) > best["share"]:
            x = yield paper_stage(problem)
            yield from series(x)
    except WorkSpent:  # the work bound: the best round end in [l, 2l] so far, if any
        if best["x"] is None:
            raise
    if best["x"] is not None:
        return best["x"], best["stage"]
    stage = last_stage()
    x = yield stage
    return x, stage


def classes_stages(problem):
    """Beyond the paper: the fewest member types at the fabrication tolerance, every member in [l, 2l].

    A member type (a length class, :mod:`equimesh.classes`) is a set of
    members cut to one nominal length within ``problem.tolerance`` l; the
    paper's aim, "to reduce the different number of edge lengths", is their
    count.  The classes themselves are unknowns (after Singh and Schaefer
    2010, Fu et al. 2010: an assignment of the members to nominal lengths
    alternating with a solve towards them), merged step by step:

    * the plane is Problem 2's with its straight sides in phase with the
      lattice (:attr:`Objective.boundary`, ``"lattice"``), so the strip along
      them repeats;
    * the start is :func:`bounded_stages`' result (every member in [l, 2l],
      as many as possible at l, the joints sound); its classes are the first
      to beat;
    * a second series of rounds starts from the remapped mesh when it has
      fewer classes than that start and holds at least
      :data:`~equimesh.tolerance.CLASSES_REMAP_SHARE` of its members within
      the tolerance of l (the plane's lattice survived the remap, as on a
      developable surface, where bounded's rounds break the repeating strip);
    * after each series, its round end outside [l, 2l] with fewer classes
      than the best kept (if any) is solved on with the band penalty of
      bounded's last stage added (:meth:`~.members.Members.band_penalty`), a
      hard constraint;
    * the nominal lengths are the :data:`~equimesh.tolerance.CLASSES_START`
      largest classes of that start (``1 + BOUNDED_OFFSET``, the class at l,
      always among them), or the caller's catalogue of stock lengths
      (``problem.catalogue``, fixed);
    * a round assigns each member to its nearest nominal length, pulls it
      there with a Cauchy weight whose scale shrinks from round to round
      down to ``tolerance / 2`` in the rounds from bounded's result
      (:func:`~.class_rounds.class_scale`: first the members far from every nominal, the
      strip's, are pulled too; at the end a member far from every nominal
      stops pulling on the others), is ``tolerance / 2`` throughout in those
      from the remapped mesh, and a member outside
      ``[1 + BOUNDED_OFFSET, 2 - BOUNDED_OFFSET]`` back with
      ``BOUNDED_PULL``, for :data:`~equimesh.tolerance.BOUNDED_ROUND_ITERATIONS`
      solver iterations; then each nominal moves to the middle of the members
      within the tolerance of it, and every :data:`~equimesh.tolerance.CLASSES_MERGE_EVERY`
      rounds the nominal holding the fewest of them is dropped (its members
      go to their next nearest), for :data:`~equimesh.tolerance.CLASSES_ROUNDS` rounds;
    * the result is the round end in [l, 2l] with sound joints and the fewest
      classes (:func:`~equimesh.classes.length_classes` at the tolerance),
      then the largest share in the ten largest; with a catalogue, the fewest
      members off the catalogue first (also where the work bound ends the
      rounds, :class:`WorkSpent`).  So it never has more classes than
      :func:`bounded_stages` give with the angle guards.
    """
    members = Members(problem)
    tolerance, catalogue = problem.tolerance, problem.catalogue
    x, stage = yield from bounded_stages(problem)
    best = {"x": x, "stage": stage, "key": class_key(members.ratio(x), tolerance, catalogue)}
    starts = [(x, class_scale)]
    remapped = members.ratio(problem.x0)
    kept = share_within(remapped, 1.0, tolerance) >= CLASSES_REMAP_SHARE
    if kept and class_key(remapped, tolerance, catalogue)[:2] < best["key"][:2]:
        # the remap kept the plane's lattice (a developable surface), bounded's rounds not: its exact members stay
        starts.append((problem.x0, half_tolerance))
    for x, scale in starts:
        if (yield from class_rounds(problem, members, x, best, scale)):
            break
    return best["x"], best["stage"]


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
    sound_joints : bool
        Every triangle angle of the result on the surface is at least
        :data:`~equimesh.tolerance.JOINT_ANGLE` (:mod:`~equimesh.surface.optimize.joints`;
        the driver keeps it, the pipeline checks it on every mesh it returns).
    max_nodes : dict
        The default node limit of :func:`~equimesh.surface.pipeline.mesh_surface`
        with this objective, per factorisation of
        :data:`~equimesh.surface.optimize.solver.FACTORISATIONS`
        (docs/performance.md, "The final optimisation"); :meth:`node_limit`
        gives the one that applies.
    max_jacobians : int
        The work bound: the Jacobian evaluations of the solver (the result's ``njev``, all stages) after which
        :func:`~equimesh.surface.optimize.driver.optimize_uv` refuses the surface (docs/decisions.md, "A work bound
        for the optimisation").
    boundary : str
        Problem 2's Step 2 points for the plane this objective starts from (``boundary=`` of
        :func:`equimesh.uniform_triangulation`): the paper's "equal" parts, or "lattice", in phase with the
        lattice on straight sides along or across it (docs/decisions.md, "Boundary points in phase with the lattice").
    """

    name: str
    stages: Callable
    description: str
    slides: bool
    bounds_members: bool
    sound_joints: bool
    max_nodes: dict
    max_jacobians: int
    boundary: str = "equal"

    def node_limit(self, factorisation=None):
        """The default node limit with ``factorisation`` (by default the one the optimisation uses,
        :data:`~equimesh.surface.optimize.solver.DEFAULT_FACTORISATION`)."""
        return self.max_nodes[factorisation_name(factorisation)]


#: Every objective's record: what ``optimize=`` names.  The default node limits keep the optimisation of a default
#: run to about two minutes on a 2-core machine with each factorisation, measured by
#: ``EQUIMESH_FACTORISATION=F python experiments/optimisation_timing.py --length L --objective bounded`` on the
#: reference dome (docs/performance.md, "The final optimisation"; wall seconds of the optimisation, its second start
#: on the second core): "bounded", sound joints kept, took 33.2 and 33.9 s (PARDISO) and 41.1 s (CHOLMOD) at 32,608
#: nodes, 64.0 s and 66.4 s at 43,571, so 57,000 nodes for both (two minutes on the line through those points on a
#: log-log scale: 57,800 and 62,300); SuperLU, in its nested-dissection order
#: (:mod:`~equimesh.surface.optimize.ordering`), 62.1 s at 22,924 nodes and 106.3 s at 32,608, so 35,000 (35,300).
#: "paper" took 59.2 s with SuperLU, the slowest, at 34,031 nodes (CPU seconds of the whole call), so 34,000 with each.
_PAPER_MAX_NODES = {"pardiso": 34_000, "cholmod": 34_000, "superlu": 34_000}
_BOUNDED_MAX_NODES = {"pardiso": 57_000, "cholmod": 57_000, "superlu": 35_000}
#: "classes" (``/usr/bin/time equimesh mesh experiments/surfaces/reference_dome.json --optimize classes --max-nodes
#: none -l L``, CPU seconds, the machine shared): with PARDISO 9.0 s at 5,716 nodes (l = 1.24), 17.9 s at 11,357
#: (l = 0.88) and 56.4 s at 22,911 (l = 0.62); at 11,357 nodes 21.6 s with CHOLMOD and 50.0 s with SuperLU
#: (``EQUIMESH_FACTORISATION``), 455 Jacobians then.  A run refused by the work bound costs its 2,600 Jacobians
#: whatever it meshes, 5.7 times those 455 (``mesh_surface(...).stages.optimization.njev``): about 100 s with PARDISO
#: and 120 s with CHOLMOD at 11,357 nodes, so 12,000 nodes with both; about 285 s with SuperLU there, so 6,000 with
#: it.  With the narrowing scale of its rounds (:func:`class_scale`) l = 0.88 takes 558 Jacobians (11,367 nodes).
_CLASSES_MAX_NODES = {"pardiso": 12_000, "cholmod": 12_000, "superlu": 6_000}
#: The work bounds in Jacobian evaluations (docs/decisions.md, "A work bound for the optimisation"), measured by
#: ``python experiments/optimisation_work.py`` (results/optimisation_work.md: the reference dome at l = 0.5 to 2, the
#: examples of experiments/surfaces at two l each, the 101 domes of experiments/bounded_sweep.py, closed-ended tubes and
#: spherical caps; with PARDISO).  "paper" is one solve of at most 500 iterations (the solver's guard,
#: :attr:`Stage.max_iterations`), so 501: the bound it always had (the tubes take it all).  "bounded": at most 637 on
#: a mesh returned there (dome 87 of the sweep, 167 nodes), 626 in docs/performance.md (64,493 nodes, above its node
#: limit), so 1,500, 2.4 times the most.  "classes": at most 522 (the reference dome at l = 1, 8,795 nodes), so
#: 2,600, about five times that, which a run at its node limit spends in about two minutes
#: (``_CLASSES_MAX_NODES``).
_PAPER_MAX_JACOBIANS = 501
_BOUNDED_MAX_JACOBIANS = 1_500
_CLASSES_MAX_JACOBIANS = 2_600
OBJECTIVES = {
    objective.name: objective
    for objective in (
        Objective(
            "paper",
            paper_stages,
            "the paper's: the G1 members' relative deviation from l, boundary fixed",
            slides=False,
            bounds_members=False,
            sound_joints=False,
            max_nodes=_PAPER_MAX_NODES,
            max_jacobians=_PAPER_MAX_JACOBIANS,
        ),
        Objective(
            "bounded",
            bounded_stages,
            "every member in [l, 2l], as many as possible at l, joints sound; boundary nodes slide along the boundary",
            slides=True,
            bounds_members=True,
            sound_joints=True,
            max_nodes=_BOUNDED_MAX_NODES,
            max_jacobians=_BOUNDED_MAX_JACOBIANS,
        ),
        Objective(
            "classes",
            classes_stages,
            "the fewest member types at the fabrication tolerance, every member in [l, 2l]; boundary nodes slide",
            slides=True,
            bounds_members=True,
            sound_joints=True,
            max_nodes=_CLASSES_MAX_NODES,
            max_jacobians=_CLASSES_MAX_JACOBIANS,
            boundary="lattice",
        ),
    )
}
