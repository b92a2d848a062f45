"""The stages of each objective (``surface/optimize/objectives.py``), driven by hand and on tiny grids.

An objective's stages are a generator: it yields a least-squares stage, is sent the point where the solve
ended, and returns the point the optimisation ends at with its stage.  Here the "solver" is the test: it
answers each stage with a point of its choosing, so that the rules of the docstrings are checked one by one
(when a series of rounds ends, when the paper's start is taken, which point is kept, when the last stage
comes, how the nominal lengths of the classes merge); the tiny grids of ``optimize_cases`` also run through
:func:`optimize_uv`.  On the flat grid with l = 8 every grid edge is 1.25 l and every
diagonal 1.7678 l; with l = 6 the diagonals are 2.357 l, outside [l, 2l].
"""

import re
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest
from optimize_cases import RIM, finite_difference, grid, moved, patch, problem

from equimesh import InvalidSurfaceError
from equimesh.classes import length_classes, on_catalogue
from equimesh.mesh import G1, edge_lengths
from equimesh.surface.optimize import OBJECTIVES, UVProblem, optimize_uv
from equimesh.surface.optimize.class_rounds import class_key, class_rounds, class_scale, merged_nominals
from equimesh.surface.optimize.joints import Joints, surface_angles
from equimesh.surface.optimize.members import Members, cauchy
from equimesh.surface.optimize.objectives import bounded_stages, classes_stages, paper_stage, paper_stages
from equimesh.surface.optimize.slide import along_polygon
from equimesh.surface.optimize.solver import DEFAULT_FACTORISATION
from equimesh.surface.optimize.stage import WorkSpent
from equimesh.tolerance import (
    BOUNDED_BAND,
    BOUNDED_FTOL,
    BOUNDED_LOSS_TOL,
    BOUNDED_OFFSET,
    BOUNDED_PENALTY,
    BOUNDED_PULL,
    BOUNDED_ROUND_ITERATIONS,
    BOUNDED_SCALE,
    BOUNDED_START_FTOL,
    CLASSES_ROUNDS,
    CLASSES_SCALE_DECAY,
    CLASSES_SCALE_START,
    CLASSES_START,
    PAPER_FTOL,
)

TARGET, HIGH = 1.0 + BOUNDED_OFFSET, 2.0 - BOUNDED_OFFSET


def drive(stages, answer):
    """Run the generator ``stages``, answering stage k with ``answer(k, stage)``; the stages and what it returns."""
    seen = [next(stages)]
    while True:
        try:
            seen.append(stages.send(answer(len(seen) - 1, seen[-1])))
        except StopIteration as done:
            return seen, done.value


def ratio(p, x):
    return edge_lengths(p.points_of(x), p.edges) / p.length


def test_the_papers_stage_by_hand():
    """``(L - l) / l`` of the G1 members only (the grid edges, 1.25 l), and its Jacobian."""
    p, _ = problem(rise=0.0, slides=True)
    stage = paper_stage(p)
    np.testing.assert_allclose(stage.residuals(p.x0), np.full(24, 0.25), rtol=1e-13)
    x = moved(p, 1)
    expected = ratio(p, x)[p.edge_groups == G1] - 1.0
    np.testing.assert_allclose(stage.residuals(x), expected, rtol=1e-12)
    np.testing.assert_allclose(stage.jacobian(x).toarray(), finite_difference(stage.residuals, x), atol=1e-7)
    assert stage.ftol == PAPER_FTOL and stage.start is None and stage.hold is None and stage.feasible is None
    assert stage.description == "relative deviation (L - l) / l of the G1 edges"
    seen, (end, last) = drive(paper_stages(p), lambda k, stage: x)
    assert len(seen) == 1 and last is seen[0] and end is x
    np.testing.assert_array_equal(last.residuals(x), expected)


