"""Nodes off the surface within a tolerance (``mesh_surface(surface_tolerance=D)``).

What must hold: with D > 0 every node lies within D of the surface along its normal (and the members in [l, 2l], the
angles sound), the deviation is reported; D = 0 is the default mesh bit for bit; a bad D is refused in one line; a
mesh with a node beyond D is never returned.
"""

from dataclasses import replace

import numpy as np
import pytest

import equimesh
from equimesh import InternalError, InvalidToleranceError
from equimesh.errors import EquimeshError
from equimesh.metrics import triangle_angles
from equimesh.surface import pipeline
from equimesh.surface.regularity import evaluate
from equimesh.testing.surfaces import dome

L = 8.0


@pytest.fixture(scope="module")
def surface():
    return dome(rise=10.0, seed=1, jitter=1.0)


@pytest.mark.parametrize("fraction", [0.005, 0.02])
def test_nodes_stay_within_the_tolerance(surface, fraction):
    d = fraction * L
    mesh = equimesh.mesh_surface(surface, L, optimize="classes", surface_tolerance=d, grid=(8, 8))
    on = evaluate(surface, mesh.uv)
    distance = np.linalg.norm(mesh.points - on, axis=1)
    assert distance.max() <= d * (1 + 1e-9)
    np.testing.assert_allclose(distance, np.abs(mesh.offsets), rtol=0, atol=1e-9 * L)
    assert mesh.deviation() == (pytest.approx(distance.max()), pytest.approx(distance.mean()))
    ratio = mesh.edge_lengths() / L
    assert np.all((ratio >= 1.0 - 1e-12) & (ratio <= 2.0 + 1e-12))
    assert triangle_angles(mesh.points, mesh.triangles).min() >= 30.0 - 1e-9


def test_zero_is_the_default_mesh(surface):
    a = equimesh.mesh_surface(surface, L, grid=(8, 8))
    b = equimesh.mesh_surface(surface, L, grid=(8, 8), surface_tolerance=0.0)
    assert a.points.tobytes() == b.points.tobytes() and a.deviation() == (0.0, 0.0)


@pytest.mark.parametrize(
    "value, match", [(-0.1, "at least 0"), (L, "below l"), (np.nan, "at least 0"), ("x", "number")]
)
def test_bad_tolerances_are_refused(surface, value, match):
    with pytest.raises(InvalidToleranceError, match=match):
        equimesh.mesh_surface(surface, L, surface_tolerance=value)


def test_fixed_boundary_objectives_refuse_a_tolerance(surface):
    with pytest.raises(EquimeshError, match="surface_tolerance"):
        equimesh.mesh_surface(surface, L, optimize="paper", surface_tolerance=0.1)


def test_a_node_beyond_the_tolerance_is_never_returned(surface, monkeypatch):
    """The pipeline measures every node's distance from the surface: an optimisation that puts one beyond D is an
    InternalError, not a mesh."""
    real = pipeline.optimize_uv

    def drifting(*args, **kwargs):
        result = real(*args, **kwargs)
        offsets = result.offsets.copy()
        offsets[-1] = 2.0 * kwargs["surface_tolerance"]
        return replace(result, offsets=offsets)

    monkeypatch.setattr(pipeline, "optimize_uv", drifting)
    monkeypatch.setattr(pipeline, "check_members", lambda *args: None)
    monkeypatch.setattr(pipeline, "check_joints", lambda *args: None)
    with pytest.raises(InternalError, match="farther than the surface tolerance"):
        equimesh.mesh_surface(surface, L, surface_tolerance=0.01 * L, grid=(8, 8))
