"""The "bounded" objective (beyond the paper): every member in [l, 2l], most of them at one length."""

import os

import numpy as np
import pandas as pd
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from repository import SURFACES
from section4_standin import parabolic_vault

from equimesh import InternalError
from equimesh.errors import InvalidSurfaceError
from equimesh.io import load_surface
from equimesh.io.provenance import provenance
from equimesh.mesh import G1
from equimesh.metrics import triangle_angles
from equimesh.surface import pipeline
from equimesh.surface.optimize import optimize_uv
from equimesh.surface.optimize.problem import parameter_box
from equimesh.surface.pipeline import mesh_surface
from equimesh.testing.surfaces import dome
from equimesh.tolerance import JOINT_ANGLE

#: "Within 0.5 % of l": what counts as an exact member.
BAND = 0.005


def share_exact(mesh):
    ratio = mesh.edge_lengths() / mesh.length
    return float(np.mean(np.abs(ratio - 1.0) <= BAND))


def in_bounds(mesh):
    ratio = mesh.edge_lengths() / mesh.length
    return bool(np.all((ratio >= 1.0) & (ratio <= 2.0)))


#: What sound joints may cost bounded against the paper's share within 0.5 % of l: the paper's optimum is not a
#: point bounded may end at (on the 7 domes where bounded trails it, 37-41 % of its members outside [l, 2l] and
#: smallest angles of 15 to 19 degrees), so its share is no bound.  Two and a half members in a hundred: domes 0 to
#: 240 of ``python experiments/bounded_sweep.py --count 441`` trail by at most 0.0192 (dome 180), the next 200 not at
#: all (docs/decisions.md, "Two starts for bounded, and the best point kept").
SOUND_COST = 0.025

#: Generated patches per run: a few in the ci profile (each costs a "bounded" and a "paper" mesh,
#: about 2 s), more in the thorough one.
EXAMPLES = {"thorough": 60}.get(os.environ.get("EQUIMESH_HYPOTHESIS_PROFILE", "ci"), 3)


@settings(max_examples=EXAMPLES, deadline=None)
@given(
    rise=st.floats(min_value=2.0, max_value=15.0),
    seed=st.integers(0, 2**32 - 1),
    l=st.floats(min_value=4.5, max_value=5.0),
)
# Rounds from the remapped mesh alone crawled here for 200 rounds with one member at 2.005 l and the last
# stage ended at 0.462 against the paper's 0.654 (docs/decisions.md, "The bounded objective").
@example(rise=8.623446459779622, seed=2893441600, l=4.876515103851089)
# Dome 3 of experiments/bounded_sweep.py, where the bounded share fell below the paper's without the trust region per
# node (docs/decisions.md, "Two starts for bounded, and the best point kept" and "A trust region per node").
@example(rise=6.326581062262999, seed=2437408156, l=4.593367092801857)
# Dome 180 of experiments/bounded_sweep.py, where bounded trails the paper's share most under sound joints: 0.6880
# against 0.7073.
@example(rise=7.5449186591664645, seed=3130914487, l=4.865769583295538)
def test_bounded_keeps_members_in_bounds_and_reaches_the_papers_share(rise, seed, l):
    """Mildly curved Bezier patches: 100 % of the members in [l, 2l], every angle at least 30 degrees, and a share
    within 0.5 % of l at least the paper's less ``SOUND_COST``."""
    surface = dome(rise=rise, seed=seed, jitter=1.0)
    bounded, paper = (mesh_surface(surface, l, optimize=o, placement="default") for o in ("bounded", "paper"))
    assert in_bounds(bounded)
    assert triangle_angles(bounded.points, bounded.triangles).min() >= JOINT_ANGLE
    assert share_exact(bounded) >= share_exact(paper) - SOUND_COST


@pytest.mark.parametrize("rise", [2.0, 4.0, 8.0, 12.0, 15.0])
def test_bounded_reaches_the_papers_share_on_the_stand_in_domes(rise):
    """Rise 2 to 15 over 60, l = 4.5: paper 0.73, 0.73, 0.65, 0.31, 0.20; bounded 0.82, 0.78, 0.73, 0.67, 0.68."""
    surface = dome(rise=rise, seed=0, jitter=1.0)
    bounded, paper = (mesh_surface(surface, 4.5, optimize=o, placement="default") for o in ("bounded", "paper"))
    assert in_bounds(bounded)
    assert share_exact(bounded) >= share_exact(paper)


def test_bounded_beats_paper_on_a_doubly_curved_dome():
    """Rise 15 over 60: the paper's objective leaves 0.20 of the members within 0.5 % of l, bounded 0.68."""
    surface = dome(rise=15.0, seed=0, jitter=1.0)
    bounded, paper = (mesh_surface(surface, 4.5, optimize=o, placement="default") for o in ("bounded", "paper"))
    assert in_bounds(bounded) and not in_bounds(paper)
    assert share_exact(bounded) >= share_exact(paper) + 0.4


def test_developable_vault_reaches_three_quarters():
    """A developable surface: lattice members can all be exact (target: >= 75 % within 0.5 %, docs/decisions.md, "The
    bounded objective")."""
    mesh = mesh_surface(parabolic_vault(), 60.0 / 17)
    assert in_bounds(mesh)
    assert share_exact(mesh) >= 0.75