def test_a_series_ends_at_a_settled_round_inside_and_keeps_the_start():
    """The flat grid at l = 8 is inside [l, 2l] with no member within the band of l: the first round, answered
    with its start, is settled; the paper's stage starts from the start with the boundary held, and with no
    better share there, the first round's end is the result."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    seen, (end, last) = drive(bounded_stages(p), lambda k, stage: p.x0)
    first, papers = seen
    assert first.description == f"members into [l, 2l] and to {TARGET:g} l, round 1"
    assert (first.ftol, first.max_iterations, first.start) == (BOUNDED_FTOL, BOUNDED_ROUND_ITERATIONS, None)
    r = ratio(p, p.x0)
    np.testing.assert_allclose(first.residuals(p.x0), cauchy(r - TARGET, BOUNDED_SCALE) * (r - TARGET), rtol=1e-12)
    step = np.zeros(len(p.x0))
    step[0] = 1.0  # node 12 along u: 30 per unit, limited to 0.1 l = 0.8
    np.testing.assert_allclose(first.limit(step), step * 0.8 / 30.0, rtol=1e-12)
    assert papers.description == paper_stage(p).description and papers.ftol == BOUNDED_START_FTOL
    np.testing.assert_array_equal(papers.start, p.x0)
    np.testing.assert_array_equal(papers.hold, p.sliding_variables)
    assert len(first.beside) == 1 and first.beside[0] is papers  # solved beside the first series
    assert papers.beside == () and last is first and np.array_equal(end, p.x0)


def test_the_papers_start_is_taken_when_its_share_is_larger():
    """The paper's answer puts one rim member at l (within the band): the boundary is released (the paper's
    objective on, no start, no hold) and a second series starts there, whose round is the result."""
    p, _ = problem(rise=0.0, slides=True, length=9.9)
    better = p.x0.copy()
    better[8] = 0.33  # node 1 slides to u = 0.33: the member from node 0 is 9.9 = l long
    assert np.count_nonzero(np.abs(ratio(p, better) - 1.0) <= BOUNDED_BAND) == 1 and p.sound(better)
    seen, (end, last) = drive(bounded_stages(p), lambda k, stage: better if k >= 1 else p.x0)
    assert len(seen) == 4
    released, second = seen[2], seen[3]
    assert released.description == paper_stage(p).description and released.start is None and released.hold is None
    assert released.ftol == PAPER_FTOL
    assert second.description.endswith("round 1") and second.start is None
    assert last is second and np.array_equal(end, better)


def infeasible_drive(answer=None):
    """The flat grid at l = 6 (every diagonal outside [l, 2l]), every stage answered with the start."""
    p, _ = problem(rise=0.0, slides=True, length=6.0)
    return p, *drive(bounded_stages(p), answer or (lambda k, stage: p.x0))


def test_a_stalled_round_restarts_once_then_the_series_ends():
    """Answered with its start, a round outside [l, 2l] stalls: the next round restarts there (with the initial
    damping); stalled again, the series ends.  Members outside ``[target, high]`` are pulled to the nearer end."""
    p, seen, _ = infeasible_drive()
    assert [s.description.rsplit(",", 1)[-1] for s in seen[:2]] == [" round 1", " round 2"]
    assert seen[0].start is None
    np.testing.assert_array_equal(seen[1].start, p.x0)
    r = ratio(p, p.x0)
    outside = r > HIGH
    assert np.count_nonzero(outside) == 9
    expected = np.where(outside, BOUNDED_PULL * (r - HIGH), cauchy(r - TARGET, BOUNDED_SCALE) * (r - TARGET))
    np.testing.assert_allclose(seen[0].residuals(p.x0), expected, rtol=1e-12)
    assert seen[2].hold is not None and seen[3].hold is None  # the paper's stage held, then released
    assert [s.description.rsplit(",", 1)[-1] for s in seen[4:6]] == [" round 1", " round 2"]


def test_without_a_round_inside_the_last_stage_is_a_penalty():
    """No round ended in [l, 2l]: the last stage restarts from the remapped mesh with a hard constraint, its
    violation naming the members out; its result is where it ended."""
    p, seen, (end, last) = infeasible_drive()
    assert len(seen) == 7 and last is seen[-1]
    assert last.description == f"members in [l, 2l] by a penalty, Cauchy loss on L / l - {TARGET:g}"
    assert last.ftol == BOUNDED_FTOL and last.max_iterations == 500
    np.testing.assert_array_equal(last.start, p.x0)
    assert not last.feasible(p.x0) and last.violation(p.x0).startswith("9 of 33 members outside [l, 2l]")
    np.testing.assert_array_equal(end, p.x0)


def test_the_penalty_below_and_above_the_band():
    """``BOUNDED_PENALTY psi(h)`` of the depth h below ``1 + BOUNDED_OFFSET / 2`` or above ``high``: ``h^2 / 2s``
    within ``s = BOUNDED_OFFSET / 4`` of it, ``h - s / 2`` beyond, and the Jacobian its derivative."""
    p, _, (_, last) = infeasible_drive()
    x = p.x0.copy()
    low, smooth = 1.0 + 0.5 * BOUNDED_OFFSET, 0.25 * BOUNDED_OFFSET
    x[8] = (low - 1e-4) / 5.0  # node 1 along the first side: the member from node 0 is 30 s / 6 l long
    x[15] = 4.0 - 0.18  # node 11 on the last side: the member to node 0 is 0.9 l
    r = ratio(p, x)
    edges = [tuple(e) for e in p.edges]
    inner, short = edges.index((0, 1)), edges.index((0, 11))
    cauchy_part = cauchy(ratio(p, p.x0) - TARGET, BOUNDED_SCALE) * (r - TARGET)
    depth = np.maximum(0.0, low - r) + np.maximum(0.0, r - HIGH)
    assert depth[inner] == pytest.approx(1e-4) and depth[short] == pytest.approx(low - 0.9)
    psi = np.where(depth < smooth, depth**2 / (2 * smooth), depth - smooth / 2)
    got = last.residuals(x)
    np.testing.assert_allclose(got, np.concatenate([cauchy_part, BOUNDED_PENALTY * psi]), rtol=1e-9, atol=1e-12)
    assert got[33 + inner] == pytest.approx(BOUNDED_PENALTY * 1e-8 / (2 * smooth))
    expected = finite_difference(last.residuals, x)
    np.testing.assert_allclose(last.jacobian(x).toarray(), expected, atol=1e-6 * np.abs(expected).max())


def test_bounded_on_the_tiny_grid():
    """Through the solver: every member in [l, 2l], a third at l, the corners fixed; l = 6 is refused."""
    uv, triangles, edges, groups = grid()
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    slide, corners = along_polygon(np.arange(RIM), square, uv[:RIM])
    run = dict(fixed=corners, slides=[slide], triangles=triangles, objective="bounded")
    result = optimize_uv(patch(), uv, edges, groups, 8.0, **run)
    r = edge_lengths(patch().evaluate(*result.uv.T), edges) / 8.0
    assert r.min() >= 1.0 and r.max() <= 2.0 and np.mean(np.abs(r - 1.0) <= BOUNDED_BAND) > 0.3
    np.testing.assert_array_equal(result.uv[corners], uv[corners])
    with pytest.raises(InvalidSurfaceError, match=r"no mesh with every member in \[l, 2l\] found, 11 of 33"):
        optimize_uv(patch(), uv, edges, groups, 6.0, **run)


def answers_for_classes(bounded_end, rounds):
    """Bounded's stages answered with ``bounded_end``, the classes' rounds (k = 0, 1, ...) with ``rounds(k)``; the
    answer and the list of the classes' rounds it answered."""
    done = []

    def answer(k, stage):
        if "nominal lengths" not in stage.description:
            return bounded_end
        done.append(stage)
        return rounds(len(done) - 1)

    return answer, done


def documented_key(p, x):
    """(members off the catalogue, classes, minus the share in the ten largest) at ``x`` (classes_stages)."""
    r = ratio(p, x)
    off = 0 if p.catalogue is None else int(np.count_nonzero(~on_catalogue(r, 1.0, p.catalogue, p.tolerance)))
    classes = length_classes(r, 1.0, p.tolerance)
    return off, len(classes), -classes.top_share()


def start_nominals(p, x):
    """The nominal lengths of the first round from bounded's end ``x``: its 30 largest classes' (in units of l),
    clipped to [target, high], and the target."""
    classes = length_classes(ratio(p, x), 1.0, p.tolerance)
    largest = np.argsort(-classes.count, kind="stable")[:CLASSES_START]
    return np.unique(np.append(np.clip(classes.nominal[largest], TARGET, HIGH), TARGET))


def round_residuals(p, x, nominal, scale):
    """A round's residuals at its start ``x``: each member pulled to its nearest nominal with the Cauchy weight of
    scale ``scale``, a member outside [target, high] to the nearer end with BOUNDED_PULL."""
    r = ratio(p, x)
    goal = nominal[np.argmin(np.abs(r[:, None] - nominal[None, :]), axis=1)]
    outside = (r < TARGET) | (r > HIGH)
    weight = np.where(outside, BOUNDED_PULL, cauchy(r - goal, scale))
    return weight * (r - np.where(outside, np.clip(r, TARGET, HIGH), goal))


