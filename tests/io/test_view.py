"""What the report and the plot draw (equimesh.io._view): every member in one group, the bins, the outline."""

from types import SimpleNamespace

import numpy as np
import report_meshes
from conftest import TentMesh
from hypothesis import given
from hypothesis import strategies as st

from equimesh import length_classes
from equimesh.io._view import MAX_BINS, PALETTE, REST_COLOUR, class_groups, length_bins, mesh_view
from equimesh.mesh import G1
from equimesh.metrics import triangle_angles

square_mesh = report_meshes.square_mesh  # the shared fixture

lengths_st = st.lists(st.floats(0.5, 3.0, allow_nan=False), min_size=1, max_size=300)
tolerances = st.sampled_from([1e-6, 0.001, 0.005, 0.05, 0.3])


@given(lengths_st, tolerances, st.integers(2, 50))
def test_every_member_is_in_exactly_one_group_and_the_largest_classes_are_drawn(lengths, tolerance, max_drawn):
    classes = length_classes(lengths, 1.0, tolerance)
    groups = class_groups(classes, max_drawn)
    members = np.sort(np.concatenate([g.members for g in groups]))
    assert np.array_equal(members, np.arange(len(lengths)))
    assert len(groups) <= max_drawn
    for g in groups:
        assert np.array_equal(np.sort(np.flatnonzero(np.isin(classes.member_class, g.classes))), g.members)
    drawn = [g for g in groups if len(g.classes) == 1]
    rest = [g for g in groups if len(g.classes) > 1]
    assert [g.classes[0] for g in drawn] == sorted(g.classes[0] for g in drawn)  # in order of length
    assert [g.colour for g in drawn] == [PALETTE[i % len(PALETTE)] for i in range(len(drawn))]
    if len(classes) <= max_drawn:
        assert not rest and len(drawn) == len(classes)
    else:
        (rest,) = rest
        assert rest.colour == REST_COLOUR and len(drawn) == max_drawn - 1
        smallest_drawn = min(classes.count[g.classes[0]] for g in drawn)
        assert smallest_drawn >= classes.count[list(rest.classes)].max()


@given(lengths_st, tolerances, st.sampled_from([0.7, 1.0, 2.5]))
def test_bins_hold_every_length_and_lie_on_l_plus_whole_multiples_of_the_tolerance(lengths, tolerance, l):
    """So that the window l +- tolerance l is whole bins: the edges are l + k tolerance l, k whole."""
    lengths = l * np.asarray(lengths)
    edges = length_bins(lengths, l, tolerance)
    assert edges[0] <= lengths.min() and lengths.max() <= edges[-1]
    assert 1 <= len(edges) - 1 <= MAX_BINS
    k = (edges - l) / (tolerance * l)
    assert np.allclose(k, np.round(k), rtol=0, atol=1e-6 * max(1.0, np.abs(k).max()))
    assert len(set(np.diff(np.round(k)).tolist())) == 1  # one width


@given(lengths_st, tolerances, st.integers(2, 40))
def test_bins_never_exceed_their_limit(lengths, tolerance, max_bins):
    """Rounding the ends out to whole steps never adds a bin beyond ``max_bins``; the bins still hold every length
    and lie on 1 + whole multiples of the tolerance."""
    edges = length_bins(lengths, 1.0, tolerance, max_bins=max_bins)
    assert 1 <= len(edges) - 1 <= max_bins
    assert edges[0] <= min(lengths) and max(lengths) <= edges[-1]
    k = (edges - 1.0) / tolerance
    assert np.allclose(k, np.round(k), rtol=0, atol=1e-6 * max(1.0, np.abs(k).max()))


def test_the_outline_is_the_outer_boundary_and_the_openings(square_mesh):
    """The planar mesh's info says how many nodes the outer ring has; a surface mesh's plane says it; without
    rings every boundary node is on the outer ring."""
    mesh = square_mesh
    outer, opening = mesh.info["boundary_rings"]
    view = mesh_view(mesh)
    # a closed ring of k nodes has k edges; the outer ring's nodes come first
    assert len(view.boundary) == outer and len(view.openings) == opening
    assert (view.boundary < outer).all() and (view.openings >= outer).all()
    surface = SimpleNamespace(**{k: getattr(mesh, k) for k in ("points", "triangles", "edges", "edge_groups")})
    surface.length, surface.n_boundary = mesh.length, mesh.n_boundary
    surface.stages = SimpleNamespace(plane=SimpleNamespace(info=mesh.info))
    assert np.array_equal(mesh_view(surface).openings, view.openings)
    surface.stages.plane.info = {}
    assert len(mesh_view(surface).openings) == 0 and len(mesh_view(surface).boundary) == outer + opening


def test_a_planar_mesh_is_drawn_at_z_0_and_its_histogram_counts_every_member(square_mesh):
    mesh = square_mesh
    view = mesh_view(mesh, 0.005)
    assert view.points.shape == (len(mesh.points), 3) and not view.points[:, 2].any()
    assert view.n_g1 == 0 and not (mesh.edge_groups == G1).any()  # none of the square's members is in G1
    np.testing.assert_array_equal(view.points[:, :2], mesh.points)
    edges, counts = view.histogram()
    assert counts.shape == (len(view.groups), len(edges) - 1) and counts.sum() == len(mesh.edges)
    angle_edges, angle_counts = view.angle_histogram()
    assert angle_counts.sum() == 3 * len(mesh.triangles)


