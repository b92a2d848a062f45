"""Stand-ins for Section 4 tests: surfaces and a planar lattice mesh with G1 labels.

The real planar step (Problem 2, ``uniform_triangulation``) is tested on its
own; the remap and optimisation stages are tested here on a simpler mesh of
the same kind: a triangular lattice of spacing l (its edges are the G1 edges)
kept at least l from the polygon boundary, plus the boundary resampled, all
triangulated by ``triangle`` without Steiner points.  The doubly curved
dome is :func:`equimesh.testing.surfaces.dome` (the experiments use it too).
"""

import numpy as np
import shapely
import triangle

from equimesh.mesh import PlanarMesh
from equimesh.surface.charts.bezier import BezierSurface


def parabolic_vault(width=60.0, depth=50.0, rise=15.0):
    """Developable vault ``z = f(x)``: a cubic Bezier arch in u, straight in v (degree (3, 1))."""
    net = np.zeros((4, 2, 3))
    for i, z in enumerate([0.0, rise * 4 / 3, rise * 4 / 3, 0.0]):
        net[i, :, 0] = width * i / 3
        net[i, :, 1] = [0.0, depth]
        net[i, :, 2] = z
    return BezierSurface(net)


class CircularVault:
    """An exact circular cylindrical vault (not a Bezier surface): the protocol's other implementer.

    ``X(u, v) = (R sin(phi), depth v, R cos(phi) - R cos(half))`` with
    ``phi = half (2u - 1)``: developable, opening angle ``2 half``.
    """

    def __init__(self, radius=40.0, half_angle=1.0, depth=50.0):
        self.radius, self.half, self.depth = radius, half_angle, depth

    def evaluate(self, u, v):
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        phi = self.half * (2 * u - 1)
        r = self.radius
        return np.stack([r * np.sin(phi), self.depth * v, r * np.cos(phi) - r * np.cos(self.half)], axis=-1)

    def derivatives(self, u, v):
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        phi = self.half * (2 * u - 1)
        k = 2 * self.half * self.radius
        su = np.stack([k * np.cos(phi), np.zeros_like(u), -k * np.sin(phi)], axis=-1)
        sv = np.stack([np.zeros_like(u), np.full_like(u, self.depth), np.zeros_like(u)], axis=-1)
        return su, sv


def flat_patch(width=40.0, depth=30.0, degree=(2, 3), shear=0.0):
    """A planar Bezier patch (z = 0) with an affine, optionally sheared, parametrisation."""
    m, n = degree
    i, j = np.meshgrid(np.linspace(0, 1, m + 1), np.linspace(0, 1, n + 1), indexing="ij")
    return BezierSurface(np.stack([width * i + shear * j, depth * j, np.zeros_like(i)], axis=-1))


def lattice_mesh(polygon, l, angle=0.0):
    """A planar mesh of ``polygon`` (CCW ring) whose interior is a triangular lattice of spacing l.

    Boundary: every polygon edge split into ``ceil(len / 1.5 l)`` equal parts
    (these points come first).  Lattice nodes are kept when at least ``0.9 l``
    from the boundary.  G1 edges: triangulation edges between lattice nodes of
    length l (the lattice's own edges).
    """
    ring = np.asarray(polygon, dtype=float)
    pts = []
    for a, b in zip(ring, np.roll(ring, -1, axis=0)):
        k = max(1, int(np.ceil(np.linalg.norm(b - a) / (1.5 * l))))
        pts.append(a + (b - a) * np.arange(k)[:, None] / k)
    boundary = np.vstack(pts)
    nb = len(boundary)
    lo, hi = ring.min(axis=0) - l, ring.max(axis=0) + l
    c, s = np.cos(angle), np.sin(angle)
    r = np.array([[c, -s], [s, c]])
    extent = int(np.ceil(np.linalg.norm(hi - lo) / l)) + 2
    a, b = np.meshgrid(np.arange(-extent, extent + 1), np.arange(-extent, extent + 1), indexing="ij")
    lat = np.column_stack([(a + 0.5 * b).ravel(), (b * np.sqrt(3) / 2).ravel()]) * l
    lat = lat @ r.T + (lo + hi) / 2
    poly = shapely.Polygon(ring)
    inside = shapely.contains_xy(poly, lat[:, 0], lat[:, 1])
    lat = lat[inside]
    far = shapely.distance(poly.exterior, shapely.points(lat)) >= 0.9 * l
    lat = lat[far]
    points = np.vstack([boundary, lat])
    segments = np.column_stack([np.arange(nb), (np.arange(nb) + 1) % nb])
    out = triangle.triangulate({"vertices": points, "segments": segments}, "p")
    assert len(out["vertices"]) == len(points), "triangle added Steiner points"
    tris = out["triangles"]
    e = np.unique(np.sort(np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]]), axis=1), axis=0)
    both_lattice = (e[:, 0] >= nb) & (e[:, 1] >= nb)
    unit = np.abs(np.linalg.norm(points[e[:, 1]] - points[e[:, 0]], axis=1) - l) <= 1e-9 * l
    return PlanarMesh.build(points, tris, l, nb, g1_edges=e[both_lattice & unit])


def standin_pipeline(surface, l, grid=(15, 15)):
    """Steps 1-4 of Section 4 with :func:`lattice_mesh` standing in for Problem 2.

    Returns ``(grid, flat_points, planar_mesh, remap_result)``.
    """
    from equimesh.surface.auxiliary import auxiliary_grid
    from equimesh.surface.flatten import flatten
    from equimesh.surface.remap import remap

    g = auxiliary_grid(*grid)
    x = surface.evaluate(g.uv[:, 0], g.uv[:, 1])
    flat = flatten(x, g.triangles, uv=g.uv, edges=g.edges).points
    mesh = lattice_mesh(flat[g.boundary], l)
    r = remap(surface, mesh.points, flat, g, on_boundary=np.arange(mesh.n_boundary))
    return g, flat, mesh, r
