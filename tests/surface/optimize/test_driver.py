"""The optimisation's driver (``surface/optimize/driver.py``): the problem it poses, how it runs the stages, its
guards and its refusals.

What must hold: the problem is the start clipped into the domain with the caller's fixed and sliding nodes, its
tolerances and catalogue (in units of l), and the joints' bounds for an objective with sound joints; a stage with a
start restarts there as a fresh solve, one with held variables keeps them, the next goes on from where the last
ended; a stage with a hard constraint that ends outside it is solved on, and an end outside it, or with an angle
below its bound, is refused in the surface's terms; no step folds a triangle that was counter-clockwise at the
start, nor leaves a hard constraint it met; a surface that is not finite at a trial point is refused.  Mostly on
the tiny grids of ``optimize_cases``, with objectives of a few stages made for the test.
"""

import threading
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse
from optimize_cases import RIM, finite_difference, grid, moved, patch, problem
from surface_cases import Wrapped, plane_patch

import equimesh
from equimesh import EquimeshError, InvalidSurfaceError
from equimesh.surface.charts.chart import Domain
from equimesh.surface.optimize import OBJECTIVES, Objective, Stage, driver, joints, optimize_uv
from equimesh.surface.optimize.beside import Beside, Stopped
from equimesh.surface.optimize.driver import fold_over_barrier, with_barriers
from equimesh.surface.optimize.jacobian import signed_areas
from equimesh.surface.optimize.joints import Joints, joint_bounds, surface_angles
from equimesh.surface.optimize.objectives import paper_stage
from equimesh.surface.optimize.problem import free_nodes
from equimesh.surface.optimize.slide import along_polygon
from equimesh.surface.optimize.solver import FACTORISATIONS
from equimesh.surface.optimize.stage import WorkSpent
from equimesh.tolerance import JOINT_MARGIN as MARGIN
from equimesh.tolerance import JOINT_WEIGHT, PAPER_FTOL

UV, TRIANGLES, EDGES, GROUPS = grid()
FIXED = np.arange(RIM)


def record(monkeypatch, name, stages, slides=False, bounds_members=False, sound_joints=False, max_jacobians=1000):
    """An objective record of ``stages(problem)`` under ``name`` for the test."""
    record = Objective(
        name, stages, name, slides, bounds_members, sound_joints, dict.fromkeys(FACTORISATIONS, 100), max_jacobians
    )
    monkeypatch.setitem(OBJECTIVES, name, record)


def run(objective="paper", surface=None, uv=UV, **kw):
    kw.setdefault("fixed", FIXED)
    surface = patch() if surface is None else surface
    return optimize_uv(surface, uv, EDGES, GROUPS, 8.0, triangles=TRIANGLES, objective=objective, **kw)


def stages_of(*make):
    """Stages ``make[0](problem), make[1](problem), ...`` in turn; the last one's end is the result."""

    def stages(problem):
        x = stage = None
        for m in make:
            stage = m(problem)
            x = yield stage
        return x, stage

    return stages


def papers(**fields):
    """The paper's stage with ``fields`` replaced (``start="x0"``: the problem's start)."""

    def make(problem):
        if isinstance(fields.get("start"), str):
            return replace(paper_stage(problem), **{**fields, "start": problem.x0})
        return replace(paper_stage(problem), **fields)

    return make


def test_nan_during_the_optimisation_is_refused():
    surface = plane_patch()
    holed = Wrapped(surface, lambda u, v: (u > 0.4) & (u < 0.6))
    uv = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, 0.5]])
    with pytest.raises(InvalidSurfaceError, match="not finite"):
        equimesh.optimize_uv(holed, uv, [[0, 1], [1, 2], [0, 2]], [1, 1, 1], 3.0, fixed=[0, 1])


def test_an_unknown_objective_or_factorisation_is_named():
    with pytest.raises(EquimeshError, match=r"unknown objective 'nope'; choose from \['bounded', 'classes', 'paper'\]"):
        run(objective="nope")
    with pytest.raises(EquimeshError, match=r"unknown objective \['paper'\]"):
        run(objective=["paper"])
    with pytest.raises(EquimeshError, match="unknown factorisation 'nope'"):
        run(factorisation="nope")


BAD_CALLS = {
    "a length that is no number": ({"length": float("nan")}, "target length l must be positive and finite, got nan"),
    "a length of zero": ({"length": 0.0}, "target length l must be positive and finite, got 0.0"),
    "uv of three columns": ({"uv": np.zeros((len(UV), 3))}, r"uv must be an \(N, 2\) array, got shape \(16, 3\)"),
    "a (u, v) not finite": ({"uv": np.where(np.arange(len(UV))[:, None] == 3, np.nan, UV)}, r"node 3 is not finite"),
    "every node far outside the range": ({"uv": UV + 5.0}, r"edge 0 joins nodes \d+ and \d+ at one point"),
    "an edge to no node": ({"edges": [[0, 1], [0, 16]]}, r"edge 1 refers to a node outside 0 \.\. 15: \[0, 16\]"),
    "an edge to node -1": ({"edges": [[0, -1]]}, r"edge 0 refers to a node outside 0 \.\. 15"),
    "an edge of fractions": ({"edges": EDGES + 0.5}, r"edges must be an \(M, 2\) array of node indices"),
    "fewer labels than edges": ({"groups": GROUPS[:3]}, r"edge_groups must hold one label per edge \(\d+\)"),
    "a fixed node that is none": ({"fixed": [0, 16]}, r"entry 1 of fixed refers to a node outside 0 \.\. 15"),
    "a mask of fixed nodes too short": ({"fixed": np.ones(3, dtype=bool)}, r"one entry per node \(16\)"),
    "a triangle to no node": ({"triangles": [[0, 1, 16]]}, r"triangle 0 refers to a node outside 0 \.\. 15"),
    "a triangle of fractions": ({"triangles": TRIANGLES + 0.5}, r"^triangles must be an \(M, 3\) array of node ind"),
    "a fixed node of a fraction": ({"fixed": [0.5]}, r"^fixed must be an \(M, 1\) array of node indices"),
}


