"""Meshes the tests of the report, the plot and their view share, each made once per test process.

A test module binds the fixtures it uses (``roof_mesh = report_meshes.roof_mesh``).
"""

import functools

import pytest
from repository import SURFACES

import equimesh


@functools.cache
def _roof():
    return equimesh.mesh_surface(equimesh.load_surface(SURFACES / "nurbs_roof_openings.json"), 3.0, optimize="none")


@functools.cache
def _large():
    square = [[0, 0], [182, 0], [182, 182], [0, 182]]
    opening = [[60, 60], [120, 60], [120, 120], [60, 120]]
    mesh = equimesh.uniform_triangulation(square, 1.0, holes=[opening], max_nodes=None)
    assert len(mesh.edges) > 100_000
    return mesh


@functools.cache
def _square():
    return equimesh.uniform_triangulation(
        [[0, 0], [5, 0], [5, 5], [0, 5]], 1.0, holes=[[[2, 2], [3, 2], [3, 3], [2, 3]]]
    )


@pytest.fixture(scope="session")
def square_mesh():
    """A planar mesh of a 5 x 5 square with a 1 x 1 opening, l = 1: 28 nodes, 64 members, made in a second."""
    return _square()


@pytest.fixture(scope="session")
def roof_mesh():
    """A NURBS roof with two openings (``experiments/surfaces/nurbs_roof_openings.json``), l = 3, not optimised."""
    return _roof()


@pytest.fixture(scope="session")
def large_mesh():
    """A planar mesh of more than 10^5 members: a square of side 182 l with a square opening."""
    return _large()
