"""Sound joints (``surface/optimize/joints.py``): every triangle angle on the surface at least its bound.

What must hold: the angles are the metrics' angles; the barrier's Jacobian is its derivative, on the surface, with
sliding nodes and with nodes off the surface; the bounds are 30 degrees except at a corner sharper than that; an
objective that cannot reach the bounds is refused, and a mesh that breaks them is never returned.
"""

from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse
from test_objectives import finite_difference, run, sliding_problem

import equimesh
from equimesh import InternalError, InvalidSurfaceError
from equimesh.metrics import triangle_angles
from equimesh.surface import pipeline
from equimesh.surface.optimize import OBJECTIVES, Objective, Stage, joints, optimize_uv
from equimesh.surface.optimize.joints import Joints, joint_bounds, surface_angles
from equimesh.surface.optimize.objectives import edge_length_terms
from equimesh.surface.optimize.solver import FACTORISATIONS
from equimesh.testing.surfaces import dome


def perturbed(problem, seed, offset=0.0):
    """The problem's start moved a little (and its offsets set to about ``offset``)."""
    rng = np.random.default_rng(seed)
    x = problem.x0 + 0.01 * rng.standard_normal(len(problem.x0))
    k = len(problem.offset_nodes)
    if k:
        x[len(x) - k :] = offset * rng.uniform(-1.0, 1.0, k)
    return x


def test_surface_angles_are_the_metrics_angles():
    mesh, plain, problem, _ = sliding_problem()
    points = problem.points_of(problem.x0)
    np.testing.assert_allclose(
        np.degrees(surface_angles(points, mesh.triangles)), triangle_angles(points, mesh.triangles), atol=1e-9
    )


@pytest.mark.parametrize("tolerance, offset", [(0.0, 0.0), (0.8, 0.6)], ids=["on the surface", "off the surface"])
def test_barrier_and_length_jacobians_match_finite_differences(tolerance, offset):
    """With sliding boundary nodes, and with offsets along the normal large enough that the normal's own derivative
    counts."""
    mesh, _, sliding, _ = sliding_problem()
    problem = replace(sliding, surface_tolerance=tolerance)
    x = perturbed(problem, 5, offset)
    lengths, jacobian = edge_length_terms(problem, mesh.edges)
    np.testing.assert_allclose(jacobian(x)[1].toarray(), finite_difference(lengths, x), atol=1e-5 * lengths(x).max())
    bounds = np.full(mesh.triangles.shape, np.radians(58.0))  # most angles within a degree of it: the barrier acts
    residuals, barrier = Joints(problem, mesh.triangles, bounds).barrier(3.0)
    assert np.count_nonzero(residuals(x)) > 10
    expected = finite_difference(residuals, x)
    np.testing.assert_allclose(barrier(x).toarray(), expected, atol=1e-6 * np.abs(expected).max())


def test_bounds_are_30_degrees_but_at_a_sharper_corner():
    """A node whose angles sum to less than 30 degrees (a corner of the input) bounds its angles by that sum less
    the barrier's margin; every other angle is bounded by 30 degrees."""
    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [10.0, 2.0, 0.0]])
    triangles = np.array([[0, 1, 2], [1, 3, 2]])

    class Flat:
        def evaluate(self, u, v):
            return np.column_stack([u, v, np.zeros_like(u)])

        def derivatives(self, u, v):
            one, zero = np.ones_like(u), np.zeros_like(u)
            return np.column_stack([one, zero, zero]), np.column_stack([zero, one, zero])

    bounds = np.degrees(joint_bounds(Flat(), points[:, :2], triangles))
    angles = triangle_angles(points, triangles)
    sharp = angles[1, 1]  # node 3 is in one triangle only, with an angle of about 8 degrees
    assert sharp < 30 and angles[1, 0] + angles[0, 1] > 30 and angles[1, 2] + angles[0, 2] > 30
    assert bounds[1, 1] == pytest.approx(sharp - np.degrees(joints.JOINT_MARGIN))
    np.testing.assert_allclose(np.delete(bounds.ravel(), 4), 30.0, rtol=1e-14)


def saddle(l=6.0):
    return equimesh.load_surface("experiments/surfaces/saddle.json"), l


def test_bounds_out_of_reach_are_refused(monkeypatch):
    """The check fires: an objective with sound joints whose stages end with an angle below its bound is refused in
    the surface's terms, naming the angles."""

    def idle(problem):
        stage = Stage(lambda x: np.zeros(1), lambda x: scipy.sparse.csr_matrix((1, len(x))), max_iterations=0)
        x = yield stage
        return x, stage

    record = Objective(
        "idle",
        idle,
        "nothing",
        slides=False,
        bounds_members=False,
        sound_joints=True,
        max_nodes=dict.fromkeys(FACTORISATIONS, 100),
        max_jacobians=10,
    )
    monkeypatch.setitem(OBJECTIVES, "idle", record)
    monkeypatch.setattr(joints, "JOINT_ANGLE", 59.0)  # the stand-in's strip has angles below 59 degrees
    mesh, r, _ = run(dome(), 8.0, objective="paper")
    with pytest.raises(InvalidSurfaceError, match=r"no mesh with every triangle angle at least 30 degrees.*below 59"):
        optimize_uv(
            dome(),
            r.uv,
            mesh.edges,
            mesh.edge_groups,
            8.0,
            fixed=np.arange(mesh.n_boundary),
            triangles=mesh.triangles,
            objective="idle",
        )


def test_a_mesh_with_an_unsound_joint_is_never_returned(monkeypatch):
    """The pipeline checks the angles of every mesh an objective with sound joints returns: an optimisation that
    squeezes a triangle is an InternalError, not a mesh."""
    real = pipeline.optimize_uv

    def squeezing(*args, **kwargs):
        result = real(*args, **kwargs)
        uv = result.uv.copy()
        tri = kwargs["triangles"][0]
        uv[tri[2]] = uv[tri[0]] + 0.97 * (uv[tri[1]] - uv[tri[0]]) + 1e-3 * (uv[tri[2]] - uv[tri[0]])
        return replace(result, uv=uv)

    monkeypatch.setattr(pipeline, "optimize_uv", squeezing)
    monkeypatch.setattr(pipeline, "check_orientation", lambda *args: None)
    monkeypatch.setattr(pipeline, "check_members", lambda *args: None)
    surface, l = saddle()
    with pytest.raises(InternalError, match="angle below its bound"):
        equimesh.mesh_surface(surface, l, grid=(8, 8), optimize="classes")


def test_the_papers_objective_keeps_its_angles_unbounded():
    """ "paper" is the paper's: no angle barrier, no angle check (its result on a steep dome has slivers)."""
    records = equimesh.surface.optimize.OBJECTIVES
    assert records["classes"].sound_joints and not records["paper"].sound_joints and not records["bounded"].sound_joints
    mesh = equimesh.mesh_surface(dome(rise=40.0), 8.0, optimize="paper", grid=(8, 8))
    assert triangle_angles(mesh.points, mesh.triangles).min() < 30.0