def test_classes_rounds_merge_the_nominal_lengths():
    """Bounded ends at the start (two classes, 1.25 l and 1.7678 l): the nominals are those and the target; every
    three rounds the one holding the fewest members is dropped (the diagonals', then the grid edges'), never the
    target; the members go to the nearest nominal left.  Nothing beats the start: it is the result."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    seen, (end, last) = drive(classes_stages(p), lambda k, stage: p.x0)
    rounds = seen[2:]
    assert len(rounds) == CLASSES_ROUNDS
    counts = [int(s.description.split(" of ")[1].split()[0]) for s in rounds]
    assert counts == [3, 3, 3, 2, 2, 2] + [1] * (CLASSES_ROUNDS - 6)
    assert rounds[-1].description == f"members to the nearest of 1 nominal lengths, round {CLASSES_ROUNDS}"
    np.testing.assert_array_equal(rounds[0].start, p.x0)
    assert all(s.start is None for s in rounds[1:])
    step = np.zeros(len(p.x0))
    step[0] = 1.0  # node 12 along u: 30 per unit, limited to 0.1 l = 0.8
    np.testing.assert_allclose(rounds[0].limit(step), step * 0.8 / 30.0, rtol=1e-12)
    assert (rounds[0].ftol, rounds[0].max_iterations) == (BOUNDED_FTOL, BOUNDED_ROUND_ITERATIONS)
    r = ratio(p, p.x0)
    diagonal = r > 1.5
    np.testing.assert_allclose(rounds[0].residuals(p.x0), 0.0, atol=1e-12)  # every member at its own nominal
    goal = np.where(diagonal, 1.25, r)
    pull = cauchy(r - goal, class_scale(3, p.tolerance)) * (r - goal)
    np.testing.assert_allclose(rounds[3].residuals(p.x0), pull, rtol=1e-9, atol=1e-12)
    pull = cauchy(r - TARGET, class_scale(6, p.tolerance)) * (r - TARGET)
    np.testing.assert_allclose(rounds[6].residuals(p.x0), pull, rtol=1e-9)
    assert last is seen[0] and np.array_equal(end, p.x0)


def test_classes_nominals_move_to_the_middle_of_their_members():
    """Answered with a point whose grid edges spread about 1.25 l, the nominal of the grid edges moves to the
    middle of those within the tolerance of it (clipped to [target, high]): the next round pulls them there."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    spread = moved(p, 3, size=0.0002)
    seen, _ = drive(classes_stages(p), lambda k, stage: spread if k >= 2 else p.x0)
    r = ratio(p, spread)
    grid_edges = np.abs(r - 1.25) <= p.tolerance
    assert grid_edges.sum() == 24
    middle = 0.5 * (r[grid_edges].min() + r[grid_edges].max())
    diagonal = 0.5 * (r[~grid_edges].min() + r[~grid_edges].max())
    nominal = np.array([TARGET, middle, diagonal])
    goal = nominal[np.argmin(np.abs(r[:, None] - nominal), axis=1)]
    expected = cauchy(r - goal, class_scale(1, p.tolerance)) * (r - goal)
    np.testing.assert_allclose(seen[3].residuals(spread), expected, rtol=1e-9, atol=1e-15)


def test_classes_keeps_the_round_with_the_fewest_classes_and_sound_joints():
    """Bounded ends at a point with more classes; a round answered with the start (two classes) is kept, unless
    the start breaks the joints' bounds."""
    p, triangles = problem(rise=0.0, slides=True, length=8.0)
    messy = moved(p, 4, size=0.004)
    r = ratio(p, messy)
    assert r.min() >= 1.0 and r.max() <= 2.0 and len(length_classes(r, 1.0, p.tolerance)) > 2
    answer, rounds = answers_for_classes(messy, lambda k: p.x0)
    seen, (end, last) = drive(classes_stages(p), answer)
    assert last is rounds[0] and np.array_equal(end, p.x0)
    angles, start = surface_angles(p.points_of(messy), triangles), surface_angles(p.points_of(p.x0), triangles)
    bounds = np.minimum(angles, start)
    corner = np.unravel_index(np.argmax(angles - start), angles.shape)
    bounds[corner] = angles[corner]  # the start's angle there is below the messy point's: unsound
    strict = replace(p, joints=Joints(p, triangles, bounds))
    assert strict.sound(messy) and not strict.sound(p.x0)
    seen, (end, last) = drive(classes_stages(strict), answers_for_classes(messy, lambda k: p.x0)[0])
    assert np.array_equal(end, messy) and last is seen[0]


def test_classes_with_a_catalogue_counts_the_members_off_it_first():
    """With the catalogue (1.25 l, 1.5 l) the nominals are the catalogue's, never merged: every member is pulled to
    the nearest stock length."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    p = replace(p, catalogue=np.array([1.25, 1.5]))
    seen, (end, last) = drive(classes_stages(p), lambda k, stage: p.x0)
    assert all(" of 2 nominal lengths" in s.description for s in seen[2:])
    r = ratio(p, p.x0)
    goal = np.where(r > 1.5, 1.5, 1.25)
    expected = cauchy(r - goal, class_scale(0, p.tolerance)) * (r - goal)
    np.testing.assert_allclose(seen[2].residuals(p.x0), expected, rtol=1e-9)
    assert last is seen[0]


def test_classes_counts_the_members_off_the_catalogue_first():
    """Bounded ends with 3 members off the catalogue; a round answered with a point with 2 off and as many classes
    is kept."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    p = replace(p, catalogue=np.array([1.25, 1.7678]))
    start, fewer_off = moved(p, 1, size=0.001), moved(p, 7, size=0.001)
    assert documented_key(p, start) == (3, 3, -1.0) and documented_key(p, fewer_off) == (2, 3, -1.0)
    answer, rounds = answers_for_classes(start, lambda k: fewer_off if k == 0 else start)
    seen, (end, last) = drive(classes_stages(p), answer)
    assert last is rounds[0] and np.array_equal(end, fewer_off)