@pytest.mark.parametrize("case", BAD_CALLS)
def test_bad_arguments_are_refused_by_name(case):
    """A public verb's arguments are checked before any work: each fault is an error of equimesh's naming it (a
    length of nan once made the solver damp forever, an edge to no node was an IndexError deep inside)."""
    given, message = BAD_CALLS[case]
    args = {"uv": UV, "edges": EDGES, "groups": GROUPS, "length": 8.0, "fixed": FIXED, "triangles": TRIANGLES}
    args.update(given)
    with pytest.raises(EquimeshError, match=message):
        optimize_uv(
            patch(),
            args["uv"],
            args["edges"],
            args["groups"],
            args["length"],
            fixed=args["fixed"],
            triangles=args["triangles"],
        )


def test_a_start_clipped_onto_one_point_names_its_first_collapsed_edge():
    """Both nodes of one edge beyond the corner (1, 1): clipped, they meet there; that edge, and no other, is named."""
    k = len(EDGES) - 1
    uv = UV.copy()
    uv[EDGES[k]] = [5.0, 5.0]
    clipped = np.clip(uv, 0.0, 1.0)
    first = int(np.flatnonzero(np.all(clipped[EDGES[:, 0]] == clipped[EDGES[:, 1]], axis=1))[0])
    a, b = EDGES[first]
    at = r"at one point, \(u, v\) = \[1\.0, 1\.0\] in the surface's parameter range$"
    message = rf"^edge {first} joins nodes {a} and {b} {at}"
    with pytest.raises(EquimeshError, match=message):
        optimize_uv(patch(), uv, EDGES, GROUPS, 8.0, fixed=FIXED)


def test_a_mask_of_fixed_nodes_is_the_nodes_it_marks():
    mask = np.zeros(len(UV), dtype=bool)
    mask[FIXED] = True
    assert np.array_equal(run(fixed=mask).uv, run().uv)


def test_a_start_with_no_node_free_is_held_to_the_band(monkeypatch):
    """Every node fixed under an objective that bounds the members: refused as any end outside [l, 2l] is when a
    member is out, returned as it is when none is."""

    def idle(problem):
        return Stage(lambda x: np.zeros(1), lambda x: scipy.sparse.csr_matrix((1, len(x))), max_iterations=0)

    record(monkeypatch, "held", stages_of(idle), bounds_members=True)
    ends = patch().evaluate(*UV[EDGES].reshape(-1, 2).T).reshape(-1, 2, 3)
    lengths = np.linalg.norm(ends[:, 1] - ends[:, 0], axis=1)
    assert lengths.max() < 1.98 * lengths.min()  # some l puts every member of the grid in [l, 2l]
    everything = np.arange(len(UV))
    inside = optimize_uv(Finer(), UV, EDGES, GROUPS, lengths.min() / 1.01, fixed=everything, objective="held")
    assert inside.message == "no free nodes" and np.array_equal(inside.uv, UV)
    with pytest.raises(InvalidSurfaceError) as refused:
        optimize_uv(Finer(), UV, EDGES, GROUPS, lengths.max(), fixed=everything, objective="held")
    text = str(refused.value)
    assert text.startswith("optimisation (held): no mesh with every member in [l, 2l] found, no node free to move, ")
    assert f" of {len(EDGES)} members outside [l, 2l] (lengths from " in text
    assert text.endswith(", a finer control net, or optimize='paper' (which does not bound the members on the surface)")


def test_without_free_nodes_nothing_moves():
    """Every node fixed: the start, clipped into the domain, with the first stage's cost at it."""
    uv = UV.copy()
    uv[0] = [-0.01, 0.0]
    result = run(uv=uv, fixed=np.arange(len(UV)))
    np.testing.assert_array_equal(result.uv, UV)
    np.testing.assert_array_equal(result.offsets, np.zeros(len(UV)))
    p, _ = problem()
    p = replace(p, free=np.zeros(len(UV), dtype=bool))
    cost = 0.5 * float(np.sum(paper_stage(p).residuals(np.zeros(0)) ** 2))
    assert result.cost_before == result.cost_after == pytest.approx(cost, rel=1e-12) and cost > 0
    assert (result.nfev, result.njev, result.converged, result.message) == (0, 0, True, "no free nodes")
    assert result.objective == "paper"


def test_the_papers_run_on_the_tiny_grid():
    """The fixed nodes keep their (clipped) start; the costs are the paper stage's at the start and at the end."""
    uv = UV.copy()
    uv[0] = [-0.01, 0.0]
    result = run(uv=uv)
    np.testing.assert_array_equal(result.uv[:RIM], UV[:RIM])
    p, _ = problem()
    stage = paper_stage(p)
    x = result.uv[RIM:].ravel()
    assert result.cost_before == pytest.approx(0.5 * float(np.sum(stage.residuals(p.x0) ** 2)), rel=1e-12)
    assert result.cost_after == pytest.approx(0.5 * float(np.sum(stage.residuals(x) ** 2)), rel=1e-12)
    assert result.cost_after < result.cost_before and result.converged and result.nfev >= result.njev > 0
    assert result.message == "relative reduction below ftol" and result.objective == "paper"
    np.testing.assert_array_equal(result.offsets, np.zeros(len(UV)))


def test_nodes_off_the_surface_within_the_tolerance():
    result = run(surface_tolerance=0.5)
    assert result.offsets.shape == (len(UV),) and not np.any(result.offsets[:RIM])
    assert np.all(np.abs(result.offsets) <= 0.5) and np.any(result.offsets[RIM:])


class Wide:
    """:func:`patch` on the parameter rectangle [0, 2] x [0, 1]."""

    domain = Domain(u=(0.0, 2.0), v=(0.0, 1.0))

    def __init__(self):
        self.chart = patch()

    def evaluate(self, u, v):
        return self.chart.evaluate(np.asarray(u) / 2.0, v)

    def derivatives(self, u, v):
        su, sv = self.chart.derivatives(np.asarray(u) / 2.0, v)
        return su / 2.0, sv


