"""The auxiliary triangulation of [0, 1]^2 (Section 4, step 1)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh import EquimeshError
from equimesh._geometry import orient, signed_area
from equimesh.surface.auxiliary import auxiliary_grid
from equimesh.surface.charts.chart import SIDES

sizes = st.integers(min_value=1, max_value=12)


@settings(max_examples=30, deadline=None)
@given(n_u=sizes, n_v=sizes)
def test_grid_is_a_ccw_triangulation_of_the_square(n_u, n_v):
    g = auxiliary_grid(n_u, n_v)
    assert g.uv.shape == ((n_u + 1) * (n_v + 1), 2)
    assert g.triangles.shape == (2 * n_u * n_v, 3)
    assert len(g.edges) == n_u * (n_v + 1) + n_v * (n_u + 1) + n_u * n_v
    assert len(g.uv) - len(g.edges) + len(g.triangles) == 1  # Euler, a disk
    area = 0.5 * orient(*(g.uv[g.triangles[:, k]] for k in range(3)))
    np.testing.assert_allclose(area, 1.0 / (2 * n_u * n_v))  # all CCW, equal halves of a cell
    assert np.isclose(area.sum(), 1.0)
    # right triangles: one angle of 90 degrees in each
    p = g.uv[g.triangles]
    dots = [np.sum((p[:, (k + 1) % 3] - p[:, k]) * (p[:, (k + 2) % 3] - p[:, k]), axis=1) for k in range(3)]
    assert np.all(np.isclose(np.min(np.abs(dots), axis=0), 0.0))


@settings(max_examples=30, deadline=None)
@given(n_u=sizes, n_v=sizes)
def test_boundary_loop_and_sides(n_u, n_v):
    g = auxiliary_grid(n_u, n_v)
    b = g.uv[g.boundary]
    assert len(g.boundary) == 2 * (n_u + n_v) == len(np.unique(g.boundary))
    assert signed_area(b) == pytest.approx(1.0)  # counter-clockwise around the square
    assert g.boundary[0] == 0
    want = np.column_stack([b[:, 0] == 0, b[:, 0] == 1, b[:, 1] == 0, b[:, 1] == 1])
    assert np.array_equal(g.boundary_sides, want)
    assert g.boundary_corner.sum() == 4
    on_border = np.any((g.uv == 0) | (g.uv == 1), axis=1)
    assert set(np.flatnonzero(on_border)) == set(g.boundary.tolist())
    # every boundary segment is a grid edge lying on the side it reports
    seg = np.sort(g.boundary_segments, axis=1)
    keys = set(map(tuple, g.edges.tolist()))
    assert all(tuple(s) in keys for s in seg.tolist())
    side = g.boundary_segment_side
    ends = g.uv[g.boundary_segments]
    for k, name in enumerate(SIDES):
        axis, value = k // 2, float(k % 2)
        assert np.all(ends[side == k][:, :, axis] == value), name


def test_node_numbering_and_diagonal():
    g = auxiliary_grid(3, 2)
    assert np.array_equal(g.uv[g.node(2, 1)], [2 / 3, 1 / 2])
    # the diagonal runs from (i, j) to (i+1, j+1)
    assert [g.node(0, 0), g.node(1, 1)] in g.edges.tolist()
    assert sorted([g.node(1, 0), g.node(0, 1)]) not in g.edges.tolist()


@pytest.mark.parametrize("bad", [0, -1, 2.5, True, "3"])
def test_invalid_sizes(bad):
    with pytest.raises(EquimeshError, match="n_u must be an integer of at least 1"):
        auxiliary_grid(bad, 3)
