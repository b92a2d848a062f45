"""The Problem 2 checks of ``invariants_uniform.py`` have teeth: each catches a mesh broken in its way."""

import invariants_uniform as inv
import numpy as np
import pytest

import equimesh
import equimesh.planar.polygon
from equimesh import G1
from equimesh._geometry import orient
from equimesh.mesh import PlanarMesh
from equimesh.planar.insertion.region import constrained_delaunay
from equimesh.testing.generators import rectangle


@pytest.fixture(scope="module")
def square_mesh():
    vertices = rectangle(9.0, 7.0)
    return vertices, equimesh.uniform_triangulation(vertices, 1.0)


def _with(mesh, points=None, triangles=None):
    return PlanarMesh.build(
        mesh.points if points is None else points,
        mesh.triangles if triangles is None else triangles,
        mesh.length,
        mesh.n_boundary,
        g1_edges=mesh.edges[mesh.edge_groups == G1],
        info=mesh.info,
    )


def test_checks_catch_a_moved_point(square_mesh):
    """Moving an inserted point onto a neighbour's doorstep breaks separation and Theorem 3."""
    vertices, mesh = square_mesh
    k = mesh.n_boundary
    j = mesh.edges[np.any(mesh.edges == k, axis=1)][0]
    other = j[j != k][0]
    pts = mesh.points.copy()
    pts[k] = pts[other] + 0.5 * (pts[k] - pts[other])
    bad = _with(mesh, points=pts)
    with pytest.raises(AssertionError):
        inv.check_theorem3(bad, 1.0)
    with pytest.raises(AssertionError):
        inv.check_separation(bad, vertices, 1.0)


def test_checks_catch_a_missing_triangle(square_mesh):
    """Dropping a triangle leaves a hole: area and boundary checks fail."""
    vertices, mesh = square_mesh
    bad = _with(mesh, triangles=mesh.triangles[1:])
    with pytest.raises(AssertionError):
        inv.check_triangulation(bad, vertices, 1.0)


def test_checks_catch_a_flipped_edge(square_mesh):
    """Flipping a non-lattice interior edge of a convex quadrilateral breaks the empty-circle property."""
    vertices, mesh = square_mesh
    flip = next(_convex_flips(mesh), None)
    assert flip is not None, "no flippable strip edge found"
    a, b, new = flip
    flipped = _with(mesh, triangles=np.vstack([np.delete(mesh.triangles, [a, b], axis=0), new]))
    with pytest.raises(AssertionError):
        inv.check_constrained_delaunay(flipped, vertices, 1.0)


def _convex_flips(mesh):
    """Yield pairs of strip triangles ``(a, b, flipped)`` sharing an edge of a convex quadrilateral, and their flip."""
    tri = mesh.triangles
    strip = np.flatnonzero(~inv.lattice_mask(mesh))
    for a in strip:
        for b in strip[strip > a]:
            shared = np.intersect1d(tri[a], tri[b])
            if len(shared) != 2:
                continue
            p, q = np.setdiff1d(tri[a], shared)[0], np.setdiff1d(tri[b], shared)[0]
            new = np.array([[p, q, shared[0]], [q, p, shared[1]]])
            o = orient(*(mesh.points[new[:, i]] for i in range(3)))
            if np.all(o > 1e-6) or np.all(o < -1e-6):  # convex quadrilateral: the flip is a triangulation
                yield a, b, new


def test_checks_catch_a_missing_point(square_mesh):
    """Removing the points near the centre (and re-triangulating) leaves a part of P uncovered."""
    vertices, mesh = square_mesh
    nb = mesh.n_boundary
    far = np.linalg.norm(mesh.points - [4.5, 3.5], axis=1) > 1.2
    far[:nb] = True
    pts = mesh.points[far]
    seg = np.column_stack([np.arange(nb), (np.arange(nb) + 1) % nb])
    tri = constrained_delaunay(pts, seg, np.empty((0, 2)))
    bad = PlanarMesh.build(pts, tri, 1.0, nb, info={"n_lattice_triangles": 0})
    with pytest.raises(AssertionError):
        inv.check_covering(bad, vertices, 1.0)