def test_classes_keeps_fewer_members_off_the_catalogue_over_fewer_classes():
    """With the catalogue (1.25 l, 1.7678 l) bounded ends with 1 member off it and 3 classes; a round answered with
    2 off and 2 classes is not kept: the members off the catalogue count first in every round's key too."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    p = replace(p, catalogue=np.array([1.25, 1.7678]))
    start, fewer_classes = moved(p, 2, size=0.0005), moved(p, 18, size=0.0005)
    assert documented_key(p, start)[:2] == (1, 3) and documented_key(p, fewer_classes)[:2] == (2, 2)
    answer, rounds = answers_for_classes(start, lambda k: fewer_classes if k == 0 else start)
    seen, (end, last) = drive(classes_stages(p), answer)
    assert len(rounds) == CLASSES_ROUNDS and last is seen[0] and np.array_equal(end, start)


def test_a_later_round_must_beat_the_best_round_not_bounded_s_end():
    """Bounded ends with 12 classes, the first round with 3, the second with 4: the first round is kept, although
    the second has fewer classes than bounded's end."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    messy, three, four = moved(p, 4, size=0.004), moved(p, 1, size=0.001), moved(p, 0, size=0.001)
    assert [documented_key(p, x)[1] for x in (messy, three, four)] == [12, 3, 4]
    answer, rounds = answers_for_classes(messy, lambda k: (three, four)[k] if k < 2 else messy)
    seen, (end, last) = drive(classes_stages(p), answer)
    assert last is rounds[0] and np.array_equal(end, three)


def test_merged_nominals_move_to_the_middle_of_the_members_within_the_tolerance_ends_included():
    """Members exactly a tolerance from a nominal are within it (exact binary fractions): the nominal 1.5 with
    members 1.5 and 1.75 at the tolerance 0.25 moves to 1.625; 1.25, as near the target as 1.5, goes to the target
    (the first nominal), which stays; no merge after the first round.  The nominal 1.8 holds 1.75 alone (1.5 is 0.3
    from it) and moves there."""
    members = SimpleNamespace(target=1.0, high=1.9)
    ratio = np.array([1.0, 1.25, 1.5, 1.75])
    moved_nominals = merged_nominals(np.array([1.0, 1.5]), ratio, 0.25, 0, members)
    np.testing.assert_array_equal(moved_nominals, [1.0, 1.625])
    np.testing.assert_array_equal(merged_nominals(np.array([1.0, 1.8]), ratio, 0.25, 0, members), [1.0, 1.75])


def test_classes_breaks_a_tie_in_classes_by_the_share_in_the_ten_largest():
    """At the tolerance 0.01 l: bounded ends at a point with 12 classes, the two smallest holding 3 members; a
    round answered with one of 12 classes whose two smallest hold 2 has the larger share in the ten largest and
    is kept.  The first round's nominals are the start's classes'."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    p = replace(p, tolerance=0.01)
    start, better = moved(p, 203, size=0.008), moved(p, 3, size=0.008)
    assert documented_key(p, start) == (0, 12, pytest.approx(-30 / 33))
    assert documented_key(p, better) == (0, 12, pytest.approx(-31 / 33))
    answer, rounds = answers_for_classes(start, lambda k: better if k == 0 else start)
    seen, (end, last) = drive(classes_stages(p), answer)
    assert last is rounds[0] and np.array_equal(end, better)
    nominal = start_nominals(p, start)
    assert len(nominal) == 13 and rounds[0].description.startswith("members to the nearest of 13 nominal lengths")
    np.testing.assert_allclose(
        rounds[0].residuals(start),
        round_residuals(p, start, nominal, class_scale(0, p.tolerance)),
        rtol=1e-9,
        atol=1e-15,
    )


def test_the_first_nominals_are_the_30_largest_classes():
    """At the tolerance 0.0003 l the start's 33 members fall into 31 classes, two of them of two members: the first
    round's nominals are those of the 30 largest (of equal ones the first by length: the longest single is left
    out) and the target."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    p = replace(p, tolerance=0.0003)
    start = moved(p, 2, size=0.008)
    classes = length_classes(ratio(p, start), 1.0, p.tolerance)
    assert len(classes) == 31 and sorted(classes.count)[-3:] == [1, 2, 2]
    answer, rounds = answers_for_classes(start, lambda k: start)
    drive(classes_stages(p), answer)
    nominal = start_nominals(p, start)
    assert len(nominal) == 31 and classes.nominal.max() not in nominal
    assert rounds[0].description.startswith("members to the nearest of 31 nominal lengths")
    np.testing.assert_allclose(
        rounds[0].residuals(start),
        round_residuals(p, start, nominal, class_scale(0, p.tolerance)),
        rtol=1e-9,
        atol=1e-15,
    )


def test_of_equal_classes_the_first_by_length_is_a_nominal():
    """On the 8 x 8 grid at the tolerance 0.0005 l the start's 161 members fall into 90 classes, many of equal
    counts: the 30 largest are those a stable sort of the counts takes first."""
    p, _ = problem(rise=0.0, slides=True, length=4.0, n=8)
    p = replace(p, tolerance=0.0005)
    start = moved(p, 0, size=0.003)
    assert len(length_classes(ratio(p, start), 1.0, p.tolerance)) == 90
    answer, rounds = answers_for_classes(start, lambda k: start)
    drive(classes_stages(p), answer)
    nominal = start_nominals(p, start)
    np.testing.assert_allclose(
        rounds[0].residuals(start),
        round_residuals(p, start, nominal, class_scale(0, p.tolerance)),
        rtol=1e-9,
        atol=1e-15,
    )


