"""The work bound of the final optimisation (docs/decisions.md, "A work bound for the optimisation"): an objective
spends at most ``Objective.max_jacobians`` Jacobian evaluations, and one that bounds the members refuses at once a
start out of reach of [l, 2l]."""

import threading
from dataclasses import dataclass, field, replace

import numpy as np
import pytest
from triangle_meshes import closed_tube

from equimesh.errors import InvalidSurfaceError
from equimesh.surface.optimize import OBJECTIVES, driver
from equimesh.surface.optimize.members import out_of_reach, short_share
from equimesh.surface.pipeline import mesh_surface
from equimesh.testing.surfaces import dome
from equimesh.tolerance import BOUNDED_ROUND_ITERATIONS, CLASSES_ROUNDS, REACH_LENGTH, REACH_SHARE

SURFACE = {"rise": 8.0, "seed": 3, "jitter": 1.0}


@dataclass
class Spent:
    """The Jacobian evaluations of the solves of an optimisation (a solve of k iterations counts k + 1, as the
    result's ``njev``): on the calling thread, and beside it (the stages the driver solves on a thread of their own,
    ``Stage.beside``)."""

    main: list = field(default_factory=list)
    beside: list = field(default_factory=list)

    def clear(self):
        self.main.clear()
        self.beside.clear()


@pytest.fixture
def jacobians(monkeypatch):
    """The Jacobian evaluations of every solve of the optimisation while the test runs (:class:`Spent`)."""
    spent = Spent()
    solve = driver.least_squares

    def counted(*args, **kwargs):
        solution = solve(*args, **kwargs)
        main = threading.current_thread() is threading.main_thread()
        (spent.main if main else spent.beside).append(solution.iterations + 1)
        return solution

    monkeypatch.setattr(driver, "least_squares", counted)
    return spent


def within(spent, bound):
    """The solves on the calling thread spent at most ``bound``, and at most one solve (bounded's second start, its
    own iterations bounding it) ran beside them."""
    return sum(spent.main) <= bound and len(spent.beside) <= 1


def bounded_to(monkeypatch, objective, bound):
    monkeypatch.setitem(OBJECTIVES, objective, replace(OBJECTIVES[objective], max_jacobians=bound))


@pytest.mark.parametrize("objective", ["paper", "bounded", "classes"])
def test_a_bound_at_the_work_of_a_run_changes_nothing_and_one_below_keeps_the_best_or_refuses(
    objective, monkeypatch, jacobians
):
    """A normal input: its optimisation spends ``njev`` Jacobians; with the bound at exactly that the mesh is the
    same bits.  One Jacobian fewer cuts the last solve short: "paper" is refused in one line; "bounded" and
    "classes" end at the best point they kept before it (bounded's best round end, found before its last solve, the
    paper's optimum as a second start; the classes objective's fewest classes), not converged; neither spends more
    than the bound."""
    surface = dome(**SURFACE)
    mesh = mesh_surface(surface, 5.0, optimize=objective, placement="default")
    work = mesh.stages.optimization.njev
    assert work == sum(jacobians.main + jacobians.beside) and work <= OBJECTIVES[objective].max_jacobians
    bounded_to(monkeypatch, objective, work)
    again = mesh_surface(surface, 5.0, optimize=objective, placement="default")
    assert np.array_equal(again.points, mesh.points) and again.stages.optimization.njev == work
    assert not again.stages.optimization.work_bound_reached
    bounded_to(monkeypatch, objective, work - 1)
    jacobians.clear()
    if objective == "paper":
        with pytest.raises(
            InvalidSurfaceError, match=rf"^optimisation \(paper\): not converged[^\n]* within {work - 1} "
        ):
            mesh_surface(surface, 5.0, optimize=objective, placement="default")
    else:
        short = mesh_surface(surface, 5.0, optimize=objective, placement="default")
        result = short.stages.optimization
        assert (
            not result.converged
            and result.message == f"the best point found within {work - 1} Jacobian evaluations (its work bound)"
        )
        assert result.njev <= work - 1 and result.work_bound_reached
        ratio = short.edge_lengths() / 5.0
        assert np.all((ratio >= 1.0 - 1e-12) & (ratio <= 2.0 + 1e-12))
        if objective == "bounded":  # its last solve was the paper's optimum, which did not beat the best round end
            assert np.array_equal(short.points, mesh.points)
    assert within(jacobians, work - 1)


