"""The lattice part K of Problem 2 (Section 3 of the paper; ``planar/lattice.py``), tested directly.

What must hold: the lattice has spacing ``l`` at ``angle`` (mod 60 degrees)
through ``offset``; a vertex is kept exactly when it lies inside P at least
``clearance * l`` from its boundary (Lemma 3 (1), compared with shapely's
distance on every vertex of a grid wider than the polygon); K is the union of
the lattice triangles with three kept vertices, its boundary edges are the
edges of one triangle, with K on their left, and there is one seed inside
each edge-connected component.  Each test runs in milliseconds, so that the
mutants of ``lattice.py`` (``make mutation``) are cheap to kill.
"""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given
from hypothesis import strategies as st
from invariants import check_edge_lengths

import equimesh
from equimesh.planar import lattice
from equimesh.planar.polygon import as_polygon
from equimesh.tolerance import at_least

S3 = math.sqrt(3.0)


SQUARE = np.array([[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]])


#: Two 6 x 6 rooms joined by a corridor 1.5 wide: no lattice vertex is 1 from both walls of the corridor.
DUMBBELL = np.array(
    [[0, 0], [6, 0], [6, 2], [9, 2], [9, 0], [15, 0], [15, 6], [9, 6], [9, 3.5], [6, 3.5], [6, 6], [0, 6]], float
)


HOLE = np.array([[2.5, 2.5], [3.5, 2.5], [3.5, 3.5], [2.5, 3.5]])


def brute_force_kept(poly, l, angle, offset, clearance, ij):
    """Which lattice vertices ``ij`` lie inside ``poly`` at least ``clearance l`` from its boundary (shapely, one by
    one)."""
    lp = poly.local_length(l)
    pts = lattice.lattice_points(ij, lp, angle, lattice.local_offset(poly, l, angle, offset))
    shape = poly.region
    inside = shapely.contains_xy(shape, pts[:, 0], pts[:, 1])
    far = at_least(shapely.distance(shapely.points(pts), shape.boundary), clearance * lp)
    return inside & far


def test_basis_at_angle_zero_by_hand():
    """a1 = l (1, 0), a2 = l (1/2, sqrt(3)/2)."""
    np.testing.assert_allclose(lattice.lattice_basis(2.0, 0.0), [[2.0, 0.0], [1.0, S3]], atol=1e-15)


@given(st.floats(-1e6, 1e6, allow_nan=False), st.sampled_from([0.5, 1.0, 3.0]))
def test_basis_vectors_have_length_l_and_turn_by_60_degrees(angle, l):
    """Both vectors are l long, a2 is a1 turned by 60 degrees, and a1 points at ``angle`` modulo 60."""
    a1, a2 = lattice.lattice_basis(l, angle)
    np.testing.assert_allclose([np.hypot(*a1), np.hypot(*a2)], [l, l], rtol=1e-12)
    np.testing.assert_allclose(a1 @ a2, 0.5 * l * l, rtol=1e-12, atol=1e-12 * l * l)
    assert a1[0] * a2[1] - a1[1] * a2[0] > 0
    t = math.radians(angle % 60.0)
    np.testing.assert_allclose(a1, [l * math.cos(t), l * math.sin(t)], atol=1e-12 * l)


def test_basis_is_periodic_in_60_degrees_exactly():
    """A huge angle gives the lattice of its remainder, bit for bit; 75 degrees is 15."""
    assert np.array_equal(lattice.lattice_basis(1.0, 1e20), lattice.lattice_basis(1.0, 1e20 % 60.0))
    assert np.array_equal(lattice.lattice_basis(1.0, 75.0), lattice.lattice_basis(1.0, 15.0))


def test_lattice_points_by_hand():
    """offset + i a1 + j a2 at angle 0."""
    pts = lattice.lattice_points([[0, 0], [1, 0], [0, 1], [-1, 2]], 2.0, 0.0, (10.0, 20.0))
    np.testing.assert_allclose(pts, [[10, 20], [12, 20], [11, 20 + S3], [10, 20 + 2 * S3]], atol=1e-13)