def test_the_start_is_clipped_into_the_charts_domain():
    """On [0, 2] x [0, 1]: a node at u = 1.5 stays, one at u = 2.01 is clipped to 2."""
    uv = UV * [2.0, 1.0]
    uv[3] = [2.01, 0.0]
    result = optimize_uv(Wide(), uv, EDGES, GROUPS, 8.0, fixed=np.arange(len(UV)))
    expected = UV * [2.0, 1.0]
    np.testing.assert_array_equal(result.uv, expected)
    assert result.uv[13, 0] == 4.0 / 3.0


def test_the_problem_posed(monkeypatch):
    """What an objective's stages see: the start clipped, the caller's nodes, tolerances and catalogue (in units of
    l), and the joints' bounds at the start with an objective with sound joints and triangles."""
    seen = []

    def capture(problem):
        seen.append(problem)
        return paper_stage(problem)

    record(monkeypatch, "capture", stages_of(capture))
    record(monkeypatch, "sound", stages_of(capture), sound_joints=True)
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    slide, corners = along_polygon(np.arange(RIM), square, UV[:RIM])
    uv = UV.copy()
    uv[0] = [-0.01, 1e-9]
    kw = dict(fixed=corners, slides=[slide], surface_tolerance=0.25, tolerance=0.01, catalogue=[10.0, 12.0])
    run("capture", uv=uv, **kw)
    (p,) = seen
    np.testing.assert_array_equal(p.uv, np.clip(uv, 0.0, 1.0))
    assert p.edges.dtype == np.int64 and np.array_equal(p.edges, EDGES) and np.array_equal(p.edge_groups, GROUPS)
    assert p.length == 8.0 and len(p.slides) == 1 and p.slides[0] is slide and p.joints is None
    np.testing.assert_array_equal(p.free, free_nodes(len(UV), corners, [slide]))
    assert (p.surface_tolerance, p.tolerance) == (0.25, 0.01)
    np.testing.assert_array_equal(p.catalogue, [1.25, 1.5])
    run("sound")
    bounds = joint_bounds(patch(), UV, TRIANGLES)
    assert seen[1].catalogue is None and isinstance(seen[1].joints, Joints)
    np.testing.assert_array_equal(seen[1].joints.bounds, bounds)
    optimize_uv(patch(), UV, EDGES, GROUPS, 8.0, fixed=FIXED, objective="sound")
    assert seen[2].joints is None  # no triangles, no joints


def test_a_stage_with_a_start_is_a_fresh_solve(monkeypatch):
    """A few iterations of the paper's stage, then the paper's stage restarted at the start (with the initial
    damping): the same result as the restarted stage alone."""
    record(monkeypatch, "restart", stages_of(papers(max_iterations=2), papers(start="x0")))
    record(monkeypatch, "alone", stages_of(papers(start="x0")))
    restarted, alone = run("restart"), run("alone")
    np.testing.assert_array_equal(restarted.uv, alone.uv)
    assert restarted.nfev > alone.nfev and restarted.njev > alone.njev


def test_a_stage_holding_some_variables_keeps_those(monkeypatch):
    """The paper's stage with node 12's two variables held: node 12 stays, the others move."""

    def hold_first(problem):
        hold = np.zeros(len(problem.x0), dtype=bool)
        hold[:2] = True
        return replace(paper_stage(problem), hold=hold)

    record(monkeypatch, "some", stages_of(hold_first))
    result = run("some")
    np.testing.assert_array_equal(result.uv[RIM], UV[RIM])
    assert np.all(np.any(result.uv[RIM + 1 :] != UV[RIM + 1 :], axis=1))


def test_a_stage_holding_every_variable_keeps_them(monkeypatch):
    """Two iterations, then a stage with every variable held: the end of the two iterations."""

    def hold_all(problem):
        return replace(paper_stage(problem), hold=np.ones(len(problem.x0), dtype=bool))

    record(monkeypatch, "held", stages_of(papers(max_iterations=2), hold_all))
    record(monkeypatch, "two", stages_of(papers(max_iterations=2)))
    np.testing.assert_array_equal(run("held").uv, run("two").uv)


def test_a_stage_goes_on_from_the_last_end(monkeypatch):
    """Two iterations, then the paper's stage on: it ends where the paper's stage alone ends, up to its tolerance,
    but not at the two iterations' end."""
    record(monkeypatch, "on", stages_of(papers(max_iterations=2), papers()))
    record(monkeypatch, "two", stages_of(papers(max_iterations=2)))
    on, two, alone = run("on"), run("two"), run()
    assert on.cost_after < two.cost_after and on.cost_after == pytest.approx(alone.cost_after, rel=1e-6)


def test_the_damping_and_the_analysis_carry_over(monkeypatch):
    """Two stages share one analysis of the normal equations (one factorisation object built for their one
    pattern), and the second goes on with the first's damping: restarted at the first's end with the initial
    damping, it takes another path."""
    built = []
    real = FACTORISATIONS["superlu"]

    def counting(*args):
        built.append(args)
        return real(*args)

    monkeypatch.setitem(FACTORISATIONS, "superlu", counting)
    record(monkeypatch, "on", stages_of(papers(max_iterations=2), papers()))
    warm = run("on", factorisation="superlu")
    assert len(built) == 1
    record(monkeypatch, "two", stages_of(papers(max_iterations=2)))
    two = run("two", factorisation="superlu")
    end = two.uv[RIM:].ravel()
    record(monkeypatch, "cold", stages_of(papers(max_iterations=2), papers(start=end)))
    assert not np.array_equal(run("cold", factorisation="superlu").uv, warm.uv)


def test_a_stage_with_no_iterations_evaluates_once(monkeypatch):
    """No iterations: one evaluation of the residuals and one of the Jacobian, at the start; solved on (its
    constraint unmet, the stage's tolerance loose), two of each."""
    record(monkeypatch, "none", stages_of(papers(max_iterations=0)))
    result = run("none")
    assert (result.nfev, result.njev) == (1, 1)
    np.testing.assert_array_equal(result.uv, UV)
    calls = []

    def met_late(x):
        calls.append(x)
        return len(calls) > 2  # the guard's start and the first solve's end: unmet; then met

    record(monkeypatch, "late", stages_of(papers(max_iterations=0, ftol=0.5, feasible=met_late, violation=str)))
    result = run("late")
    assert (result.nfev, result.njev) == (2, 2)


