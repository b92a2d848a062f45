"""Meshes the tests of the report, the plot and their view share (each made once per test process)."""

from pathlib import Path

import pytest

import equimesh

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def roof_mesh():
    """A NURBS roof with two openings (``experiments/surfaces/nurbs_roof_openings.json``), l = 3, not optimised."""
    surface = equimesh.load_surface(ROOT / "experiments" / "surfaces" / "nurbs_roof_openings.json")
    return equimesh.mesh_surface(surface, 3.0, optimize="none")


@pytest.fixture(scope="session")
def large_mesh():
    """A planar mesh of more than 10^5 members: a square of side 182 l with a square opening."""
    square = [[0, 0], [182, 0], [182, 182], [0, 182]]
    opening = [[60, 60], [120, 60], [120, 120], [60, 120]]
    mesh = equimesh.uniform_triangulation(square, 1.0, holes=[opening], max_nodes=None)
    assert len(mesh.edges) > 100_000
    return mesh
