"""Hostile surfaces through the whole pipeline: each meshed within the pipeline's invariants or refused in one line."""

import numpy as np
import pytest
from conftest import exercised
from hypothesis import given, settings
from hypothesis import strategies as st
from invariants import check_edge_lengths
from surface_invariants import assert_valid_surface_mesh

import equimesh
from equimesh.surface.charts.bezier import BezierSurface

#: The condition of the fuzz test: the input is accepted.
MESHED = "a jittered net is meshed"


@st.composite
def jittered_nets(draw):
    """Bicubic-to-quintic nets over a 40 x 40 square with every control point moved by up to 30% of a cell."""
    n = draw(st.integers(3, 5))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    net = np.zeros((n + 1, n + 1, 3))
    net[..., 0] = np.linspace(0, 40, n + 1)[:, None]
    net[..., 1] = np.linspace(0, 40, n + 1)[None, :]
    net += rng.uniform(-0.3, 0.3, size=net.shape) * 40.0 / n
    return BezierSurface(net)


@pytest.mark.exercised(MESHED, share=0.5)
@settings(max_examples=8, deadline=None)
@given(jittered_nets())
def test_jittered_nets_are_meshed_correctly_or_refused_cleanly(surface):
    try:
        mesh = equimesh.mesh_surface(surface, 6.0, grid=(8, 8), optimize="none")
    except equimesh.EquimeshError as exc:
        assert "\n" not in str(exc) and "edge (" not in str(exc)
        exercised(MESHED, False)
        return
    exercised(MESHED, True)
    assert_valid_surface_mesh(mesh, surface)
    check_edge_lengths(mesh.stages.plane, 6.0)