def test_a_small_bound_refuses_a_normal_input_naming_the_members_outside(monkeypatch, jacobians):
    """Three rounds (12 Jacobians): none has ended with every member in [l, 2l]; the fifth, at 20, is the first, so a
    bound of 20 returns it."""
    bounded_to(monkeypatch, "bounded", 12)
    with pytest.raises(
        InvalidSurfaceError,
        match=r"^optimisation \(bounded\): no mesh with every member in \[l, 2l\] found within 12 Jacobian "
        r"evaluations \(its work bound\), \d+ of \d+ members outside \[l, 2l\] \(lengths from [^\n]*optimize='paper'",
    ):
        mesh_surface(dome(**SURFACE), 5.0, optimize="bounded", placement="default")
    assert within(jacobians, 12)
    bounded_to(monkeypatch, "bounded", 20)
    result = mesh_surface(dome(**SURFACE), 5.0, optimize="bounded", placement="default").stages.optimization
    assert result.work_bound_reached and result.njev == 20


def test_the_bounds_cover_each_objective_s_own_guards():
    """ "paper" is one solve of at most 500 iterations: its bound is never tighter than that guard; "classes" runs
    bounded's stages, then its own rounds of at most BOUNDED_ROUND_ITERATIONS iterations each."""
    assert OBJECTIVES["paper"].max_jacobians == 501
    rounds = CLASSES_ROUNDS * (BOUNDED_ROUND_ITERATIONS + 1)
    assert OBJECTIVES["classes"].max_jacobians >= OBJECTIVES["bounded"].max_jacobians + rounds


def test_out_of_reach_is_more_than_the_share_of_members_shorter_than_the_length():
    n = 1000
    short = int(REACH_SHARE * n)
    ratio = np.r_[np.full(short, 0.99 * REACH_LENGTH), np.full(n - short, 1.5)]
    assert short_share(ratio) == short / n and not out_of_reach(ratio)
    assert out_of_reach(np.r_[ratio[:-1], 0.99 * REACH_LENGTH])
    assert not out_of_reach(np.full(n, REACH_LENGTH))  # shorter than, not at
    assert short_share(np.zeros(0)) == 0.0


@pytest.mark.parametrize("objective", ["bounded", "classes"])
def test_a_stretched_start_is_refused_before_any_work(objective, jacobians):
    """A closed-ended tube flattens to several times its area: nearly every member of the remapped mesh is shorter
    than l / 2 on the surface, refused before the solver's first Jacobian."""
    with pytest.raises(
        InvalidSurfaceError,
        match=rf"^optimisation \({objective}\): no mesh with every member in \[l, 2l\] within reach of the remapped "
        r"mesh: [\d.]+ % of its \d+ members shorter than 0.5 l on the surface [^\n]*$",
    ):
        mesh_surface(closed_tube(1.0, 10.0), 1.0, optimize=objective, max_nodes=None)
    assert jacobians == Spent()


@pytest.mark.parametrize("radius, length", [(1.0, 4.0), (1.0, 10.0), (1.0, 17.0), (1.5, 12.0), (2.0, 12.0)])
def test_closed_tubes_are_meshed_or_refused_within_the_work_bound(radius, length, jacobians):
    """Closed-ended tubes of several radii and lengths (their flattening stretched more the longer and thinner they
    are), meshed with the default objective: a mesh or a one-line refusal, never more work than the bound."""
    try:
        mesh_surface(closed_tube(radius, length), radius, max_nodes=None)
    except InvalidSurfaceError as error:
        assert "\n" not in str(error) and str(error).startswith("optimisation (bounded): no mesh"), str(error)
    assert within(jacobians, OBJECTIVES["bounded"].max_jacobians)
