"""The final (u, v) optimisation of the inner nodes (Section 4, last paragraph)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from section4_standin import CircularVault, flat_patch, parabolic_vault, standin_pipeline

from equimesh import EquimeshError
from equimesh._geometry import nearest_segment as nearest_segment
from equimesh.mesh import edge_lengths
from equimesh.surface.optimize import OBJECTIVES, Objective, Stage, UVProblem, objectives, optimize_uv
from equimesh.surface.optimize.driver import fold_over_barrier, with_barriers
from equimesh.surface.optimize.jacobian import signed_areas
from equimesh.surface.optimize.objectives import bounded_stages, edge_length_terms, paper_stage
from equimesh.surface.optimize.slide import along_polygon
from equimesh.surface.optimize.solver import FACTORISATIONS
from equimesh.surface.regularity import derivatives
from equimesh.testing.surfaces import dome


def run(surface, l, **kw):
    g, flat, mesh, r = standin_pipeline(surface, l)
    fixed = np.arange(mesh.n_boundary)
    opt = optimize_uv(surface, r.uv, mesh.edges, mesh.edge_groups, l, fixed=fixed, triangles=mesh.triangles, **kw)
    return mesh, r, opt


def problem_for(surface, l, seed, spread=0.01):
    g, flat, mesh, r = standin_pipeline(surface, l, grid=(8, 8))
    free = np.ones(mesh.n_nodes, dtype=bool)
    free[: mesh.n_boundary] = False
    rng = np.random.default_rng(seed)
    uv = r.uv.copy()
    uv[free] = np.clip(uv[free] + spread * rng.standard_normal(uv[free].shape), 0.0, 1.0)
    return mesh, UVProblem(surface, uv, mesh.edges, mesh.edge_groups, l, free)


def finite_difference(fun, x, h=1e-7):
    cols = []
    for k in range(len(x)):
        d = np.zeros_like(x)
        d[k] = h
        cols.append((fun(x + d) - fun(x - d)) / (2 * h))
    return np.column_stack(cols)


@settings(max_examples=6, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_edge_length_jacobian_matches_finite_differences(seed):
    mesh, problem = problem_for(dome(rise=15.0), 12.0, seed)
    lengths, jacobian = edge_length_terms(problem, mesh.edges)
    x = problem.x0
    got_lengths, jac = jacobian(x)
    assert np.array_equal(got_lengths, lengths(x))  # the residuals' lengths, not a second computation
    np.testing.assert_allclose(jac.toarray(), finite_difference(lengths, x), atol=1e-5 * lengths(x).max())


def test_paper_objective_and_barrier_jacobians_match_finite_differences():
    mesh, problem = problem_for(dome(rise=15.0), 12.0, 1)
    obj = paper_stage(problem)
    x = problem.x0
    np.testing.assert_allclose(obj.jacobian(x).toarray(), finite_difference(obj.residuals, x), atol=1e-6)
    barrier = with_barriers(problem, obj, fold_over_barrier(problem, mesh.triangles, 0.9), None, x)
    squeezed = x + 0.03 * np.random.default_rng(2).standard_normal(x.shape)  # some triangles below the floor
    assert np.any(barrier.residuals(squeezed)[len(obj.residuals(x)) :] > 0)
    np.testing.assert_allclose(
        barrier.jacobian(squeezed).toarray(), finite_difference(barrier.residuals, squeezed), atol=1e-5
    )


def sliding_problem():
    """A stand-in dome's problem with its boundary nodes sliding along the unit square (four corners fixed), and the
    plain one."""
    mesh, plain = problem_for(dome(rise=15.0), 12.0, 3)
    square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
    nodes = np.arange(mesh.n_boundary)
    slide, corners = along_polygon(nodes, square, plain.uv[nodes])
    assert len(corners) == 4 and len(slide.nodes) == mesh.n_boundary - 4
    problem = UVProblem(plain.surface, plain.uv, mesh.edges, mesh.edge_groups, 12.0, plain.free, (slide,))
    return mesh, plain, problem, slide


def test_sliding_nodes_jacobians_match_finite_differences():
    """Boundary nodes sliding along the domain's outline by arc position; the chain rule through ``d uv / d
    s``."""
    mesh, plain, problem, slide = sliding_problem()
    x = problem.x0
    assert len(x) == len(plain.x0) + len(slide.nodes)
    np.testing.assert_allclose(problem.uv_of(x), plain.uv, rtol=0, atol=1e-15)
    x = x + np.concatenate([np.zeros(len(plain.x0)), 0.01 * np.random.default_rng(4).standard_normal(len(slide.nodes))])
    obj = paper_stage(problem)
    lengths, jacobian = edge_length_terms(problem, mesh.edges)
    np.testing.assert_allclose(jacobian(x)[1].toarray(), finite_difference(lengths, x), atol=1e-5 * lengths(x).max())
    barrier = with_barriers(problem, obj, fold_over_barrier(problem, mesh.triangles, 0.9), None, x)
    squeezed = x + 0.03 * np.random.default_rng(2).standard_normal(x.shape)
    assert np.any(barrier.residuals(squeezed)[len(obj.residuals(x)) :] > 0)
    expected = finite_difference(barrier.residuals, squeezed)
    np.testing.assert_allclose(barrier.jacobian(squeezed).toarray(), expected, atol=1e-5)


def flipped_triangles(uv_before, uv_after, triangles):
    """Triangles counter-clockwise in (u, v) before but not strictly after (fold-over)."""
    before, after = signed_areas(uv_before, triangles), signed_areas(uv_after, triangles)
    return np.flatnonzero((before > 0) & (after <= 0))


def check_invariants(mesh, r, opt):
    nb = mesh.n_boundary
    assert opt.cost_after <= opt.cost_before
    assert np.array_equal(opt.uv[:nb], r.uv[:nb])  # boundary nodes bit-identical
    assert not len(flipped_triangles(r.uv, opt.uv, mesh.triangles))
    assert np.all((opt.uv >= 0) & (opt.uv <= 1))


@settings(max_examples=5, deadline=None)
@given(
    rise=st.floats(min_value=0.0, max_value=20.0),
    seed=st.integers(0, 2**32 - 1),
    l=st.floats(min_value=5.0, max_value=9.0),
)
def test_invariants_on_mild_domes(rise, seed, l):
    """G1 deviation after <= before, boundary fixed, no fold-over in (u, v)."""
    surface = dome(rise=rise, seed=seed, jitter=2.0)
    mesh, r, opt = run(surface, l)
    check_invariants(mesh, r, opt)
    before = edge_lengths(r.points, mesh.edges)[mesh.g1_mask]
    after = edge_lengths(surface.evaluate(opt.uv[:, 0], opt.uv[:, 1]), mesh.edges)[mesh.g1_mask]
    assert np.sum((after - l) ** 2) <= np.sum((before - l) ** 2) * (1 + 1e-12)


def test_developable_vault_reaches_target_length():
    surface = parabolic_vault()
    mesh, r, opt = run(surface, 5.0)
    check_invariants(mesh, r, opt)
    g1 = edge_lengths(surface.evaluate(opt.uv[:, 0], opt.uv[:, 1]), mesh.edges)[mesh.g1_mask]
    before = edge_lengths(r.points, mesh.edges)[mesh.g1_mask]
    assert np.abs(before / 5.0 - 1).max() > 1e-4  # remapping alone is not exact
    assert np.abs(g1 / 5.0 - 1).max() < 1e-3


def test_any_parametric_surface_works_circular_vault():
    """A non-Bezier surface with the same two methods goes through every stage; a circle is developable."""
    surface = CircularVault()
    g, flat, mesh, r = standin_pipeline(surface, 5.0)
    fixed = np.arange(mesh.n_boundary)
    opt = optimize_uv(surface, r.uv, mesh.edges, mesh.edge_groups, 5.0, fixed=fixed, triangles=mesh.triangles)
    check_invariants(mesh, r, opt)
    g1 = edge_lengths(surface.evaluate(opt.uv[:, 0], opt.uv[:, 1]), mesh.edges)[mesh.g1_mask]
    assert np.abs(g1 / 5.0 - 1).max() < 1e-3


def test_flat_surface_is_already_optimal():
    surface = flat_patch()
    mesh, r, opt = run(surface, 3.0)
    assert opt.cost_before < 1e-20 and opt.cost_after <= opt.cost_before
    np.testing.assert_allclose(opt.uv, r.uv, atol=1e-12)


def test_acceptance_guard_without_barrier():
    """Without the barrier only the solver's acceptance test stands between the steps and a fold-over."""
    mesh, r, opt = run(dome(rise=20.0), 5.0, area_floor=0.0)
    check_invariants(mesh, r, opt)
    assert opt.converged


