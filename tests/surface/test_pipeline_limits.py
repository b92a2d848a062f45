"""The pipeline's arguments and size limits (``surface/pipeline.py``): refused before any stage, in one line.

What must hold: l outside the supported range, a mesh too large for ``max_nodes`` (default depending on the
objective), a grid beyond its limit or a bad keyword is refused before flattening; an own stage that inverts
the mesh is an :class:`~equimesh.InternalError`, never a returned mesh.
"""

import numpy as np
import pytest
from surface_cases import plane_patch, refuse

import equimesh
from equimesh.errors import InternalError, MeshTooLargeError
from equimesh.surface import pipeline
from equimesh.surface.optimize import OBJECTIVES
from equimesh.surface.optimize.solver import DEFAULT_FACTORISATION, FACTORISATIONS, INSTALLED


@pytest.mark.parametrize("l", [1e-200, 1e-160, 5e-324, 1e200, 1.7e308])
def test_length_outside_the_supported_range_is_refused(l):
    """Outside [MIN_LENGTH, MAX_LENGTH] (tolerance.py) l is refused before any stage."""
    refuse(equimesh.InvalidLengthError, plane_patch(), l, r"outside the supported range")


@pytest.mark.parametrize("l", [1e-140, 1e-12])
def test_tiny_length_is_too_large_a_mesh(l):
    """The estimate is a plain float: never an OverflowError or ZeroDivisionError."""
    limit = OBJECTIVES["bounded"].node_limit()  # the default objective's
    refuse(MeshTooLargeError, plane_patch(), l, rf"would need about .* nodes in this surface .* max_nodes = {limit}\b")


@pytest.mark.parametrize("l", [1e100, 1e149])
def test_huge_length_names_a_side(l):
    refuse(equimesh.SurfaceTooSmallError, plane_patch(), l, r"side v = 0 .* shorter than l .* use l <= 30$")


@pytest.mark.parametrize("max_nodes", [float("nan"), 0, -1, 2.5, True, "x", 1e9])
def test_bad_max_nodes(max_nodes):
    refuse(equimesh.EquimeshError, plane_patch(), 3.0, "max_nodes", max_nodes=max_nodes)


def test_max_nodes_none_means_no_limit_and_default_depends_on_optimize():
    """None is no limit; the default is UNOPTIMIZED_MAX_NODES without optimisation and each objective's own, smaller,
    limit with it, for the factorisation in use (the refusal of a tiny l names the limit that applied)."""
    assert equimesh.mesh_surface(plane_patch(), 3.0, grid=(4, 4), optimize="none", max_nodes=None).points.size
    # about 115 nodes: refused under a limit of 100, with either optimisation
    for optimize in ("none", "paper"):
        refuse(MeshTooLargeError, plane_patch(), 3.0, "max_nodes = 100", max_nodes=100, optimize=optimize)
    defaults = {"none": pipeline.UNOPTIMIZED_MAX_NODES, **{name: o.node_limit() for name, o in OBJECTIVES.items()}}
    for optimize, limit in defaults.items():
        assert optimize == "none" or limit < pipeline.UNOPTIMIZED_MAX_NODES
        refuse(MeshTooLargeError, plane_patch(), 1e-12, rf"max_nodes = {limit}\b", optimize=optimize)


def test_size_is_checked_before_flattening():
    """A too large request is refused before any stage completes."""
    stages = []
    refuse(MeshTooLargeError, plane_patch(), 0.01, "nodes", progress=lambda stage, s: stages.append(stage))
    assert stages == []


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"boundary_spacing": float("nan")}, "boundary_spacing must be finite"),
        ({"boundary_spacing": "x"}, "boundary_spacing must be a real number"),
        ({"optimize": []}, "optimize must be"),
        ({"grid": (np.float64(2.5), 3)}, r"n_u must be an integer of at least 1, got 2\.5$"),
    ],
)
def test_bad_keywords_are_refused_before_any_stage(kwargs, match):
    refuse(equimesh.EquimeshError, plane_patch(), 3.0, match, **kwargs)


@pytest.mark.parametrize("grid", [(1000, 1000), (pipeline.MAX_GRID_CELLS + 1, 1), (2**62, 2**62)])
def test_grid_is_bounded(grid):
    refuse(equimesh.EquimeshError, plane_patch(), 3.0, f"more than the limit of {pipeline.MAX_GRID_CELLS}", grid=grid)


def test_an_inverting_stage_is_an_internal_error(monkeypatch):
    """Our own stage breaking orientation is a loud InternalError, never a returned mesh."""
    real = pipeline.optimize_uv

    def inverting(*args, **kwargs):
        result = real(*args, **kwargs)
        uv = result.uv.copy()
        uv[:, 0] = 1.0 - uv[:, 0]
        return type(result)(uv, *list(vars(result).values())[1:])

    monkeypatch.setattr(pipeline, "optimize_uv", inverting)
    with pytest.raises(InternalError, match="the optimisation inverted"):
        equimesh.mesh_surface(plane_patch(), 5.0, grid=(4, 4))


def test_each_objective_has_a_limit_for_every_factorisation_and_the_one_in_use_applies():
    """The default node limit follows the factorisation (docs/performance.md, "The final optimisation"): one per
    factorisation of every objective, the slowest factorisation's the smallest, and a name that is not a factorisation
    is refused like anywhere else."""
    for record in OBJECTIVES.values():
        assert set(record.max_nodes) == set(FACTORISATIONS)
        assert record.max_nodes["superlu"] == min(record.max_nodes.values())
        assert record.node_limit() == record.max_nodes[DEFAULT_FACTORISATION]
        assert all(record.node_limit(name) == record.max_nodes[name] for name in INSTALLED)
        with pytest.raises(equimesh.EquimeshError, match="unknown factorisation 'nope'"):
            record.node_limit("nope")