def test_the_view_of_the_tent(tent_mesh):
    """Seven nodes by hand: the three classes in order of length, labelled with their nominal length and count, the
    six sides as the outer boundary, the six G1 spokes, whatever integer types the mesh holds."""
    mesh = TentMesh()
    mesh.triangles, mesh.edges = mesh.triangles.astype(np.int32), mesh.edges.astype(np.int32)
    mesh.points = np.round(4 * mesh.points).astype(int)
    np.testing.assert_array_equal(mesh_view(mesh).points, np.round(4 * tent_mesh.points))
    assert mesh_view(mesh).points.dtype == float
    mesh.points = tent_mesh.points
    view = mesh_view(mesh, "1%")
    assert view.classes.count.tolist() == [6, 3, 3]
    assert view.tolerance == 0.01 and view.l == 1.0 and view.n_g1 == 6
    assert view.triangles.dtype == view.edges.dtype == np.int64
    np.testing.assert_array_equal(view.edges, tent_mesh.edges)
    np.testing.assert_array_equal(view.lengths, tent_mesh.edge_lengths())
    assert [g.label for g in view.groups] == ["1.0198 (6)", "1.04403 (3)", "1.11803 (3)"]
    assert [g.colour for g in view.groups] == list(PALETTE[:3])
    assert [g.members.tolist() for g in view.groups] == [[0, 1, 3, 5, 7, 9], [4, 8, 11], [2, 6, 10]]
    assert [g.classes for g in view.groups] == [(0,), (1,), (2,)]
    assert view.boundary.tolist() == [[0, 1], [0, 5], [1, 2], [2, 3], [3, 4], [4, 5]] and view.openings.shape == (0, 2)
    np.testing.assert_allclose(view.deviation, tent_mesh.edge_lengths() - 1.0)
    edges, counts = view.histogram()
    np.testing.assert_allclose(edges, 1.0 + 0.01 * np.arange(1, 13))
    assert counts.tolist() == [[6] + [0] * 10, [0] * 3 + [3] + [0] * 7, [0] * 10 + [3]]
    angle_edges, angle_counts = view.angle_histogram()
    np.testing.assert_array_equal(angle_edges, np.arange(181.0))
    expected, _ = np.histogram(triangle_angles(view.points, view.triangles), bins=np.arange(181.0))
    assert angle_counts.tolist() == expected.tolist() and angle_counts.sum() == 18


def test_as_many_classes_as_drawn_are_all_drawn_and_the_largest_first_beyond(tent_mesh):
    """max_drawn classes: each its own group; more: the largest ones, and among equal counts the shorter."""
    classes = length_classes(tent_mesh.edge_lengths(), 1.0, 0.01)
    groups = class_groups(classes, max_drawn=3)
    assert [g.classes for g in groups] == [(0,), (1,), (2,)] and [g.colour for g in groups] == list(PALETTE[:3])
    middle = length_classes([1.0, 1.1, 1.1, 1.1, 1.2], 1.0, 0.01)  # the largest class is not the first
    assert [g.classes for g in class_groups(middle, max_drawn=2)] == [(1,), (0, 2)]
    ties = length_classes(np.repeat(1.0 + 0.1 * np.arange(20), [1, 2] * 10), 1.0, 0.01)  # ten of 2 members
    drawn = [g.classes[0] for g in class_groups(ties, max_drawn=10)[:-1]]
    assert drawn == [1, 3, 5, 7, 9, 11, 13, 15, 17]


def test_the_smaller_classes_are_one_grey_group(tent_mesh):
    classes = length_classes(tent_mesh.edge_lengths(), 1.0, 0.01)
    drawn, rest = class_groups(classes, max_drawn=2)
    assert (drawn.label, drawn.colour, drawn.classes) == ("1.0198 (6)", PALETTE[0], (0,))
    assert (rest.label, rest.colour, rest.classes) == ("2 smaller classes (6)", REST_COLOUR, (1, 2))
    assert rest.members.tolist() == [2, 4, 6, 8, 10, 11]


def test_length_bins_by_hand():
    """Bins of tolerance l, l an edge, widened to whole multiples beyond max_bins; no lengths: one bin above l."""
    np.testing.assert_array_equal(length_bins([0.75, 1.0, 1.3], 1.0, 0.25), [0.75, 1.0, 1.25, 1.5])
    np.testing.assert_array_equal(length_bins([1.0, 1.0], 1.0, 0.25), [1.0, 1.25])
    np.testing.assert_array_equal(length_bins(np.array([]), 1.0, 0.25), [1.0, 1.25])
    np.testing.assert_array_equal(length_bins([0, 3], 1.0, 0.25, max_bins=6), np.arange(7) / 2)
    np.testing.assert_array_equal(length_bins([0, 3], 1.0, 0.25, max_bins=12), np.arange(-4, 9) / 4 + 1)
    # Steps 1 and 2 round out to 3 bins; a step of 3 (0.75) gives 2: [0.25, 1.0, 1.75].
    np.testing.assert_allclose(length_bins([0.8, 1.7], 1.0, 0.25, max_bins=2), [0.25, 1.0, 1.75])
    # Every length above l + tolerance l: 4 bins from 3 to 7 steps above l fit 4, so the step stays one bin.
    np.testing.assert_array_equal(length_bins([1.75, 2.75], 1.0, 0.25, max_bins=4), [1.75, 2.0, 2.25, 2.5, 2.75])
