"""Section 4 end to end: mesh_surface on developable, flat, generic and non-Bézier surfaces."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from surface_invariants import assert_valid_surface_mesh

import equimesh
from equimesh.metrics import length_stats
from equimesh.surface.charts.bezier import BezierSurface


def _vault(span=40.0, rise=8.0, width=30.0):
    """A parabolic-cylinder vault z = f(u): developable (zero Gaussian curvature)."""
    net = np.zeros((3, 2, 3))
    net[:, :, 0] = np.array([0.0, span / 2, span])[:, None]
    net[:, :, 1] = np.array([0.0, width])[None, :]
    net[:, :, 2] = np.array([0.0, 2 * rise, 0.0])[:, None]
    return BezierSurface(net)


def _flat(size=30.0):
    net = np.zeros((2, 2, 3))
    net[..., 0] = np.array([0.0, size])[:, None]
    net[..., 1] = np.array([0.0, size])[None, :]
    return BezierSurface(net)


class Cylinder:
    """A circular-cylinder patch, not a Bézier surface: the pipeline needs only evaluate/derivatives."""

    def __init__(self, radius=20.0, angle=1.5, height=25.0):
        self.r, self.a, self.h = radius, angle, height

    def evaluate(self, u, v):
        t = self.a * np.asarray(u, dtype=float)
        return np.stack([self.r * np.sin(t), self.h * np.asarray(v, dtype=float), self.r * (1 - np.cos(t))], axis=-1)

    def derivatives(self, u, v):
        t = self.a * np.asarray(u, dtype=float)
        zero = np.zeros_like(t + np.asarray(v, dtype=float))
        su = np.stack([self.r * self.a * np.cos(t), zero, self.r * self.a * np.sin(t)], axis=-1)
        sv = np.stack([zero, zero + self.h, zero], axis=-1)
        return su, sv


def g1_deviation(points, mesh):
    lengths = np.linalg.norm(points[mesh.edges[:, 1]] - points[mesh.edges[:, 0]], axis=1)[mesh.g1_mask]
    return np.abs(lengths - mesh.length).max(), np.sum(((lengths - mesh.length) / mesh.length) ** 2)


def test_flat_surface_is_exact():
    """A flat square: flattening energy 0, the G1 members exactly l before and after optimisation."""
    s = _flat()
    mesh = equimesh.mesh_surface(s, 3.0, grid=(6, 6), optimize="paper")
    assert mesh.stages.flattening.energy < 1e-20
    g1 = mesh.edge_lengths()[mesh.g1_mask]
    np.testing.assert_allclose(g1, 3.0, rtol=1e-9)
    assert_valid_surface_mesh(mesh, s)


def test_developable_vault_reaches_l():
    """A parabolic vault is developable: energy ~0 and the final G1 lengths equal l to 1e-3 relative."""
    s = _vault()
    mesh = equimesh.mesh_surface(s, 4.0, grid=(20, 8), optimize="paper")
    assert mesh.stages.flattening.energy < 1e-3
    g1 = mesh.edge_lengths()[mesh.g1_mask]
    np.testing.assert_allclose(g1, 4.0, rtol=1e-3)
    assert_valid_surface_mesh(mesh, s)


def test_any_parametric_surface_works():
    """A non-Bézier surface (circular cylinder patch) goes through the whole pipeline."""
    s = Cylinder()
    mesh = equimesh.mesh_surface(s, 4.0, grid=(12, 8), optimize="paper")
    assert_valid_surface_mesh(mesh, s)
    np.testing.assert_allclose(mesh.edge_lengths()[mesh.g1_mask], 4.0, rtol=1e-3)


@st.composite
def mild_bezier(draw):
    """Bicubic nets over a 30..50 square with random heights up to 15% of the span."""
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    span = draw(st.floats(30.0, 50.0))
    deg_u, deg_v = draw(st.integers(2, 4)), draw(st.integers(2, 4))
    net = np.zeros((deg_u + 1, deg_v + 1, 3))
    net[..., 0] = (span * np.linspace(0, 1, deg_u + 1))[:, None]
    net[..., 1] = (span * np.linspace(0, 1, deg_v + 1))[None, :]
    net[..., 2] = rng.uniform(-0.15, 0.15, size=net.shape[:2]) * span
    return BezierSurface(net)


@settings(max_examples=6, deadline=None)
@given(mild_bezier())
def test_pipeline_property(surface):
    """On mild Bézier surfaces: a valid surface triangulation, and optimisation never worsens G1."""
    mesh = equimesh.mesh_surface(surface, 5.0, grid=(8, 8), optimize="paper")
    assert_valid_surface_mesh(mesh, surface)
    before = g1_deviation(mesh.stages.remapped_points, mesh)[1]
    after = g1_deviation(mesh.points, mesh)[1]
    assert after <= before * (1 + 1e-12)


def test_optimize_none_keeps_remapped():
    s = _vault()
    mesh = equimesh.mesh_surface(s, 4.0, grid=(10, 6), optimize="none")
    np.testing.assert_array_equal(mesh.points, mesh.stages.remapped_points)
    assert mesh.stages.optimization is None


def test_deterministic():
    """The same surface gives the same mesh, bit for bit."""
    a = equimesh.mesh_surface(_vault(), 4.0, grid=(10, 6))
    b = equimesh.mesh_surface(_vault(), 4.0, grid=(10, 6))
    np.testing.assert_array_equal(a.points, b.points)
    np.testing.assert_array_equal(a.triangles, b.triangles)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"l": 0.0}, "positive"),
        ({"l": 0.01}, "nodes"),
        ({"l": 4.0, "optimize": "magic"}, "optimize"),
        ({"l": 4.0, "placement": "random"}, "placement"),
        ({"l": 4.0, "grid": (0, 5)}, "n_u"),
        ({"l": 100.0}, "shorter than l"),
    ],
)
def test_bad_arguments(kwargs, match):
    """Bad arguments raise an EquimeshError naming the problem."""
    l = kwargs.pop("l")
    with pytest.raises(equimesh.EquimeshError, match=match):
        equimesh.mesh_surface(_vault(), l, **kwargs)


def test_stage_metrics_are_table1_columns():
    mesh = equimesh.mesh_surface(_vault(), 4.0, grid=(10, 6))
    stats = length_stats(mesh.edge_lengths())
    assert {"members", "mean", "min", "max", "std"} <= set(stats)