def test_bounded_objective_jacobian_matches_finite_differences(monkeypatch):
    """The stages in order; a round (members pulled in from outside the band, Cauchy-weighted inside) and the penalised
    last stage."""
    monkeypatch.setattr(objectives, "BOUNDED_ROUNDS", 1)  # each series of rounds is one round
    mesh, problem = problem_for(dome(rise=15.0), 12.0, 3, spread=0.03)
    x = problem.x0
    stages = bounded_stages(problem)
    first = next(stages)  # round 1 from the remapped mesh
    ratio = edge_lengths(problem.surface.evaluate(*problem.uv.T), mesh.edges) / 12.0
    assert np.any(ratio < 1.0) and first.max_iterations == objectives.BOUNDED_ROUND_ITERATIONS  # some pulled in
    paper = stages.send(x)  # the paper's objective from the remapped mesh, boundary nodes held
    assert np.array_equal(paper.start, x) and paper.hold.shape == x.shape
    released = stages.send(x)  # its share beats no kept point: the boundary nodes are released
    assert released.hold is None and released.start is None
    second = stages.send(x)  # round 1 from the paper's optimum
    assert second.max_iterations == objectives.BOUNDED_ROUND_ITERATIONS
    last = stages.send(x)  # no round ended in [l, 2l]
    assert last.feasible is not None and np.any(last.residuals(x)[len(mesh.edges) :] > 0)  # the penalty acts
    with pytest.raises(StopIteration) as done:
        stages.send(x)
    assert done.value.value[1] is last  # the last stage's point and costs are the result
    for stage in (first, last):
        np.testing.assert_allclose(stage.jacobian(x).toarray(), finite_difference(stage.residuals, x), atol=1e-4)


