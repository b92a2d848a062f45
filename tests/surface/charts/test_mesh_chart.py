"""A triangle mesh as a chart (``surface/charts/mesh_chart.py``): its flattening starts and the map they give.

What must hold: a strip that folds when projected on a plane starts from the conformal map and develops
with zero energy; Tutte's embedding never folds a disc; an opening stays a simple hole on a curved fine mesh.
"""

import numpy as np
import pytest
import shapely
from triangle_meshes import assert_on_input_surface, roof

from equimesh import TriangulatedSurface, mesh_surface
from equimesh.mesh import triangle_orient
from equimesh.surface.charts.mesh_chart import (
    MeshChart,
    conformal_start,
    flatten_mesh,
    flattening_start,
    harmonic_start,
)
from equimesh.surface.flatten import flatten
from equimesh.testing.meshes import roof_mesh


def cylinder_strip(angle, n_around=24, n_along=3, radius=5.0, length=6.0):
    """A developable strip: ``angle`` degrees of a cylinder, open along both straight sides."""
    phi = np.radians(angle) * np.arange(n_around + 1) / n_around
    z = length * np.arange(n_along + 1) / n_along
    p, q = np.meshgrid(phi, z, indexing="ij")
    vertices = np.column_stack([radius * np.cos(p.ravel()), radius * np.sin(p.ravel()), q.ravel()])
    node = np.arange(len(vertices)).reshape(n_around + 1, n_along + 1)
    a, b, c, d = node[:-1, :-1].ravel(), node[1:, :-1].ravel(), node[1:, 1:].ravel(), node[:-1, 1:].ravel()
    return vertices, np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


def unfolded(x, triangles):
    """Every triangle of ``x`` counter-clockwise."""
    return bool(np.all(triangle_orient(x, triangles) > 0))


def best_fit_plane(vertices):
    """Orthonormal axes of the best-fit plane of ``vertices`` (principal axes, SVD) and its normal."""
    axes = np.linalg.svd(vertices - vertices.mean(axis=0), full_matrices=False)[2]
    return axes[:2], axes[2]


def test_folding_projection_starts_from_the_conformal_map():
    """A 300-degree cylinder strip folds when projected on a plane (triangles of both orientations, whichever way
    the plane is seen): eq. (1) starts from the conformal map and develops it.  A vault projects without folding:
    its start is the orthogonal projection on its best-fit plane, one-to-one."""
    surface = TriangulatedSurface(*cylinder_strip(300.0))
    axes, _ = best_fit_plane(surface.vertices)
    signs = np.sign(triangle_orient((surface.vertices - surface.vertices.mean(axis=0)) @ axes.T, surface.triangles))
    assert {-1.0, 1.0} <= set(signs.tolist())
    np.testing.assert_array_equal(flattening_start(surface), conformal_start(surface))
    assert flatten_mesh(surface).energy < 1e-12
    mesh = mesh_surface(surface, 2.0, optimize="none")
    assert_on_input_surface(mesh, surface, 2.0)
    vault = TriangulatedSurface(*roof())
    start = flattening_start(vault)
    assert unfolded(start, vault.triangles)
    centred = vault.vertices - vault.vertices.mean(axis=0)
    linear = np.linalg.lstsq(centred, start - start.mean(axis=0), rcond=None)[0]  # start = centred @ linear
    np.testing.assert_allclose(centred @ linear, start - start.mean(axis=0), rtol=0, atol=1e-9)
    np.testing.assert_allclose(linear.T @ linear, np.eye(2), rtol=0, atol=1e-9)  # an orthogonal projection ...
    normal = np.cross(*linear.T)
    assert abs(np.dot(normal, best_fit_plane(vault.vertices)[1])) == pytest.approx(1.0, abs=1e-9)  # ... on that plane


def test_tutte_embedding_never_folds_a_disc():
    """Tutte's embedding (the last start) of the opening-free vault and of the strip: every triangle
    counter-clockwise."""
    for vertices, triangles in (roof_mesh(20.0, 14.0, (10, 7), 3.0), cylinder_strip(300.0)):
        surface = TriangulatedSurface(vertices, triangles)
        assert unfolded(harmonic_start(surface), surface.triangles)


def test_openings_stay_open_on_a_curved_fine_mesh():
    """Eq. (1) alone lets this opening's rim cross itself; capped for the fold-over guard it stays a simple hole."""
    surface = TriangulatedSurface(*roof_mesh(20.0, 14.0, (40, 28), 5.0, opening=(16, 24, 12, 16)))
    bare = flatten(surface.vertices, surface.triangles)
    assert not shapely.LinearRing(bare.points[surface.loops[1]]).is_simple
    chart = MeshChart(surface, flatten_mesh(surface).points)  # checks that the flattening is one-to-one
    assert chart.outer == 0
