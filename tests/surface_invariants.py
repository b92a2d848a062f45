"""What every mesh of a surface must satisfy (Section 4): nodes on the surface and in the chart, no fold-over in (u,
v)."""

import numpy as np

from equimesh._geometry import orient
from equimesh.surface.charts.chart import domain_of


def assert_valid_surface_mesh(mesh, surface):
    """The invariants every surface mesh must satisfy."""
    uv, tri = mesh.uv, mesh.triangles
    lower, upper = domain_of(surface).lower, domain_of(surface).upper
    # Every node on the surface, parameters in the chart's rectangle.
    assert np.all((uv >= lower) & (uv <= upper))
    np.testing.assert_allclose(mesh.points, surface.evaluate(uv[:, 0], uv[:, 1]), rtol=0, atol=1e-9)
    # Boundary nodes on the boundary curves: u or v exactly a bound of the rectangle.
    b = uv[: mesh.n_boundary]
    assert np.all(np.any((b == lower) | (b == upper), axis=1))
    # No fold-over in (u, v): every triangle counter-clockwise with positive area.
    p = uv[tri]
    area2 = orient(p[:, 0], p[:, 1], p[:, 2])
    assert np.all(area2 > 0)
    # The (u, v) triangles tile the unit square's polygonal approximation without overlap:
    # each edge is used by at most two triangles, boundary edges by one.
    e = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    assert counts.max() <= 2
    # Manifold: the boundary edges form one closed loop through the boundary nodes.
    boundary_edges = np.unique(e, axis=0)[counts == 1]
    assert set(np.unique(boundary_edges)) == set(range(mesh.n_boundary))