@pytest.mark.parametrize(
    "offset, expected",
    [
        ((3.0, 4.0), (3.0, 4.0)),  # near the polygon: kept as is
        ((13.0, 0.0), (13.0, 0.0)),  # exactly 2 * 6 + 1 from the local origin: still kept
        ((13.25, 0.0), (0.25, 0.0)),  # farther: moved by 13 lattice vectors a1
        ((0.0, -13.5), (0.0, -13.5 + 8 * S3)),  # moved by 8 (2 a2 - a1), i.e. 8 rows up
    ],
)
def test_local_offset_keeps_a_near_offset_and_moves_a_far_one_by_whole_lattice_vectors(offset, expected):
    """The frame of SQUARE at l = 1 is the identity; the threshold is 2 * extent + l = 13."""
    poly = as_polygon(SQUARE, 1.0)
    np.testing.assert_allclose(lattice.local_offset(poly, 1.0, 0.0, offset), expected, atol=1e-12)


def test_local_offset_in_a_scaled_and_translated_frame():
    """A polygon near 1e9 with l = 4: the offset is the same lattice, moved next to the local origin."""
    poly = as_polygon(SQUARE * 4.0 + 1e9, 4.0)
    local = lattice.local_offset(poly, 4.0, 30.0, (0.0, 0.0))
    lp = poly.local_length(4.0)
    assert np.max(np.abs(local)) <= 2.0 * lp
    steps = (local - poly.frame.to_local((0.0, 0.0))) @ np.linalg.inv(lattice.lattice_basis(lp, 30.0))
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-6)


POLYGONS = {
    "square from its top-right corner": (np.roll(SQUARE, 2, axis=0), None),
    "dumbbell": (DUMBBELL, None),
    "square with a hole": (SQUARE * 2.0, [HOLE * 2.0]),
}


@pytest.mark.parametrize("name", sorted(POLYGONS))
@given(
    angle=st.floats(0.0, 60.0),
    ox=st.floats(-2.0, 2.0),
    oy=st.floats(-2.0, 2.0),
    clearance=st.sampled_from([1.0, 1.3, 2.0]),
    l=st.sampled_from([0.75, 1.0]),
)
def test_kept_vertices_are_those_inside_at_clearance(name, angle, ox, oy, clearance, l):
    """Lemma 3 (1): kept <=> inside P and at least clearance l from its boundary; the grid covers P."""
    vertices, holes = POLYGONS[name]
    poly = as_polygon(vertices, l, holes)
    ii, jj, pts, kept = lattice.kept_vertices(poly, l, angle, (ox, oy), clearance)
    ij = np.column_stack([ii.ravel(), jj.ravel()])
    assert np.array_equal(kept.ravel(), brute_force_kept(poly, l, angle, (ox, oy), clearance, ij))
    np.testing.assert_allclose(
        pts,
        lattice.lattice_points(ij, poly.local_length(l), angle, lattice.local_offset(poly, l, angle, (ox, oy))),
        atol=1e-12,
    )
    # No vertex of P's bounding box is missing from the grid: a wider grid keeps no more vertices.
    pad = 3
    wide = np.stack(
        np.meshgrid(
            np.arange(ii.min() - pad, ii.max() + pad + 1), np.arange(jj.min() - pad, jj.max() + pad + 1), indexing="ij"
        ),
        axis=-1,
    ).reshape(-1, 2)
    assert brute_force_kept(poly, l, angle, (ox, oy), clearance, wide).sum() == kept.sum()
    # The bounding box of P lies inside the grid, one lattice step away from its border.
    lo, hi = poly.local.min(axis=0), poly.local.max(axis=0)
    inside_box = np.all((pts >= lo) & (pts <= hi), axis=1)
    assert not np.any(
        inside_box
        & ((ii.ravel() == ii.min()) | (ii.ravel() == ii.max()) | (jj.ravel() == jj.min()) | (jj.ravel() == jj.max()))
    )


def test_kept_vertices_grid_by_hand():
    """SQUARE, l = 1, angle 0, offset (0.5, 1): i = x - y/sqrt(3), j = 2y/sqrt(3) of the box corners minus the
    offset span i in [-3.39, 6.08], j in [-1.15, 5.77]; floor/ceil and one step more: i in [-5, 8], j in [-3, 7]."""
    ii, jj, pts, kept = lattice.kept_vertices(as_polygon(SQUARE, 1.0), 1.0, 0.0, (0.5, 1.0))
    assert (ii.min(), ii.max(), jj.min(), jj.max()) == (-5, 8, -3, 7)
    assert ii.shape == jj.shape == kept.shape == (14, 11) and pts.shape == (154, 2)
    assert ii.dtype.kind == jj.dtype.kind == "i"
    assert kept.sum() == 22


def test_triangle_masks_by_hand():
    """Up (i,j),(i+1,j),(i,j+1) and down (i+1,j),(i+1,j+1),(i,j+1) need all three vertices."""
    kept = np.array([[1, 1, 0], [1, 1, 1], [1, 0, 1]], dtype=bool)
    up, down = lattice.lattice_triangle_masks(kept)
    assert up.tolist() == [[True, False], [True, False]]
    assert down.tolist() == [[True, False], [False, False]]