def test_the_callers_tolerances_and_the_stages_limit_are_the_solvers(monkeypatch):
    """A loose gtol or xtol stops the solve by that test; a limit that takes every step to zero keeps the start."""
    assert run(gtol=1.0).message == "projected gradient below gtol"
    assert "step below xtol" in run(xtol=0.5).message
    record(monkeypatch, "still", stages_of(papers(limit=lambda d: 0.0 * d)))
    np.testing.assert_array_equal(run("still").uv, UV)


def test_the_callers_ftol_replaces_the_stages(monkeypatch):
    record(monkeypatch, "loose", stages_of(papers(ftol=0.5)))
    loose, tight = run("loose"), run()
    assert loose.nfev < tight.nfev and loose.cost_after > tight.cost_after
    np.testing.assert_array_equal(run("loose", ftol=PAPER_FTOL).uv, tight.uv)


def test_a_stage_ending_outside_its_constraint_is_solved_on(monkeypatch):
    """A loose stage whose constraint (a cost near the optimum's) only the paper's tolerance reaches: solved on,
    it is met."""
    best = run().cost_after

    def constrained(problem):
        stage = paper_stage(problem)

        def near(x):
            return 0.5 * float(np.sum(stage.residuals(x) ** 2)) <= best * (1 + 2e-7)

        return replace(stage, ftol=0.5, feasible=near, violation=lambda x: "too far")

    record(monkeypatch, "near", stages_of(constrained))
    record(monkeypatch, "loose", stages_of(papers(ftol=0.5)))
    assert run("loose").cost_after > best * (1 + 2e-7)
    assert run("near").cost_after <= best * (1 + 2e-7)


class Finer:
    """:func:`patch` (or ``chart``) that names what refines it."""

    finer = "a finer control net"

    def __init__(self, chart=None):
        self.chart = patch() if chart is None else chart
        self.evaluate, self.derivatives = self.chart.evaluate, self.chart.derivatives
        self.second_derivatives = self.chart.second_derivatives


def test_an_end_outside_the_constraint_is_refused(monkeypatch):
    record(monkeypatch, "never", stages_of(papers(feasible=lambda x: False, violation=lambda x: f"{len(x)} fit")))
    message = (
        "optimisation (never): no mesh with every member in [l, 2l] found, 8 fit; use a smaller l, {}, or "
        "optimize='paper' (which does not bound the members on the surface)"
    )
    with pytest.raises(InvalidSurfaceError) as refused:
        run("never")
    assert str(refused.value) == message.format("a finer auxiliary grid")
    with pytest.raises(InvalidSurfaceError) as refused:
        run("never", surface=Finer())
    assert str(refused.value) == message.format("a finer control net")


def test_bounds_out_of_reach_are_refused(monkeypatch):
    """The joints' check fires: an objective with sound joints whose stages end with an angle below its bound is
    refused in the surface's terms, naming the angles; so is such a start where no node is free to move."""

    def idle(problem):
        return Stage(lambda x: np.zeros(1), lambda x: scipy.sparse.csr_matrix((1, len(x))), max_iterations=0)

    record(monkeypatch, "idle", stages_of(idle), sound_joints=True)
    monkeypatch.setattr(joints, "JOINT_ANGLE", 59.0)  # the grid's triangles have angles of about 45 degrees
    with pytest.raises(InvalidSurfaceError) as refused:
        run("idle", surface=Finer())
    text = str(refused.value)
    assert text.startswith("optimisation (idle): no mesh with every triangle angle at least 30 degrees found, 18 of")
    assert "below 59 degrees" in text
    assert text.endswith(
        "; use a smaller l, a finer control net, or optimize='paper' (which does not bound the angles)"
    )
    with pytest.raises(InvalidSurfaceError, match=r"use a smaller l, a finer auxiliary grid, or optimize='paper'"):
        run("idle")
    with pytest.raises(InvalidSurfaceError) as refused:
        run("idle", surface=Finer(), fixed=np.arange(len(UV)))  # no node free to move: the start is the end, held
    assert str(refused.value) == text


def test_the_joints_are_kept_in_a_stage_that_keeps_them(monkeypatch):
    """Bounds a little below the start's smallest angle and node 12 pulled towards node 13: without sound joints
    its angles go far below them; with them the stage ends sound, the barrier holding every angle a part of its
    margin above its bound."""
    start = surface_angles(patch().evaluate(*UV.T), TRIANGLES).min()
    monkeypatch.setattr(joints, "JOINT_ANGLE", float(np.degrees(start)) - 0.5)
    bound = start - np.radians(0.5)
    record(monkeypatch, "free", stages_of(pulling(RIM, 0.9)))
    assert surface_angles(patch().evaluate(*run("free").uv.T), TRIANGLES).min() < bound - np.radians(5.0)
    record(monkeypatch, "kept", stages_of(pulling(RIM, 0.9)), sound_joints=True)
    kept = run("kept")
    assert surface_angles(patch().evaluate(*kept.uv.T), TRIANGLES).min() >= bound + 0.25 * joints.JOINT_MARGIN


def test_a_pull_stronger_than_the_angle_barrier_is_held_by_the_acceptance_test(monkeypatch):
    """Node 12 pulled towards node 13 a hundred times harder: the pull outweighs the angle barrier, and the acceptance
    test alone ends the stage sound, its smallest angle at its bound."""
    start = surface_angles(patch().evaluate(*UV.T), TRIANGLES).min()
    monkeypatch.setattr(joints, "JOINT_ANGLE", float(np.degrees(start)) - 0.5)
    bound = start - np.radians(0.5)
    record(monkeypatch, "hard", stages_of(pulling(RIM, 0.9, weight=1000.0)), sound_joints=True)
    smallest = surface_angles(patch().evaluate(*run("hard").uv.T), TRIANGLES).min()
    assert bound <= smallest < bound + 0.25 * joints.JOINT_MARGIN


