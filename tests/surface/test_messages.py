"""Refusals of Problem 2 restated in the surface's terms (``surface/messages.py``): the place on the patch named in
(u, v), and the largest l that fits, which then meshes.
"""

import numpy as np
import pytest
from invariants import check_edge_lengths
from surface_cases import plane_patch, refuse, waist_net

import equimesh
from equimesh.errors import InvalidPolygonError, InvalidSurfaceError
from equimesh.surface import front


def test_narrow_side_is_named_with_the_largest_l_that_fits():
    message = refuse(equimesh.SurfaceTooSmallError, plane_patch((30.0, 0.0), (0.0, 4.0)), 5.0, r"side u = 1")
    assert "corner (u, v) = (1, 0)" in message and message.endswith("use l <= 4")
    equimesh.mesh_surface(plane_patch((30.0, 0.0), (0.0, 4.0)), 4.0, grid=(6, 2), optimize="none")


@pytest.fixture
def located_refusals(monkeypatch):
    """Problem 2's refusal carries the two points at fault (the planar core does this itself).

    Until it does, the closest pair of outline vertices, not neighbours, is attached here, so that the
    restatement in surface terms is tested on every branch.
    """
    real = front.uniform_triangulation

    def located(vertices, l, **kwargs):
        try:
            return real(vertices, l, **kwargs)
        except InvalidPolygonError as exc:
            if exc.points:
                raise
            v = np.asarray(vertices)
            d = np.linalg.norm(v[:, None] - v[None], axis=2)
            n = len(v)
            i, j = np.indices((n, n))
            d[(np.abs(i - j) <= 1) | (np.abs(i - j) == n - 1)] = np.inf
            a, b = np.unravel_index(np.argmin(d), d.shape)
            raise InvalidPolygonError(str(exc), points=[v[a], v[b]]) from None

    monkeypatch.setattr(front, "uniform_triangulation", located)


def test_sharp_corner_is_named_with_the_largest_l_that_fits(located_refusals):
    """A flat 20-degree parallelogram, sides 30, at l = 9: the refusal names the sharp corner, its angle and an l that
    works."""
    a = np.radians(20.0)
    patch = plane_patch((30.0, 0.0), (30.0 * np.cos(a), 30.0 * np.sin(a)))
    message = refuse(InvalidSurfaceError, patch, 9.0, r"corner \(u, v\) = \((1, 1|0, 0)\) .* is 20\.0 degrees")
    assert "staggered boundary points need side" in message and "edge (" not in message
    suggested = float(message.rsplit("use l <= ", 1)[1])
    check_edge_lengths(equimesh.mesh_surface(patch, suggested, optimize="none").stages.plane, suggested)


def test_waist_is_named_with_the_largest_l_that_fits(located_refusals):
    """A flat patch with a waist 4 wide: the refusal names both sides there and an l that works."""
    message = refuse(InvalidSurfaceError, waist_net(), 5.0, r"only 4\.0\d* wide .* side v = 0 at \(u, v\) = \(0\.4")
    assert "side v = 1 at (u, v) = (0.4" in message
    suggested = float(message.rsplit("use l <= ", 1)[1])
    mesh = equimesh.mesh_surface(waist_net(), suggested, optimize="none")
    check_edge_lengths(mesh.stages.plane, suggested)


def test_problem2_refusal_without_points_is_still_in_surface_terms(monkeypatch):
    def refusing(vertices, l, **kwargs):
        raise InvalidPolygonError("polygon is too narrow for l = 3: boundary points on edge (1, 2) and edge (7, 0)")

    monkeypatch.setattr(front, "uniform_triangulation", refusing)
    message = refuse(InvalidSurfaceError, plane_patch(), 3.0, "cannot be meshed with l = 3")
    assert "edge (" not in message
