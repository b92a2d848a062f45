"""The checks ``mesh_surface`` runs on every mesh it returns fire at their thresholds, not only far beyond them.

A broken optimiser is stood in by one that returns a valid result moved a little: on a flat patch (the dome with
no rise, so that lengths on the surface are lengths in (u, v) times the span) scaling every (u, v) about the centre
scales every member by the same factor, which puts the shortest member at 0.999 l or the longest at 2.001 l.
A catalogue of stock lengths no side of the outline can be made of is refused before the optimisation runs.
"""

from dataclasses import replace

import numpy as np
import pytest

import equimesh
from equimesh.errors import InternalError, InvalidCatalogueError
from equimesh.surface import pipeline
from equimesh.surface.pipeline import mesh_surface
from equimesh.testing.surfaces import dome

L = 8.0


def _moved(monkeypatch, move):
    """``mesh_surface`` with its optimisation's result passed through ``move(uv, lengths / l)``."""
    real = pipeline.optimize_uv

    def broken(surface, uv, edges, *args, **kwargs):
        result = real(surface, uv, edges, *args, **kwargs)
        points = surface.evaluate(result.uv[:, 0], result.uv[:, 1])
        ratio = np.linalg.norm(points[edges[:, 1]] - points[edges[:, 0]], axis=1) / L
        fields = {f: getattr(result, f) for f in result.__dataclass_fields__}
        return type(result)(**{**fields, "uv": move(result.uv, ratio)})

    monkeypatch.setattr(pipeline, "optimize_uv", broken)
    return mesh_surface(dome(rise=0.0), L, placement="default")


def _scaled(factor):
    def move(uv, ratio):
        centre = np.array([0.5, 0.5])
        return centre + factor(ratio) * (uv - centre)

    return move


def test_the_flat_patch_passes_unmoved(monkeypatch):
    mesh = _moved(monkeypatch, lambda uv, ratio: uv)
    ratio = mesh.edge_lengths() / L
    assert ratio.min() >= 1.0 and ratio.max() <= 2.0


def test_a_member_just_below_l_is_an_internal_error(monkeypatch):
    with pytest.raises(InternalError, match=r"outside \[l, 2l\] \(lengths from 0\.999"):
        _moved(monkeypatch, _scaled(lambda ratio: 0.999 / ratio.min()))


def test_a_member_just_above_2l_is_an_internal_error(monkeypatch):
    with pytest.raises(InternalError, match=r"outside \[l, 2l\] .* to 2\.001"):
        _moved(monkeypatch, _scaled(lambda ratio: 2.001 / ratio.max()))


def test_a_folded_triangle_is_an_internal_error(monkeypatch):
    """Two nodes of an inner triangle swapped: it turns clockwise in (u, v)."""

    def swap(uv, ratio):
        out = uv.copy()
        inner = np.flatnonzero(np.all((uv > 0.2) & (uv < 0.8), axis=1))
        a, b = inner[:2]
        out[[a, b]] = out[[b, a]]
        return out

    with pytest.raises(InternalError, match=r"the optimisation inverted \d+ of \d+ triangles"):
        _moved(monkeypatch, swap)


def test_a_catalogue_that_cannot_make_a_side_is_refused_before_the_optimisation():
    """The flat patch's sides are 60 long on the surface, 7.5 members of 8: stock lengths of 8 alone cannot make one."""
    with pytest.raises(InvalidCatalogueError, match=r"adds up to side 0 of the outer boundary, 60 long on the surface"):
        mesh_surface(dome(rise=0.0), L, placement="default", optimize="classes", lengths=[L], tolerance=0.001)


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
    surface = equimesh.load_surface("experiments/surfaces/saddle.json")
    with pytest.raises(InternalError, match="angle below its bound"):
        equimesh.mesh_surface(surface, 6.0, grid=(8, 8), optimize="classes")