def test_classes_are_counted_at_the_problems_tolerance():
    """At 0.01 l a round's point with 4 classes beats bounded's end with 5 (at 0.005 l both have 7)."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    p = replace(p, tolerance=0.01)
    start, fewer = moved(p, 2, size=0.002), moved(p, 0, size=0.002)
    assert documented_key(p, start)[1] == 5 and documented_key(p, fewer)[1] == 4
    answer, rounds = answers_for_classes(start, lambda k: fewer if k == 0 else start)
    _, (end, last) = drive(classes_stages(p), answer)
    assert last is rounds[0] and np.array_equal(end, fewer)


def test_nominals_stay_at_most_high():
    """With l = 10 / sqrt(2) the diagonals are about 2 l: their class's middle is above ``high``, its nominal
    ``high``, at the start and after a round; a diagonal just inside [target, high] is pulled to it."""
    p, _ = problem(rise=0.0, slides=True, length=10.0 / np.sqrt(2.0))
    start = moved(p, 1, size=0.0003)
    r = ratio(p, start)
    diagonals = r > 1.9
    inside = diagonals & (r < HIGH)
    assert np.any(inside) and 0.5 * (r[diagonals].min() + r[diagonals].max()) > HIGH
    answer, rounds = answers_for_classes(start, lambda k: start)
    drive(classes_stages(p), answer)
    nominal = start_nominals(p, start)
    assert nominal.max() == HIGH
    for k, stage in enumerate(
        rounds[:2]
    ):  # after the first round the diagonals' nominal moves to their middle, at most high
        expected = round_residuals(p, start, nominal, class_scale(k, p.tolerance))
        np.testing.assert_allclose(stage.residuals(start), expected, rtol=1e-9, atol=1e-15)


def test_a_class_at_l_starts_at_the_target():
    """With l = 10 the grid edges are l long: their class's nominal is clipped to the target, one nominal with it;
    they are below the target, so pulled up to it with BOUNDED_PULL."""
    p, _ = problem(rise=0.0, slides=True, length=10.0)
    answer, rounds = answers_for_classes(p.x0, lambda k: p.x0)
    drive(classes_stages(p), answer)
    assert rounds[0].description.startswith("members to the nearest of 2 nominal lengths")
    r = ratio(p, p.x0)
    expected = np.where(r < 1.2, BOUNDED_PULL * (r - TARGET), 0.0)  # the diagonals at their own nominal
    np.testing.assert_allclose(rounds[0].residuals(p.x0), expected, atol=1e-12)


def test_of_rounds_with_equal_shares_the_first_is_kept():
    """Two rounds end inside [l, 2l] with no member within the band of l: the first round's end is the result."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    first, second = moved(p, 1, size=0.02), moved(p, 2, size=0.001)
    for x in (first, second):
        assert Members.inside(ratio(p, x)) and not np.any(np.abs(ratio(p, x) - 1.0) <= BOUNDED_BAND)
    seen, (end, last) = drive(bounded_stages(p), lambda k, stage: first if k == 0 else second)
    assert seen[1].description.endswith("round 2")  # the first round's loss moved: not settled
    assert last is seen[0] and np.array_equal(end, first)


def cauchy_loss(r):
    return float(np.sum(np.log1p(((r - TARGET) / BOUNDED_SCALE) ** 2)))


def along(p, direction, change, measure, t_max=1.0):
    """The point ``x0 + t direction`` at which ``measure(x)`` has changed by ``change`` relative to its value at
    ``x0`` (bisection on t in [0, t_max]; the change grows with t there)."""
    base = measure(p.x0)
    lo, hi = 0.0, t_max
    for _ in range(60):
        t = 0.5 * (lo + hi)
        lo, hi = (t, hi) if abs(measure(p.x0 + t * direction) - base) < change * abs(base) else (lo, t)
    return p.x0 + hi * direction


