"""What the report and the plot draw (equimesh.io._view): every member in one group, the bins, the outline."""

import numpy as np
import report_meshes
from hypothesis import given
from hypothesis import strategies as st

from equimesh import length_classes
from equimesh.io._view import MAX_BINS, PALETTE, REST_COLOUR, class_groups, length_bins, mesh_view

large_mesh = report_meshes.large_mesh  # the shared fixture
roof_mesh = report_meshes.roof_mesh  # the shared fixture

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


def test_the_outline_is_the_outer_boundary_and_the_openings(roof_mesh):
    view = mesh_view(roof_mesh)
    rings = roof_mesh.stages.plane.info["boundary_rings"]
    assert len(rings) == 3  # the outer boundary and two openings
    # a closed ring of k nodes has k edges; the outer ring's nodes come first
    assert len(view.boundary) == rings[0] and len(view.openings) == sum(rings[1:])
    assert (view.boundary < rings[0]).all() and (view.openings >= rings[0]).all()


def test_a_planar_mesh_is_drawn_at_z_0_and_its_histogram_counts_every_member(large_mesh):
    view = mesh_view(large_mesh, 0.005)
    assert view.points.shape[1] == 3 and not view.points[:, 2].any()
    edges, counts = view.histogram()
    assert counts.shape == (len(view.groups), len(edges) - 1) and counts.sum() == len(large_mesh.edges)
    angle_edges, angle_counts = view.angle_histogram()
    assert angle_counts.sum() == 3 * len(large_mesh.triangles)