def test_boundary_nodes_slide_along_their_side_and_corners_stay():
    surface = dome(rise=12.0)
    none = mesh_surface(surface, 5.0, optimize="none", placement="default")
    mesh = mesh_surface(surface, 5.0, placement="default")
    nb = mesh.n_boundary
    before, after = none.uv[:nb], mesh.uv[:nb]
    lower, upper = parameter_box(surface)
    on_side = (before == lower) | (before == upper)
    assert np.array_equal(after[on_side], before[on_side])  # the side's coordinate is kept bit for bit
    moved = np.any(after != before, axis=1)
    assert moved.any()  # they do slide
    corners = np.all(on_side, axis=1)
    assert corners.sum() == 4 and not moved[corners].any()


def test_deterministic():
    surface = dome(rise=10.0)
    a, b = (mesh_surface(surface, 6.0, placement="default") for _ in range(2))
    assert np.array_equal(a.uv, b.uv)


def test_no_feasible_mesh_is_a_clear_error():
    """Two fixed nodes 0.5 l apart: no member between them can reach [l, 2l]."""
    surface = dome(size=10.0, rise=0.0)
    uv = np.array([[0.0, 0.0], [0.05, 0.0], [0.05, 0.05]])
    edges = np.array([[0, 1], [1, 2], [0, 2]])
    with pytest.raises(InvalidSurfaceError, match=r"optimisation \(bounded\): no mesh with every member in \[l, 2l\]"):
        optimize_uv(surface, uv, edges, np.zeros(3), 1.0, fixed=[0, 1], objective="bounded")


@pytest.mark.parametrize("objective", ["bounded", "classes"])
def test_a_start_with_no_free_node_is_held_to_the_band(objective):
    """The reference dome at l = 83: its flattened sides are longer than l, their chords on the surface (80) shorter,
    and every node is a corner, so nothing can move: refused as any end outside [l, 2l] is, never returned."""
    surface = load_surface(SURFACES / "reference_dome.json")
    with pytest.raises(InvalidSurfaceError, match=r"no mesh with every member in \[l, 2l\] found, no node free"):
        mesh_surface(surface, 83.0, optimize=objective)
    assert mesh_surface(surface, 83.0, optimize="paper").stages.optimization.message == "no free nodes"


def test_a_member_outside_the_bounds_is_an_internal_error(monkeypatch):
    """The pipeline checks the guarantee on the returned mesh: a broken optimiser cannot slip through."""
    real = pipeline.optimize_uv

    def broken(*args, **kwargs):
        result = real(*args, **kwargs)
        squeezed = result.uv.copy()
        boundary = np.concatenate([kwargs["fixed"], *(slide.nodes for slide in kwargs["slides"])])
        inner = np.setdiff1d(np.arange(len(squeezed)), boundary)
        squeezed[inner] = 0.5 * squeezed[inner] + 0.25  # shrink inside
        return type(result)(squeezed, *(getattr(result, f) for f in result.__dataclass_fields__ if f != "uv"))

    monkeypatch.setattr(pipeline, "optimize_uv", broken)
    with pytest.raises(InternalError, match=r"outside \[l, 2l\]"):
        mesh_surface(dome(rise=5.0), 8.0, placement="default")


def test_experiment_measures_a_surface_and_reports_the_target(load_experiment):
    """experiments/bounded.py on its developable barrel vault: a row that meets the developable target."""
    bounded = load_experiment("bounded")
    row = bounded._measure(("barrel vault", True, 16, "bounded"))
    assert row["share_in_l_2l"] == 1.0 and row["share_within_0.5pct"] >= bounded.DEVELOPABLE_TARGET
    report = bounded.summarize(pd.DataFrame([row]), provenance({}))
    assert "| barrel vault | span/16 = 5 | bounded |" in report and report.count("| yes |") == 1


def test_the_papers_stage_holds_the_boundary_nodes(monkeypatch):
    """The paper's optimum that "bounded" compares with holds the boundary as the paper does (the sliding boundary
    nodes stay put) and keeps the joints sound: its residuals are the G1 members', one of the fold-over barrier per
    triangle and one of the angle barrier per angle."""
    from equimesh.surface.optimize import driver

    calls = []
    real = driver.least_squares

    def spy(residuals, jacobian, x0, lower, upper, **kwargs):
        solution = real(residuals, jacobian, x0, lower, upper, **kwargs)
        calls.append((np.array(x0), lower == upper, solution.x, len(residuals(x0))))
        return solution

    monkeypatch.setattr(driver, "least_squares", spy)
    mesh = mesh_surface(dome(rise=12.0), 5.0, placement="default")
    held = [(x0, h, x, n) for x0, h, x, n in calls if h.any()]
    assert len(held) == 1  # one solve of the paper's objective
    x0, h, x, n = held[0]
    assert n == np.count_nonzero(mesh.edge_groups == G1) + 4 * len(mesh.triangles)
    assert h.sum() == mesh.n_boundary - 4  # every boundary node but the corners has one variable, held
    assert np.array_equal(x[h], x0[h]) and not np.array_equal(x[~h], x0[~h])