def pulling(node, target, weight=10.0, axis=0):
    """A stage pulling the free ``node``'s u (``axis`` 0, variable ``2 (node - RIM)``) or v (1) to ``target``."""

    def make(problem):
        k = 2 * (node - RIM) + axis

        def residuals(x):
            return np.array([weight * (x[k] - target)])

        def jacobian(x):
            return scipy.sparse.csr_matrix(([weight], ([0], [k])), shape=(1, len(x)))

        return Stage(residuals, jacobian, "pull")

    return make


@pytest.mark.parametrize("area_floor", [0.0, 0.5], ids=["acceptance only", "with the barrier"])
def test_no_step_folds_a_triangle(monkeypatch, area_floor):
    """Node 12 pulled across its neighbours (to u = 0.9, beyond node 13 at 2/3): every triangle counter-clockwise
    at the start stays so, by the acceptance test alone or with the barrier."""
    record(monkeypatch, "pull", stages_of(pulling(RIM, 0.9)))
    result = run("pull", area_floor=area_floor)
    assert np.all(signed_areas(result.uv, TRIANGLES) > 0) and result.uv[RIM, 0] > UV[RIM, 0]
    free = optimize_uv(patch(), UV, EDGES, GROUPS, 8.0, fixed=FIXED, objective="pull")  # no triangles, no guards
    assert free.uv[RIM, 0] == pytest.approx(0.9)


def test_a_stage_solved_beside_keeps_the_acceptance_test(monkeypatch):
    """Node 12 pulled across its neighbours by a stage solved beside the first (its own start, no barrier): the
    acceptance test keeps every triangle counter-clockwise there too, and node 12 moves."""

    def stages(problem):
        pull = replace(pulling(RIM, 0.9)(problem), start=problem.x0)
        yield replace(paper_stage(problem), max_iterations=2, beside=(pull,))
        return (yield pull), pull

    record(monkeypatch, "pull beside", stages)
    result = run("pull beside", area_floor=0.0)
    assert np.all(signed_areas(result.uv, TRIANGLES) > 0) and result.uv[RIM, 0] > UV[RIM, 0]


def test_the_barrier_holds_a_squeezed_triangle_back(monkeypatch):
    """Node 12 pulled towards node 13: the acceptance test alone lets a triangle shrink to almost nothing; the
    barrier (floor 0.5 or 0.9 of the start areas) keeps the smallest larger, the higher floor the more."""
    record(monkeypatch, "pull", stages_of(pulling(RIM, 0.9)))
    start = signed_areas(UV, TRIANGLES)
    smallest = [(signed_areas(run("pull", area_floor=f).uv, TRIANGLES) / start).min() for f in (0.0, 0.5, 0.9)]
    assert smallest[0] < 1e-3 < smallest[1] < smallest[2]


def test_a_triangle_flat_at_the_start_is_not_guarded(monkeypatch):
    """A triangle of three rim nodes on a side (zero area) added: the guard ignores it, and node 12 still moves."""
    record(monkeypatch, "pull", stages_of(pulling(RIM, 0.5)))
    triangles = np.vstack([TRIANGLES, [[0, 1, 2]]])
    result = optimize_uv(patch(), UV, EDGES, GROUPS, 8.0, fixed=FIXED, triangles=triangles, objective="pull")
    assert result.uv[RIM, 0] > UV[RIM, 0] + 0.05


def test_a_step_that_flattens_a_triangle_is_refused(monkeypatch):
    """Node 12 pulled below the square (v = -1): its steps are clipped onto v = 0, the side through nodes 0 and
    1, which flattens the triangle (0, 1, 12) to area 0 exactly; the acceptance test refuses that as a fold."""
    record(monkeypatch, "down", stages_of(pulling(RIM, -1.0, axis=1)))
    result = run("down", area_floor=0.0)
    assert np.all(signed_areas(result.uv, TRIANGLES) > 0) and 0.0 < result.uv[RIM, 1] < UV[RIM, 1]


def test_a_triangle_clockwise_at_the_start_is_not_guarded(monkeypatch):
    """One of node 12's triangles given clockwise: the guard ignores it, and node 12 still moves."""
    record(monkeypatch, "pull", stages_of(pulling(RIM, 0.5)))
    triangles = TRIANGLES.copy()
    touching = np.flatnonzero(np.any(triangles == RIM, axis=1))[0]
    triangles[touching] = triangles[touching, ::-1]
    result = optimize_uv(patch(), UV, EDGES, GROUPS, 8.0, fixed=FIXED, triangles=triangles, objective="pull")
    assert result.uv[RIM, 0] > UV[RIM, 0] + 0.05


def test_a_constraint_met_stays_met(monkeypatch):
    """Node 12 pulled to u = 0.6 under the constraint u <= 0.45, met at the start: every step keeps it."""

    def constrained(problem):
        return replace(pulling(RIM, 0.6)(problem), feasible=lambda x: x[0] <= 0.45, violation=lambda x: "")

    record(monkeypatch, "kept", stages_of(constrained))
    result = run("kept", area_floor=0.0)
    assert UV[RIM, 0] + 0.05 < result.uv[RIM, 0] <= 0.45