def lattice_part_checks(part, poly, l, angle, offset, clearance):
    """The properties of :class:`LatticePart` that follow from its definition."""
    lp = poly.local_length(l)
    np.testing.assert_allclose(
        part.points,
        lattice.lattice_points(part.ij, lp, angle, lattice.local_offset(poly, l, angle, offset)),
        atol=1e-12,
    )
    assert len(np.unique(part.ij, axis=0)) == len(part.ij)
    assert np.array_equal(np.unique(part.triangles), np.arange(len(part.points)))  # no dangling vertex
    assert brute_force_kept(poly, l, angle, offset, clearance, part.ij).all()
    a, b, c = (part.points[part.triangles[:, k]] for k in range(3))
    for p, q in ((a, b), (b, c), (c, a)):
        np.testing.assert_allclose(np.linalg.norm(q - p, axis=1), lp, rtol=1e-12)
    cross = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]
    np.testing.assert_allclose(cross, S3 / 2 * lp * lp, rtol=1e-9)  # counter-clockwise, area sqrt(3)/4 l^2
    # Every lattice triangle with three kept vertices is there.
    ii, jj, _, kept = lattice.kept_vertices(poly, l, angle, offset, clearance)
    up, down = lattice.lattice_triangle_masks(kept)
    assert len(part.triangles) == up.sum() + down.sum()
    # Boundary edges: in exactly one triangle, directed as in it (K on the left).
    directed = {tuple(e) for t in part.triangles for e in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0]))}
    single = {e for e in directed if (e[1], e[0]) not in directed}
    assert {tuple(e) for e in part.boundary_edges} == single
    assert np.array_equal(part.boundary_vertices, np.unique(part.boundary_edges))
    # One seed per edge-connected component, each inside a triangle of its own component.
    shapes = shapely.unary_union([shapely.Polygon(part.points[t]) for t in part.triangles])
    components = list(getattr(shapes, "geoms", [shapes])) if len(part.triangles) else []
    assert len(part.holes) == len(components)
    for seed in part.holes:
        assert sum(shapely.contains_xy(comp, *seed) for comp in components) == 1
    assert len(
        {next(k for k, comp in enumerate(components) if shapely.contains_xy(comp, *s)) for s in part.holes}
    ) == len(components)


@pytest.mark.parametrize("name", sorted(POLYGONS))
@given(
    angle=st.floats(0.0, 60.0), ox=st.floats(-2.0, 2.0), oy=st.floats(-2.0, 2.0), clearance=st.sampled_from([1.0, 1.5])
)
def test_lattice_part_is_the_union_of_fully_kept_lattice_triangles(name, angle, ox, oy, clearance):
    """K: kept vertices only, edges exactly l, counter-clockwise, boundary with K on its left, one seed per
    component."""
    vertices, holes = POLYGONS[name]
    poly = as_polygon(vertices, 1.0, holes)
    part = lattice.lattice_part(poly, 1.0, angle, (ox, oy), clearance)
    lattice_part_checks(part, poly, 1.0, angle, (ox, oy), clearance)


def test_dumbbell_has_two_components_and_square_ring_one():
    """The corridor of DUMBBELL keeps no triangle: two seeds; the square with a hole: one annulus, one seed."""
    part = lattice.lattice_part(as_polygon(DUMBBELL, 1.0), 1.0, 0.0, (0.0, 0.0))
    assert len(part.holes) == 2
    assert sorted(part.holes[:, 0] < 7.5) == [False, True]
    ring = lattice.lattice_part(as_polygon(SQUARE * 2.0, 1.0, [HOLE * 2.0]), 1.0, 0.0, (0.0, 0.0))
    assert len(ring.holes) == 1
    assert len(ring.boundary_edges) > 0 and len(np.unique(ring.boundary_edges)) == len(ring.boundary_edges)