@pytest.mark.parametrize("change", [1.05, 1.5])
def test_a_round_whose_loss_moved_is_followed_by_another(change):
    """A round ending inside [l, 2l] where the Cauchy loss changed by more than BOUNDED_LOSS_TOL of its start's
    is not settled: another round follows."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    x = along(p, moved(p, 11, size=0.01) - p.x0, change * BOUNDED_LOSS_TOL, lambda y: cauchy_loss(ratio(p, y)))
    assert Members.inside(ratio(p, x))
    seen, _ = drive(bounded_stages(p), lambda k, stage: x)
    assert seen[1].description.endswith("round 2") and seen[1].start is None


def test_a_round_whose_loss_hardly_moved_has_settled():
    """Changed by half of BOUNDED_LOSS_TOL, inside [l, 2l]: settled, the series ends (the paper's stage next)."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    x = along(p, moved(p, 11, size=0.01) - p.x0, 0.5 * BOUNDED_LOSS_TOL, lambda y: cauchy_loss(ratio(p, y)))
    seen, _ = drive(bounded_stages(p), lambda k, stage: x)
    assert seen[1].description == paper_stage(p).description


def test_a_round_at_zero_loss_that_did_not_move_has_settled():
    """Two members exactly at the target (their Cauchy loss 0, l chosen to the bit) and the round answered with its
    start: its loss moved by 0, within any share of 0, so the series ends after that round."""
    uv = np.array([[0.0, 0.0], [0.5, 0.0], [0.5, 0.5]])
    edges = np.array([[0, 1], [1, 2]])
    free = np.array([False, True, False])
    length = 15.0 / TARGET  # both members 15 long on the flat patch
    for _ in range(64):
        p = UVProblem(patch(0.0), uv, edges, np.array([G1, G1]), float(length), free)
        r = ratio(p, p.x0)
        if np.all(r == TARGET):
            break
        length = np.nextafter(length, np.inf if r[0] > TARGET else -np.inf)
    assert np.all(r == TARGET) and cauchy_loss(r) == 0.0
    seen, _ = drive(bounded_stages(p), lambda k, stage: p.x0)
    assert [stage.description for stage in seen] == [
        f"members into [l, 2l] and to {TARGET:g} l, round 1",
        paper_stage(p).description,
    ]


def test_a_settled_round_whose_cost_fell_does_not_restart():
    """Outside [l, 2l], a round whose Cauchy loss hardly changed (settled) but whose own cost fell by 1.5
    BOUNDED_LOSS_TOL has not stalled: the next round goes on without a restart; one whose cost fell by half that
    has stalled, and the next round restarts."""
    p, _ = problem(rise=0.0, slides=True, length=6.0)
    first = next(bounded_stages(p))
    descent = -(first.jacobian(p.x0).T @ first.residuals(p.x0))

    def cost(y):
        return float(np.sum(first.residuals(y) ** 2))

    for change, restarts in ((1.5 * BOUNDED_LOSS_TOL, False), (0.5 * BOUNDED_LOSS_TOL, True)):
        x = along(p, descent, change, cost, t_max=1e-3)
        loss_change = abs(cauchy_loss(ratio(p, x)) - cauchy_loss(ratio(p, p.x0)))
        assert loss_change <= BOUNDED_LOSS_TOL * cauchy_loss(ratio(p, p.x0))
        seen, _ = drive(bounded_stages(p), lambda k, stage: x)
        assert seen[1].description.endswith("round 2") and (seen[1].start is not None) == restarts
        assert len(seen[0].beside) == 1 and seen[1].beside == ()  # only the first round carries the second start


def test_the_work_bound_ends_bounded_at_its_best_round_end_or_passes():
    """WorkSpent thrown into bounded's stages: at the first round, before any round ended, it passes (nothing kept);
    at the paper's start, after a first round ended in [l, 2l] (the flat grid at l = 8), that round's end and stage
    are returned; in the last stage (no round in [l, 2l] at l = 6) it passes."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    stages = bounded_stages(p)
    next(stages)
    with pytest.raises(WorkSpent):
        stages.throw(WorkSpent())
    stages = bounded_stages(p)
    first = next(stages)
    stages.send(p.x0)  # the first round ends at the start, inside: kept; the paper's start is next
    with pytest.raises(StopIteration) as done:
        stages.throw(WorkSpent())
    end, last = done.value.value
    assert last is first and np.array_equal(end, p.x0)
    p, _ = problem(rise=0.0, slides=True, length=6.0)
    stages = bounded_stages(p)
    stage = next(stages)
    while "penalty" not in stage.description:
        stage = stages.send(p.x0)
    with pytest.raises(WorkSpent):
        stages.throw(WorkSpent())


@pytest.mark.parametrize("length", [8.0, 10.0])
def test_the_work_bound_ends_classes_at_its_fewest_classes(length):
    """WorkSpent thrown into a round of the classes: the fewest classes so far, here bounded's end (the flat grid
    moved: more classes than its start), with bounded's stage; at l = 10, where the start would begin a second
    series, at once too."""
    p, _ = problem(rise=0.0, slides=True, length=length)
    messy = moved(p, 4, size=0.004)
    stages = classes_stages(p)
    stage = next(stages)
    while "nominal lengths" not in stage.description:
        stage = stages.send(messy)
    with pytest.raises(StopIteration) as done:
        stages.throw(WorkSpent())
    end, last = done.value.value
    assert np.array_equal(end, messy) and "nominal lengths" not in last.description


def test_the_records():
    """What each objective promises, and its default node limits (measured, objectives.py)."""
    paper, bounded, classes = (OBJECTIVES[name] for name in ("paper", "bounded", "classes"))
    assert [r.name for r in OBJECTIVES.values()] == ["paper", "bounded", "classes"]
    assert (paper.slides, paper.bounds_members, paper.sound_joints) == (False, False, False)
    assert (bounded.slides, bounded.bounds_members, bounded.sound_joints) == (True, True, True)
    assert (classes.slides, classes.bounds_members, classes.sound_joints) == (True, True, True)
    assert paper.max_nodes == {"pardiso": 34_000, "cholmod": 34_000, "superlu": 34_000}
    assert bounded.max_nodes == {"pardiso": 57_000, "cholmod": 57_000, "superlu": 35_000}
    assert classes.max_nodes == {"pardiso": 12_000, "cholmod": 12_000, "superlu": 6_000}
    assert bounded.node_limit("superlu") == 35_000 and bounded.node_limit() == bounded.max_nodes[DEFAULT_FACTORISATION]
    assert paper.stages is paper_stages and bounded.stages is bounded_stages and classes.stages is classes_stages


def test_classes_runs_a_second_series_from_a_remap_that_kept_the_lattice():
    """At l = 10 the flat grid's edges are exactly l (24 of 33 members, two classes): bounded ends at a point with
    more classes, so after the rounds from it come rounds from the remapped start, nominals from its classes; a
    round of those answered with the start keeps it."""
    p, _ = problem(rise=0.0, slides=True, length=10.0)
    messy = moved(p, 4, size=0.004)
    assert documented_key(p, p.x0)[:2] == (0, 2) and documented_key(p, messy)[1] > 2
    answer, rounds = answers_for_classes(messy, lambda k: messy if k < CLASSES_ROUNDS else p.x0)
    seen, (end, last) = drive(classes_stages(p), answer)
    assert len(rounds) == 2 * CLASSES_ROUNDS
    np.testing.assert_array_equal(rounds[CLASSES_ROUNDS].start, p.x0)
    nominal = start_nominals(p, p.x0)
    np.testing.assert_allclose(nominal, [TARGET, 1.0 + np.sqrt(2.0) - 1.0], rtol=1e-12)
    np.testing.assert_allclose(
        rounds[CLASSES_ROUNDS].residuals(p.x0),
        round_residuals(p, p.x0, nominal, 0.5 * p.tolerance),
        rtol=1e-9,
        atol=1e-15,
    )  # the rounds from the remap keep half the tolerance from their first on
    assert last is rounds[CLASSES_ROUNDS] and np.array_equal(end, p.x0)


def test_classes_keeps_to_one_series_where_the_remap_lost_the_lattice():
    """At l = 8 no member of the start lies within the tolerance of l: no rounds from it, however few its
    classes."""
    p, _ = problem(rise=0.0, slides=True, length=8.0)
    messy = moved(p, 4, size=0.004)
    answer, rounds = answers_for_classes(messy, lambda k: messy)
    drive(classes_stages(p), answer)
    assert len(rounds) == CLASSES_ROUNDS


def test_a_second_series_outside_the_band_is_solved_on_with_the_penalty():
    """Rounds from the remap all ending a hair below l with its two classes: the first of them, the fewest classes
    outside [l, 2l], is solved on with the members' band penalty added (a hard constraint), from there; answered
    with the start, that end is kept."""
    p, _ = problem(rise=0.0, slides=True, length=10.0)
    messy, low = moved(p, 4, size=0.004), moved(p, 5, size=1e-5)
    r = ratio(p, low)
    assert r.min() < 1.0 - 1e-9 and documented_key(p, low)[:2] == (0, 2)
    answer, rounds = answers_for_classes(messy, lambda k: messy if k < CLASSES_ROUNDS else low)
    solved_on = "into [l, 2l] by a penalty"
    seen, (end, last) = drive(classes_stages(p), lambda k, s: p.x0 if solved_on in s.description else answer(k, s))
    penalty = seen[-1]
    assert penalty.description == "members to the nearest of 2 nominal lengths and into [l, 2l] by a penalty"
    np.testing.assert_array_equal(penalty.start, low)
    assert penalty.ftol == BOUNDED_FTOL and penalty.feasible(p.x0) and not penalty.feasible(low)
    low_end, smooth = 1.0 + 0.5 * BOUNDED_OFFSET, 0.25 * BOUNDED_OFFSET
    depth = np.maximum(0.0, low_end - ratio(p, p.x0))
    psi = np.where(depth < smooth, depth**2 / (2 * smooth), depth - smooth / 2)
    nominal = start_nominals(p, p.x0)
    expected = np.concatenate([round_residuals(p, p.x0, nominal, 0.5 * p.tolerance), BOUNDED_PENALTY * psi])
    np.testing.assert_allclose(penalty.residuals(p.x0), expected, rtol=1e-9, atol=1e-12)
    assert last is penalty and np.array_equal(end, p.x0)


def classes_answered(p, bounded_end, first, second, solved_on):
    """Drive classes_stages: bounded's stages with ``bounded_end``, the first series' rounds with ``first(k)``, the
    second's with ``second(k)`` and a stage solved on with the band penalty with ``solved_on``; the stages seen,
    the end, and the stages solved on."""
    rounds, penalties = [], []

    def answer(k, stage):
        if "into [l, 2l] by a penalty" in stage.description:
            penalties.append(stage)
            return solved_on
        if "nominal lengths" not in stage.description:
            return bounded_end
        rounds.append(stage)
        k = len(rounds) - 1
        return first(k) if k < CLASSES_ROUNDS else second(k - CLASSES_ROUNDS)

    seen, result = drive(classes_stages(p), answer)
    return seen, result, rounds, penalties


def test_a_round_end_outside_that_a_later_one_inside_matches_is_not_solved_on():
    """The second series' first round ends a hair below l with the start's two classes, its second at the start
    itself (two classes, in [l, 2l], the same key): the best is as good, so nothing is solved on."""
    p, _ = problem(rise=0.0, slides=True, length=10.0)
    messy, low = moved(p, 4, size=0.004), moved(p, 5, size=1e-5)
    assert documented_key(p, low) == documented_key(p, p.x0)
    seen, (end, last), rounds, penalties = classes_answered(
        p, messy, lambda k: messy, lambda k: low if k == 0 else p.x0, p.x0
    )
    assert not penalties and last is rounds[CLASSES_ROUNDS + 1] and np.array_equal(end, p.x0)


def test_the_penalty_stage_keeps_the_rounds_trust_region_and_names_its_violation():
    p, _ = problem(rise=0.0, slides=True, length=10.0)
    messy, low = moved(p, 4, size=0.004), moved(p, 5, size=1e-5)
    _, _, rounds, penalties = classes_answered(p, messy, lambda k: messy, lambda k: low, p.x0)
    (penalty,) = penalties
    step = np.zeros(len(p.x0))
    step[0] = 1.0
    np.testing.assert_array_equal(penalty.limit(step), rounds[0].limit(step))
    assert re.fullmatch(r"\d+ of 33 members outside \[l, 2l\] \(lengths from .* l to .* l\)", penalty.violation(low))


@pytest.mark.parametrize("sound", [True, False])
def test_a_penalty_solve_that_ends_outside_or_unsound_is_not_kept(sound):
    """Solved on with the penalty, the end is kept only in [l, 2l] and with sound joints: ending outside (or,
    with joints that the start breaks, at the start), bounded's result stays the result."""
    p, triangles = problem(rise=0.0, slides=True, length=10.0)
    messy, low = moved(p, 4, size=0.004), moved(p, 5, size=1e-5)
    if sound:
        end_there = low  # outside [l, 2l]
    else:
        p = replace(p, joints=Joints(p, triangles, surface_angles(p.points_of(low), triangles)))
        assert p.sound(low) and not p.sound(p.x0)  # the start's angles are below low's somewhere
        end_there = p.x0
    _, (end, last), _, penalties = classes_answered(p, messy, lambda k: messy, lambda k: low, end_there)
    assert len(penalties) == 1 and "nominal lengths" not in last.description and np.array_equal(end, messy)