def test_the_barriers_are_appended_with_a_weight_above_the_cost():
    """The fold-over and the angle barriers after the stage's residuals, each of weight ``1 + 2 sqrt(cost)``;
    without them the stage itself."""
    p, triangles = problem(seed=1)
    stage = paper_stage(p)
    x = p.x0
    weight = 1.0 + 2.0 * np.sqrt(0.5 * float(np.sum(stage.residuals(x) ** 2)))
    assert with_barriers(p, stage, None, None, x) is stage
    folds = fold_over_barrier(p, triangles, 0.9)
    angles = Joints(p, triangles, np.full(triangles.shape, np.radians(44.5)))
    both = with_barriers(p, stage, folds, angles, x)
    assert both.description == stage.description + " + barriers"
    y = moved(p, 2, size=0.05)  # some triangles squeezed below 0.9 of their area, some angles near 44.5 degrees
    expected = np.concatenate(
        [stage.residuals(y), folds.weighted(weight).residuals(p.uv_of(y)), angles.barrier(weight)[0](y)]
    )
    assert np.count_nonzero(expected[len(stage.residuals(y)) : len(stage.residuals(y)) + 18]) > 0
    assert np.count_nonzero(expected[len(stage.residuals(y)) + 18 :]) > 0
    np.testing.assert_allclose(both.residuals(y), expected, rtol=1e-12)
    np.testing.assert_allclose(both.jacobian(y).toarray(), finite_difference(both.residuals, y), atol=1e-5)
    only_folds = with_barriers(p, stage, folds, None, x)
    np.testing.assert_allclose(only_folds.residuals(y), expected[: len(stage.residuals(y)) + 18], rtol=1e-12)


def test_the_angle_barrier_weighs_joint_weight_once_every_angle_meets_its_bound():
    """Where the acceptance test already keeps every angle at its bound, the angle barrier only shows the model the
    bounds (weight ``JOINT_WEIGHT``); one angle below its bound gives it the fold-over barrier's weight again."""
    p, triangles = problem(seed=1)
    stage, x = paper_stage(p), p.x0
    weight = 1.0 + 2.0 * np.sqrt(0.5 * float(np.sum(stage.residuals(x) ** 2)))
    angles = surface_angles(p.points_of(x), triangles)
    n = len(stage.residuals(x))
    sound = Joints(p, triangles, angles - 0.5 * MARGIN)  # every angle half a margin above its bound: all active
    tail = with_barriers(p, stage, None, sound, x).residuals(x)[n:]
    np.testing.assert_allclose(tail, sound.barrier(JOINT_WEIGHT)[0](x), rtol=1e-14)
    assert JOINT_WEIGHT < weight and np.all(tail > 0)
    bounds = angles - 0.5 * MARGIN
    bounds[3, 1] = np.nextafter(angles[3, 1], np.inf)  # one angle a rounding below its bound
    unsound = Joints(p, triangles, bounds)
    tail = with_barriers(p, stage, None, unsound, x).residuals(x)[n:]
    np.testing.assert_allclose(tail, unsound.barrier(weight)[0](x), rtol=1e-14)


def test_the_fold_over_barrier_by_hand():
    """``(1 - A / (f A0))^2`` per triangle of weight 1: zero at the start, 1 for a triangle folded flat."""
    p, triangles = problem(rise=0.0)
    barrier = fold_over_barrier(p, triangles, 0.5)
    assert not np.any(barrier.residuals(p.uv))
    uv = p.uv.copy()
    uv[RIM] = uv[RIM - 1] + 0.25 * (uv[RIM] - uv[RIM - 1])  # node 12 towards node 11: its triangles shrink
    areas, start = signed_areas(uv, triangles), signed_areas(p.uv, triangles)
    expected = np.maximum(0.0, 1.0 - areas / (0.5 * start)) ** 2
    assert np.count_nonzero(expected) == 2 and np.all(expected < 1.0)
    np.testing.assert_allclose(barrier.residuals(uv), expected, atol=1e-15)


@pytest.mark.parametrize("bounds_members", [False, True])
def test_a_run_within_its_work_bound_keeps_its_bits_and_one_beyond_is_refused(monkeypatch, bounds_members):
    """The paper's stage takes some Jacobians on the tiny grid: with exactly that bound the same result, bit for bit;
    with one fewer the solve is cut short and the surface refused, in the terms of the objective."""
    record(monkeypatch, "free", stages_of(papers()), bounds_members=bounds_members)
    free = run("free")
    record(monkeypatch, "exact", stages_of(papers()), bounds_members=bounds_members, max_jacobians=free.njev)
    exact = run("exact")
    assert exact.uv.tobytes() == free.uv.tobytes() and exact.njev == free.njev
    record(monkeypatch, "short", stages_of(papers()), bounds_members=bounds_members, max_jacobians=free.njev - 1)
    with pytest.raises(InvalidSurfaceError) as refused:
        run("short", surface=Finer())
    within = f"within {free.njev - 1} Jacobian evaluations (its work bound)"
    if bounds_members:
        assert str(refused.value).startswith(
            f"optimisation (short): no mesh with every member in [l, 2l] found {within}, "
        )
        assert " members outside [l, 2l] (lengths from " in str(refused.value)
        assert str(refused.value).endswith(
            "; use a smaller l, a finer control net, or optimize='paper' (which does not "
            "bound the members on the surface)"
        )
    else:
        assert (
            str(refused.value) == f"optimisation (short): not converged {within}; use a larger l or a finer control net"
        )


def test_a_bound_leaving_no_iteration_refuses_before_the_first_solve(monkeypatch):
    """A bound of one Jacobian leaves a solve no iteration: refused before it starts."""
    record(monkeypatch, "none", stages_of(papers()), max_jacobians=1)
    with pytest.raises(
        InvalidSurfaceError, match=r"^optimisation \(none\): not converged within 1 Jacobian evaluations"
    ):
        run("none")
    record(monkeypatch, "two", stages_of(papers()), max_jacobians=2)
    with pytest.raises(InvalidSurfaceError, match=r"not converged within 2 Jacobian evaluations"):
        run("two")
    # An objective that bounds the members says where the start is: the remapped mesh's members.
    record(monkeypatch, "bounded one", stages_of(papers()), bounds_members=True, max_jacobians=1)
    with pytest.raises(InvalidSurfaceError) as refused:
        run("bounded one")
    found = "found within 1 Jacobian evaluations (its work bound), "
    assert found in str(refused.value) and " members outside [l, 2l] (lengths from " in str(refused.value)