def test_objective_table_is_the_seam(monkeypatch):
    """A new objective record with its stages is picked up by name."""
    calls = []

    def all_edges(problem):
        calls.append(problem)
        lengths, jacobian = edge_length_terms(problem, problem.edges)
        stage = Stage(lambda x: lengths(x) / problem.length - 1.0, lambda x: jacobian(x)[1] / problem.length)
        x = yield stage
        return x, stage

    limits = dict.fromkeys(FACTORISATIONS, 100)
    record = Objective(
        "all",
        all_edges,
        "every member to l",
        slides=False,
        bounds_members=False,
        sound_joints=False,
        max_nodes=limits,
        max_jacobians=501,
    )
    monkeypatch.setitem(OBJECTIVES, "all", record)
    mesh, r, opt = run(dome(), 8.0, objective="all")
    assert calls and opt.objective == "all"
    check_invariants(mesh, r, opt)


def test_unknown_objective():
    with pytest.raises(EquimeshError, match="unknown objective 'nope'"):
        optimize_uv(dome(), np.zeros((3, 2)), np.array([[0, 1]]), np.array([1]), 1.0, fixed=[0], objective="nope")


def test_no_free_nodes_is_a_no_op():
    uv = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    opt = optimize_uv(dome(), uv, np.array([[0, 1], [1, 2], [0, 2]]), np.array([1, 1, 1]), 5.0, fixed=[0, 1, 2])
    assert np.array_equal(opt.uv, uv) and opt.cost_after == opt.cost_before and opt.nfev == 0


@settings(max_examples=5, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), radius=st.floats(0.05, 3.0))
def test_step_limit_is_a_trust_region_per_node(seed, radius):
    """``UVProblem.step_limit``: no node moves further than ``radius`` on the surface (to first order, measured
    by ``|X_u| du`` and ``|X_v| dv`` at its start), a limited node keeps its (u, v) direction, a node within
    the radius is untouched; sliding nodes (one arc variable each) are limited the same way."""
    _, _, problem, slide = sliding_problem()
    direction = np.random.default_rng(seed).standard_normal(len(problem.x0)) * 0.05
    step = problem.step_limit(radius)(direction)
    su, sv = derivatives(problem.surface, problem.uv)
    tangent = np.column_stack([np.linalg.norm(su, axis=1), np.linalg.norm(sv, axis=1)])

    def moves(d):
        """Per node: its (u, v) step (zero for a fixed node) and its move on the surface to first order."""
        n = int(problem.variables.sum())
        duv = np.zeros(problem.uv.size)
        duv[problem.variables] = d[:n]
        duv = duv.reshape(-1, 2)
        move = np.linalg.norm(duv * tangent, axis=1)
        move[slide.nodes] = np.abs(d[n:]) * tangent[slide.nodes].max(axis=1)
        duv[slide.nodes, 0] = d[n:]
        return duv, move

    before, move_before = moves(direction)
    after, move_after = moves(step)
    assert np.all(move_after <= radius * (1 + 1e-12))
    inside = move_before <= radius
    assert np.array_equal(after[inside], before[inside])
    assert np.any(~inside)  # the draw exercises the limit
    ratio = move_after[~inside] / move_before[~inside]
    np.testing.assert_allclose(after[~inside], before[~inside] * ratio[:, None], rtol=1e-12)
    np.testing.assert_allclose(move_after[~inside], radius, rtol=1e-12)