def test_a_penalty_solve_that_ends_as_good_as_the_best_is_not_kept():
    """At l = 9.5 bounded ends in [l, 2l] with 10 classes, every round with 6 and one member below l (node 12 moved
    along u): solved on with the penalty and answered with bounded's end itself (the same key), the best stays
    bounded's, its stage too; answered with the start (2 classes), the start is kept with the penalty's stage."""
    p, _ = problem(rise=0.0, slides=True, length=9.5)
    messy, out = moved(p, 4, size=0.004), p.x0.copy()
    out[0] += 0.03  # node 12 along u by 0.9: its member towards node 11 is 9.1 long, below l
    assert documented_key(p, messy)[1] == 10 and documented_key(p, out)[1] == 6 and not Members.inside(ratio(p, out))
    seen, (end, last), _, penalties = classes_answered(p, messy, lambda k: out, lambda k: messy, messy)
    assert len(penalties) == 1 and last is not penalties[0] and "nominal lengths" not in last.description
    assert np.array_equal(end, messy)
    seen, (end, last), _, penalties = classes_answered(p, messy, lambda k: out, lambda k: messy, p.x0)
    assert len(penalties) == 1 and last is penalties[0] and np.array_equal(end, p.x0)


def test_a_penalty_solve_kept_leaves_its_key_in_the_best():
    """The rounds driven alone from bounded's end (10 classes) with the catalogue (1.0526 l): every round ends with
    6 classes, one member below l; the penalty solve, answered with the start (2 classes, its 9 diagonals off the
    catalogue), is kept with its own key (the one later rounds must beat), members off the catalogue counted."""
    p, _ = problem(rise=0.0, slides=True, length=9.5)
    p = replace(p, catalogue=np.array([10.0 / 9.5]))
    messy, out = moved(p, 4, size=0.004), p.x0.copy()
    out[0] += 0.03
    members = Members(p)
    best = {"x": messy, "stage": None, "key": class_key(ratio(p, messy), p.tolerance, p.catalogue)}
    assert documented_key(p, messy)[1] == 10 and documented_key(p, out)[1] == 6
    assert best["key"][0] > documented_key(p, out)[0] and documented_key(p, p.x0)[:2] == (9, 2)
    solved_on = "into [l, 2l] by a penalty"
    seen, spent = drive(
        class_rounds(p, members, messy, best, class_scale), lambda k, s: p.x0 if solved_on in s.description else out
    )
    assert spent is False and solved_on in seen[-1].description and best["stage"] is seen[-1]
    assert np.array_equal(best["x"], p.x0) and best["key"] == documented_key(p, p.x0)