def test_a_start_out_of_reach_is_refused_before_any_work(monkeypatch):
    """At l = 21 the tiny flat grid's sides are 0.476 l: more than half the members shorter than l/2, so an objective
    that bounds the members refuses at once, saying how far they are; one that does not runs."""
    record(monkeypatch, "reach", stages_of(papers()), bounds_members=True)
    flat = plane_patch()
    with pytest.raises(InvalidSurfaceError) as refused:
        optimize_uv(flat, UV, EDGES, GROUPS, 21.0, triangles=TRIANGLES, objective="reach", fixed=FIXED)
    assert str(refused.value).startswith(
        "optimisation (reach): no mesh with every member in [l, 2l] within reach of the remapped mesh: "
    )
    assert "members shorter than 0.5 l on the surface (the flattening stretched it)" in str(refused.value)
    assert str(refused.value).endswith(
        "; use a smaller l, a finer auxiliary grid, or optimize='paper' "
        "(which does not bound the members on the surface)"
    )
    with pytest.raises(InvalidSurfaceError, match=r"; use a smaller l, a finer control net, or optimize='paper'"):
        optimize_uv(Finer(flat), UV, EDGES, GROUPS, 21.0, triangles=TRIANGLES, objective="reach", fixed=FIXED)
    record(monkeypatch, "free", stages_of(papers()))
    assert optimize_uv(flat, UV, EDGES, GROUPS, 21.0, triangles=TRIANGLES, objective="free", fixed=FIXED).njev > 0


def test_the_work_bound_gives_each_solve_the_iterations_left():
    """A solve of k iterations spends k + 1 Jacobians: of a bound of 10, a first solve may take 9 iterations; after
    5 spent, 4 (or its stage's fewer); after 8, one; after 9 none, and the bound ends the optimisation where the
    last solve ended."""
    work, x = driver._Work(10), np.zeros(2)
    assert work.cap(100, x) == 9 and work.cap(3, x) == 3 and work.cap(0, x) == 0
    work.spent = 5
    assert work.cap(100, x) == 4 and work.cap(3, x) == 3
    work.spent = 8
    assert work.cap(100, x) == 1
    work.spent = 9
    with pytest.raises(driver._OutOfWork) as spent:
        work.cap(100, x)
    assert spent.value.x is x


def test_the_work_bound_ends_where_the_stages_keep_a_point(monkeypatch):
    """At the bound the driver throws WorkSpent into the objective's stages until they return an end: here they
    keep the first solve's end, yield one more stage when the bound is first thrown (which gets it too), and return
    the kept point at the second; the result is that point, not converged.  Stages that let it pass are refused."""
    first = run("paper")
    thrown = []

    def keeping(problem):
        stage = paper_stage(problem)
        kept = yield stage
        try:
            yield replace(stage, start=problem.x0)
        except WorkSpent:
            thrown.append("first")
            try:
                yield replace(stage, start=problem.x0)
            except WorkSpent:
                thrown.append("second")
                return kept, stage

    record(monkeypatch, "keeping", keeping, bounds_members=True, max_jacobians=first.njev + 1)
    result = run("keeping")
    assert thrown == ["first", "second"] and result.uv.tobytes() == first.uv.tobytes()
    assert not result.converged and result.njev == first.njev and result.work_bound_reached
    assert not first.work_bound_reached
    assert result.message == f"the best point found within {first.njev + 1} Jacobian evaluations (its work bound)"
    record(monkeypatch, "passing", stages_of(papers(), papers(start="x0")), max_jacobians=first.njev + 1)
    with pytest.raises(InvalidSurfaceError, match=rf"not converged within {first.njev + 1} Jacobian evaluations"):
        run("passing")


def in_turn(monkeypatch):
    """The driver with every stage solved in turn (:attr:`Stage.beside` ones when taken, on the calling thread)."""
    monkeypatch.setattr(driver, "Beside", lambda solve, concurrent: Beside(solve, concurrent=False))


def with_one_beside(carried, iterations, keeping, breaks, squeezed=False):
    """Stages: two iterations of the paper's, then the paper's from the start with the rim's neighbours held (at
    most ``iterations``; carried by the first if ``carried``; if ``breaks``, its Jacobian not finite from its third
    evaluation on; if ``squeezed``, from a start whose third free node is pushed towards the rim, squeezing its
    triangles into the fold-over barrier), then the paper's on from its end with its damping.  Where the work bound
    ends them, ``keeping`` ones return the end of the stage before, the others nothing."""

    def stages(problem):
        held = np.zeros(len(problem.x0), dtype=bool)
        held[:4] = True
        start = problem.x0.copy()
        if squeezed:
            start[4] -= 0.2
            assert np.any(fold_over_barrier(problem, TRIANGLES, 0.5).residuals(problem.uv_of(start)) > 0)
        later = replace(paper_stage(problem), start=start, hold=held, max_iterations=iterations)
        if breaks:
            calls, jacobian = [], later.jacobian

            def broken(x):
                calls.append(x)
                return jacobian(x) * (np.nan if len(calls) > 2 else 1.0)

            later = replace(later, jacobian=broken)
        first = replace(paper_stage(problem), max_iterations=2, beside=(later,) if carried else ())
        ends = [(None, None)]
        for stage in (first, later, paper_stage(problem)):
            try:
                ends.append(((yield stage), stage))
            except WorkSpent:
                if keeping and ends[-1][0] is not None:
                    return ends[-1]
                raise
        return ends[-1]

    return stages


