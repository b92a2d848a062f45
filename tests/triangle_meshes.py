"""Triangle meshes for the tests: the roof with an opening, an open tube, a closed-ended one, meshes that must be
refused, and the checks that a surface mesh lies on the input triangles and that its boundary nodes slid along the
loops.
"""

import numpy as np
import shapely

import equimesh
from equimesh import REL_TOL
from equimesh.surface.charts.mesh_chart import MeshChart
from equimesh.testing import meshes
from equimesh.testing.meshes import roof_mesh


def roof():
    """A 20 x 14 vault rising 3, 10 x 7 cells of 2 x 2, with the opening OPENING (cells 4-5 x 3-4) left out."""
    return roof_mesh(20.0, 14.0, (10, 7), 3.0, opening=(4, 6, 3, 5))


def tube(radius=10.0, height=10.0, around=60, along=10, strip=0):
    """An open cylinder about the z axis, ``around`` x ``along`` cells, the cells of the first ``strip`` columns left
    out (a strip of triangles from rim to rim: then a disc); vertices ring by ring, two triangles a cell."""
    phi = 2.0 * np.pi * np.arange(around) / around
    z = height * np.arange(along + 1) / along
    ring = np.column_stack([radius * np.cos(phi), radius * np.sin(phi)])
    vertices = np.column_stack([np.tile(ring, (along + 1, 1)), np.repeat(z, around)])
    k, j = np.meshgrid(np.arange(strip, around), np.arange(along))
    a, b = (j * around + k).ravel(), (j * around + (k + 1) % around).ravel()
    triangles = np.stack([np.column_stack([a, b, b + around]), np.column_stack([a, b + around, a + around])], axis=1)
    return vertices, triangles.reshape(-1, 3)


def tetrahedron():
    v = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    return v, np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])


def torus_with_hole(n=8, m=6):
    a, b = np.meshgrid(2 * np.pi * np.arange(n) / n, 2 * np.pi * np.arange(m) / m, indexing="ij")
    v = np.column_stack(
        [(3 + np.cos(b.ravel())) * np.cos(a.ravel()), (3 + np.cos(b.ravel())) * np.sin(a.ravel()), np.sin(b.ravel())]
    )
    node = np.arange(n * m).reshape(n, m)
    nxt = np.roll(node, -1, axis=0)
    a0, b0, c0, d0 = node.ravel(), nxt.ravel(), np.roll(nxt, -1, axis=1).ravel(), np.roll(node, -1, axis=1).ravel()
    t = np.concatenate([np.column_stack([a0, b0, c0]), np.column_stack([a0, c0, d0])])
    return v, np.delete(t, [0, n * m], axis=0)  # one cell removed: a boundary loop, the handle stays


def moebius(n=12):
    s = np.arange(n + 1) / n * 2 * np.pi
    v = []
    for w in (-1.0, 1.0):
        v.append(
            np.column_stack(
                [(4 + w * np.cos(s / 2)) * np.cos(s), (4 + w * np.cos(s / 2)) * np.sin(s), w * np.sin(s / 2)]
            )
        )
    v = np.vstack([v[0][:-1], v[1][:-1]])
    lo, hi = np.arange(n), n + np.arange(n)
    t = [[lo[i], lo[(i + 1) % n], hi[(i + 1) % n]] for i in range(n - 1)] + [
        [lo[i], hi[(i + 1) % n], hi[i]] for i in range(n - 1)
    ]
    t += [[lo[n - 1], hi[0], lo[0]], [lo[n - 1], lo[0], hi[n - 1]]]  # the twist: the last cell glues lo to hi
    return v, np.array(t)