def test_square_lattice_part_by_hand():
    """SQUARE, l = 1, angle 0, offset (0.5, 1): rows y = 1, 1 + h, ..., kept x in [1, 5]: 4 rows of 5 or 4 vertices.

    Row j (y = 1 + j sqrt(3)/2, j = 0..4; row 4 at y = 4.46 <= 5) has x = 0.5 + j/2 + i; kept x in [1, 5]:
    rows 0, 2, 4: x = 1.5 .. 4.5 (4 vertices); rows 1, 3: x = 1 .. 5 (5 vertices).  Between two rows of
    4 and 5 vertices there are 4 + 3 = 7 triangles: 4 strips, 28 triangles.
    """
    part = lattice.lattice_part(as_polygon(SQUARE, 1.0), 1.0, 0.0, (0.5, 1.0))
    assert len(part.points) == 22
    assert len(part.triangles) == 28
    assert len(part.boundary_edges) == 3 + 3 + 2 * 4  # top and bottom rows, two zig-zag sides
    np.testing.assert_allclose(part.holes, [part.points[part.triangles[0]].mean(axis=0)])


def test_component_seeds_by_hand():
    """Triangles touching at a vertex only are two components; the seed is the centroid of each first triangle."""
    points = np.array([[0, 0], [3, 0], [0, 3], [3, 3], [6, 3], [3, 6], [6, 0]], float)
    tri = np.array([[1, 3, 2], [3, 4, 5], [0, 1, 2], [1, 6, 3]])  # {0, 2, 3} share edges, 1 touches at 3 only
    seeds = lattice.component_seeds(points, tri)
    np.testing.assert_allclose(seeds, [points[[1, 3, 2]].mean(axis=0), points[[3, 4, 5]].mean(axis=0)])
    assert lattice.component_seeds(points, np.empty((0, 3), int)).shape == (0, 2)


def test_lattice_adjacent_is_exactly_the_six_steps():
    """The six neighbour steps and their translates are adjacent; (0, 0), (1, 1), (2, 0), (-1, -1), (2, -1) are not."""
    steps = np.array(lattice.NEIGHBOUR_STEPS)
    base = np.array([[3, -2]] * 6)
    assert lattice.lattice_adjacent(base, base + steps).all()
    assert lattice.lattice_adjacent(base + steps, base).all()
    others = np.array([[0, 0], [1, 1], [2, 0], [-1, -1], [2, -1], [1, -2]])
    assert not lattice.lattice_adjacent(base, base + others).any()
    mixed = np.array([[1, 0], [1, 1], [0, -1], [2, 0]])
    assert lattice.lattice_adjacent(base[:4], base[:4] + mixed).tolist() == [True, False, True, False]
    assert sorted(map(tuple, steps.tolist())) == [(-1, 0), (-1, 1), (0, -1), (0, 1), (1, -1), (1, 0)]


def test_defaults_are_angle_0_offset_origin_clearance_1():
    """The paper's lattice: first vector along x, vertex (0, 0) at the origin, vertices kept at distance l."""
    poly = as_polygon(SQUARE, 1.0)
    explicit = lattice.lattice_part(poly, 1.0, 0.0, (0.0, 0.0), 1.0)
    default = lattice.lattice_part(poly, 1.0)
    assert np.array_equal(default.points, explicit.points) and np.array_equal(default.triangles, explicit.triangles)
    for a, b in zip(lattice.kept_vertices(poly, 1.0), lattice.kept_vertices(poly, 1.0, 0.0, (0.0, 0.0), 1.0)):
        assert np.array_equal(a, b)


def test_a_far_offset_is_the_same_lattice_as_its_near_equivalent():
    """Offsets 1000 a1 + 1000 a2 apart give the same lattice, so the same kept vertices, at any angle."""
    poly = as_polygon(SQUARE, 1.0)
    a1, a2 = lattice.lattice_basis(1.0, 30.0)
    near = lattice.kept_vertices(poly, 1.0, 30.0, (0.3, 0.2))
    far = lattice.kept_vertices(poly, 1.0, 30.0, np.array([0.3, 0.2]) + 1000.0 * (a1 + a2))
    assert near[3].sum() == far[3].sum() > 0
    np.testing.assert_allclose(near[2][near[3].ravel()], far[2][far[3].ravel()], atol=1e-9)


SQUARE10 = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


@pytest.mark.parametrize("angle", [1e14, 1e20, -7.5, 1e300])
def test_angle_is_reduced_modulo_60_degrees(angle):
    """The lattice has 60-degree symmetry: a huge angle is its exact remainder, and the mesh is valid."""
    mesh = equimesh.uniform_triangulation(SQUARE10, 1.0, angle=angle)
    same = equimesh.uniform_triangulation(SQUARE10, 1.0, angle=angle % 60.0)
    assert np.array_equal(mesh.points, same.points) and np.array_equal(mesh.triangles, same.triangles)
    check_edge_lengths(mesh, 1.0)
    assert np.max(np.abs(mesh.edge_lengths()[mesh.g1_mask] - 1.0)) <= 1e-12