@pytest.mark.parametrize(
    "bound, iterations, keeping, bounds_members, breaks, squeezed",
    [
        (1000, 500, False, False, False, True),
        (1000, 500, False, False, False, False),
        (1000, 2, False, False, False, False),
        (6, 500, True, False, False, False),
        (6, 500, True, False, True, False),
        (4, 500, False, True, False, False),
    ],
)
def test_a_stage_carried_beside_ends_where_the_stages_in_turn_do(
    bound, iterations, keeping, bounds_members, breaks, squeezed, monkeypatch
):
    """The same stages with the second solved beside the first (on a thread, or in turn when taken) and not carried
    at all: the same point, the same evaluations and Jacobians, bit for bit, the third going on from the second's end
    with its damping (13 Jacobians: 3, 5 and 5; with the second given only 2 iterations, unconverged, the third goes
    on all the same).  With a work bound that cuts the second short (6: it may take 2 of its 4 iterations, so it is
    solved again in turn, and the end kept is the first's; also where its normal equations stop being finite just at
    those 2, which in turn ends it unconverged at its cap) or leaves it none (4: refused, the members outside [l, 2l]
    named at its start), the same end.  On a thread the second is solved once, there, unless the bound cuts it; from
    a start in the fold-over barrier, with SuperLU (not the default), it keeps the guards and the factorisation."""
    ends = []
    for carried, concurrent in ((True, True), (True, False), (False, True)):
        stages = with_one_beside(carried, iterations, keeping, breaks, squeezed)
        record(monkeypatch, "beside", stages, bounds_members=bounds_members, max_jacobians=bound)
        solves, solve = [], driver._solve

        def spied(problem, stage, *args, **kwargs):
            solves.append((stage.start is not None, threading.current_thread() is threading.main_thread()))
            return solve(problem, stage, *args, **kwargs)

        with monkeypatch.context() as patched:
            patched.setattr(driver, "_solve", spied)
            if not concurrent:
                in_turn(patched)
            try:
                result = run("beside", factorisation="superlu" if squeezed else None)
            except InvalidSurfaceError as error:
                ends.append(str(error))
            else:
                ends.append((result.uv.tobytes(), result.nfev, result.njev, result.cost_after, result.message))
        if carried and concurrent and bound == 1000:
            assert sorted(solves) == [(False, True), (False, True), (True, False)]
    assert ends[0] == ends[1] == ends[2]
    assert isinstance(ends[0], str) == (bound == 4), ends[0]
    if bounds_members:
        assert "no mesh with every member in [l, 2l] found within 4 Jacobian evaluations" in ends[0]
    if keeping:
        assert ends[0][-1] == "the best point found within 6 Jacobian evaluations (its work bound)"


def test_a_stage_carried_by_a_later_stage_is_solved_beside_it(monkeypatch):
    """The stage carried by the second (not the first) is solved beside that one, on a thread of its own: the same
    end, evaluations and Jacobians as with it solved in turn uncarried, bit for bit."""

    def stages(carried):
        def make(problem):
            held = np.zeros(len(problem.x0), dtype=bool)
            held[:4] = True
            later = replace(paper_stage(problem), start=problem.x0.copy(), hold=held)
            second = replace(paper_stage(problem), max_iterations=2, beside=(later,) if carried else ())
            x = stage = None
            for stage in (replace(paper_stage(problem), max_iterations=2), second, later, paper_stage(problem)):
                x = yield stage
            return x, stage

        return make

    ends, solve = [], driver._solve
    for carried in (True, False):
        solves = []

        def spied(problem, stage, *args, **kwargs):
            solves.append((stage.start is not None, threading.current_thread() is threading.main_thread()))
            return solve(problem, stage, *args, **kwargs)

        record(monkeypatch, "later", stages(carried))
        with monkeypatch.context() as patched:
            patched.setattr(driver, "_solve", spied)
            result = run("later")
        ends.append((result.uv.tobytes(), result.nfev, result.njev, result.cost_after, result.message))
        assert sorted(solves) == [(False, True)] * 3 + [(True, not carried)]
    assert ends[0] == ends[1]


@pytest.mark.parametrize("objective", ["bounded", "classes"])
def test_a_stage_solved_beside_gives_the_bits_of_the_solve_in_turn(objective, monkeypatch):
    """Bounded's second start is solved on a thread of its own beside the first series: the mesh and the work
    counted are those of every stage solved in turn, bit for bit, on a dome at two lengths."""
    from equimesh.testing.surfaces import dome

    surface = dome(rise=8.0, seed=3, jitter=1.0)
    for length in (3.0, 4.0):
        beside = equimesh.mesh_surface(surface, length, optimize=objective, placement="default")
        with monkeypatch.context() as patched:
            in_turn(patched)
            turn = equimesh.mesh_surface(surface, length, optimize=objective, placement="default")
        assert np.array_equal(beside.points, turn.points) and np.array_equal(beside.uv, turn.uv)
        done, then = beside.stages.optimization, turn.stages.optimization
        assert (done.njev, done.nfev, done.cost_after) == (then.njev, then.nfev, then.cost_after)


def test_a_solve_beside_that_no_stage_takes_is_stopped_when_the_optimisation_ends():
    """A stage solved beside whose end nobody asks for: :meth:`Beside.close` stops it at its next evaluation of
    the residuals and waits for its thread, so no work goes on after the optimisation returns."""
    p, _ = problem(seed=1)
    paper = paper_stage(p)
    calls, under_way = [], threading.Event()
    beside = Beside(driver._alone(p, None, None, None, (None, 1e-10, 1e-10)), concurrent=True)

    def residuals(x):
        calls.append(1)
        if len(calls) == 2:  # the solve is under way: held here until close asks it to stop
            under_way.set()
            beside._stop.wait()
        return paper.residuals(x)

    beside.start(replace(paper, residuals=residuals, start=p.x0))
    ((_, future),) = beside._pending.values()
    while not (under_way.wait(timeout=0.05) or future.done()):  # the second evaluation, or an end before it
        pass
    beside.close()
    assert future.done()  # close waited for it
    assert under_way.is_set() and len(calls) == 2 and isinstance(future.exception(), Stopped)


@pytest.mark.parametrize("change", [{"start": None}, {"feasible": lambda x: True}])
def test_only_a_stage_with_its_own_start_and_no_hard_constraint_is_solved_beside(change):
    p, _ = problem()
    beside = Beside(driver._alone(p, None, None, None, (None, 1e-10, 1e-10)), concurrent=True)
    stage = replace(paper_stage(p), start=p.x0)
    with pytest.raises(
        equimesh.errors.InternalError,
        match="^a stage solved beside the others needs its own start and no hard constraint$",
    ):
        beside.start(replace(stage, **change))
    beside.close()