def bad_meshes():
    v, t = roof()
    square = np.array([[0.0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    two = np.array([[0, 1, 2], [0, 2, 3]])
    nan = v.copy()
    nan[5, 2] = np.nan
    inf = v.copy()
    inf[7, 0] = np.inf
    fin = np.vstack([square, [[0.5, 0.5, 1.0]], [[0.5, 0.5, -1.0]]])
    return {
        "no triangles": ((v, np.zeros((0, 3), dtype=int)), "no triangles"),
        "NaN": ((nan, t), "vertex 5 of the triangle mesh is not finite"),
        "infinity": ((inf, t), "vertex 7 of the triangle mesh is not finite"),
        "index out of range": ((square, [[0, 1, 4]]), "refers to a vertex outside"),
        "repeated corner": ((square, [[0, 1, 1], [0, 2, 3]]), "two of its corners are the same point"),
        "zero area": ((np.vstack([square, [[2.0, 0, 0]]]), [[0, 1, 4], [0, 2, 3]]), r"degenerate \(zero area\)"),
        "triangle twice": ((square, [[0, 1, 2], [0, 2, 3], [2, 1, 0]]), "have the same corners"),
        "edge in three triangles": (
            (np.vstack([fin, [[0.5, 2.0, 0.0]]]), [[0, 2, 4], [0, 2, 5], [0, 2, 6]]),
            "belongs to 3 triangles",
        ),
        "bow tie": (
            (np.vstack([square, [[2.0, 1, 0], [2, 2, 0]]]), [[0, 1, 2], [2, 4, 5]]),
            "not manifold at the vertex",
        ),
        "two pieces": ((np.vstack([square, square + [5.0, 0, 0]]), np.vstack([two, two + 4])), "2 separate pieces"),
        "closed": (tetrahedron(), "cut it open first"),
        "Moebius": (moebius(), "not orientable"),
        "handle": (torus_with_hole(), "1 handle"),
    }


def point_triangle_distance(p, a, b, c):
    """Distance from each point p (K, 3) to the triangle (a, b, c) (K, 3 each): the closest of its plane and edges."""
    n = np.cross(b - a, c - a)
    n = n / np.linalg.norm(n, axis=1, keepdims=True)
    height = np.einsum("ij,ij->i", p - a, n)
    q = p - height[:, None] * n
    inside = np.ones(len(p), dtype=bool)
    for x, y in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("ij,ij->i", np.cross(y - x, q - x), n) >= 0
    edge = np.full(len(p), np.inf)
    for x, y in ((a, b), (b, c), (c, a)):
        t = np.clip(np.einsum("ij,ij->i", p - x, y - x) / np.einsum("ij,ij->i", y - x, y - x), 0, 1)
        edge = np.minimum(edge, np.linalg.norm(x + t[:, None] * (y - x) - p, axis=1))
    return np.where(inside, np.abs(height), edge)


def assert_on_input_surface(mesh, surface, l):
    """Every node within 1e-9 l of the input triangle its parameters fall in."""
    chart = MeshChart(surface, mesh.stages.flattening.points)
    k = chart.locate(mesh.uv[:, 0], mesh.uv[:, 1])[0]
    corners = surface.vertices[surface.triangles[k]]
    distance = point_triangle_distance(mesh.points, corners[:, 0], corners[:, 1], corners[:, 2])
    assert distance.max() <= 1e-9 * l, distance.max()


def closed_tube(radius, length, n_ring=24, n_cap=6):
    """:func:`equimesh.testing.meshes.closed_tube` as a surface."""
    return equimesh.TriangulatedSurface(*meshes.closed_tube(radius, length, n_ring, n_cap))


def spherical_cap(radius, degrees, n_ring=24, n_rings=12):
    """:func:`equimesh.testing.meshes.spherical_cap` as a surface."""
    return equimesh.TriangulatedSurface(*meshes.spherical_cap(radius, degrees, n_ring, n_rings))


def assert_boundary_slid_along_the_loops(mesh):
    """Boundary nodes on their flattened loops (to 1e-12 of its length), corners where they were, some moved."""
    outline, plane = mesh.stages.outline, mesh.stages.plane
    start, moved = 0, 0
    for loop, corners, count in zip(outline.loops, outline.corners, plane.info["boundary_rings"]):
        nodes = np.arange(start, start + count)
        start += count
        length = loop.length
        assert np.all(
            shapely.distance(shapely.LinearRing(loop.points), shapely.points(mesh.uv[nodes])) <= 1e-12 * length
        )
        before = mesh.stages.remapped_uv[nodes]
        for corner in loop.at(corners):
            at = np.linalg.norm(before - corner, axis=1) <= REL_TOL * length
            assert at.sum() == 1 and np.array_equal(mesh.uv[nodes[at]], before[at])
        moved += int(np.count_nonzero(np.any(mesh.uv[nodes] != before, axis=1)))
    assert moved > 0