def test_the_work_bound_in_the_penalty_solve_ends_the_classes_at_once():
    p, _ = problem(rise=0.0, slides=True, length=10.0)
    messy, low = moved(p, 4, size=0.004), moved(p, 5, size=1e-5)
    stages = classes_stages(p)
    stage, rounds = next(stages), 0
    while "into [l, 2l] by a penalty" not in stage.description:
        if "nominal lengths" in stage.description:
            rounds += 1
        stage = stages.send(low if rounds > CLASSES_ROUNDS else messy)
    with pytest.raises(StopIteration) as done:
        stages.throw(WorkSpent())
    assert np.array_equal(done.value.value[0], messy)


def test_no_second_series_from_a_remap_with_more_members_off_the_catalogue():
    """At l = 10 the remap (2 classes, its grid edges at l) starts a second series from bounded's end (10 classes)
    without a catalogue; with a catalogue of bounded's end's nominal lengths away from both of the remap's lengths
    every one of its members is off it, more than at bounded's end: its key is worse, members off the catalogue
    counted first, and no rounds start there."""
    p, _ = problem(rise=0.0, slides=True, length=10.0)
    messy = moved(p, 4, size=0.004)
    assert documented_key(p, messy)[1] == 10
    assert len(classes_answered(p, messy, lambda k: messy, lambda k: messy, messy)[2]) == 2 * CLASSES_ROUNDS
    nominal = length_classes(ratio(p, messy), 1.0, p.tolerance).nominal
    away = np.min(np.abs(nominal[:, None] - np.array([1.0, np.sqrt(2.0)])[None, :]), axis=1) > p.tolerance
    p = replace(p, catalogue=nominal[away])
    assert documented_key(p, p.x0)[:2] == (33, 2) and documented_key(p, messy)[0] < 33
    _, _, rounds, _ = classes_answered(p, messy, lambda k: messy, lambda k: messy, messy)
    assert len(rounds) == CLASSES_ROUNDS


def test_no_second_series_from_a_remap_with_as_many_classes():
    """A remap with no fewer classes than bounded's result starts no rounds of its own."""
    p, _ = problem(rise=0.0, slides=True, length=10.0)
    _, _, rounds, _ = classes_answered(p, p.x0, lambda k: p.x0, lambda k: p.x0, p.x0)
    assert len(rounds) == CLASSES_ROUNDS


def test_a_penalty_solve_after_the_first_series_is_kept_and_the_second_series_follows():
    """The first series' rounds all end a hair below l with two classes: solved on with the penalty and answered
    with a point in [l, 2l] with two classes, that point is the best so far, and the rounds from the remap follow
    (none beats it: answered with bounded's end).  The work bound thrown into that penalty solve ends the stages
    there, at bounded's end."""
    p, _ = problem(rise=0.0, slides=True, length=10.0)
    messy, low = moved(p, 4, size=0.004), moved(p, 5, size=1e-5)
    seen, (end, last), rounds, penalties = classes_answered(p, messy, lambda k: low, lambda k: messy, p.x0)
    assert len(penalties) == 1 and len(rounds) == 2 * CLASSES_ROUNDS
    assert seen.index(penalties[0]) < seen.index(rounds[CLASSES_ROUNDS])
    assert last is penalties[0] and np.array_equal(end, p.x0)
    stages = classes_stages(p)
    stage = next(stages)
    while "into [l, 2l] by a penalty" not in stage.description:
        stage = stages.send(low if "nominal lengths" in stage.description else messy)
    with pytest.raises(StopIteration) as done:
        stages.throw(WorkSpent())
    assert np.array_equal(done.value.value[0], messy)


def test_of_rounds_in_the_band_the_largest_share_is_kept():
    """At l = 9.9 two rim members at l (nodes 1 and 2 slid to a corner's distance l) against one: the round that
    ended with two within the band of l is the result, although a later one ended with one."""
    p, _ = problem(rise=0.0, slides=True, length=9.9)
    one = p.x0.copy()
    one[8] = 0.33  # node 1 slides to u = 0.33: the member from node 0 is 9.9 = l long
    two = one.copy()
    two[9] = 0.67  # node 2 slides to u = 0.67: the member to node 3 (a corner) is l long too
    for x, count in ((one, 1), (two, 2)):
        assert np.count_nonzero(np.abs(ratio(p, x) - 1.0) <= BOUNDED_BAND) == count
        assert Members.inside(ratio(p, x)) and p.sound(x)
    seen, (end, last) = drive(bounded_stages(p), lambda k, stage: two if k == 0 else one)
    assert last is seen[0] and np.array_equal(end, two)


def test_the_classes_scale_narrows_from_wide_to_half_the_tolerance():
    """Round k's Cauchy scale: CLASSES_SCALE_START tolerance shrunk by CLASSES_SCALE_DECAY a round, never below half
    the tolerance; the rounds of a remap that kept the lattice use half the tolerance from the first."""
    for tolerance in (0.005, 0.01):
        scales = [class_scale(k, tolerance) for k in range(CLASSES_ROUNDS + 40)]
        assert scales[0] == CLASSES_SCALE_START * tolerance and min(scales) == 0.5 * tolerance
        assert all(a >= b for a, b in zip(scales, scales[1:])) and scales[1] == scales[0] * CLASSES_SCALE_DECAY


def test_the_rounds_from_a_remap_that_kept_the_lattice_pull_with_half_the_tolerance():
    """A remap a hair off its lattice (members within about 1e-4 of their nominal): the first round from it weighs
    each member by the Cauchy weight of scale tolerance / 2, which a scale of 1.5 tolerances would not give."""
    p, _ = problem(rise=0.0, slides=True, length=10.0, seed=3, spread=1e-5)
    messy = moved(p, 4, size=0.004)
    assert documented_key(p, p.x0)[:2] == (0, 2) and documented_key(p, messy)[1] > 2
    answer, rounds = answers_for_classes(messy, lambda k: messy)
    drive(classes_stages(p), answer)
    assert len(rounds) == 2 * CLASSES_ROUNDS
    nominal = start_nominals(p, p.x0)
    got = rounds[CLASSES_ROUNDS].residuals(p.x0)
    assert np.abs(got).max() > 0.0
    np.testing.assert_allclose(got, round_residuals(p, p.x0, nominal, 0.5 * p.tolerance), rtol=1e-12, atol=0.0)
    assert not np.allclose(got, round_residuals(p, p.x0, nominal, 1.5 * p.tolerance), rtol=1e-9, atol=0.0)
