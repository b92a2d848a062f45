"""Topology and geometry helpers of equimesh.mesh: column-wise versions give the floats and rows of the obvious ones."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from equimesh._geometry import orient
from equimesh.mesh import (
    counter_clockwise,
    edge_keys,
    edge_lengths,
    half_edges,
    single_edges,
    triangle_orient,
    unique_edges,
)

coordinates = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False)


@st.composite
def points_and_triangles(draw, dim=2):
    n = draw(st.integers(3, 12))
    points = draw(arrays(float, (n, dim), elements=coordinates))
    triangles = draw(arrays(np.int64, (draw(st.integers(0, 20)), 3), elements=st.integers(0, n - 1)))
    return points, triangles


@given(points_and_triangles())
def test_triangle_orient_is_orient_bit_for_bit(data):
    p, t = data
    assert np.array_equal(triangle_orient(p, t), orient(p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]))


@given(points_and_triangles())
def test_counter_clockwise_flips_exactly_the_clockwise_rows(data):
    p, t = data
    out = counter_clockwise(p, t)
    assert np.all(triangle_orient(p, out) >= 0)
    assert np.array_equal(np.sort(out, axis=1), np.sort(t, axis=1))


@given(st.integers(2, 3).flatmap(lambda dim: points_and_triangles(dim)))
def test_edge_lengths_are_the_norms_bit_for_bit(data):
    p, t = data
    e = half_edges(t)
    assert np.array_equal(edge_lengths(p, e), np.linalg.norm(p[e[:, 1]] - p[e[:, 0]], axis=1))


@given(points_and_triangles())
def test_unique_edges_are_the_sorted_unique_undirected_edges(data):
    _, t = data
    expected = np.unique(np.sort(half_edges(t), axis=1), axis=0).reshape(-1, 2)
    got = unique_edges(t)
    assert got.dtype == np.int64
    assert np.array_equal(got, expected)


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_compiled_orientation_is_the_floats_of_orient(seed):
    """``triangle_orient`` (a compiled loop) gives the floats of ``_geometry.orient`` bit for bit, at any scale."""
    rng = np.random.default_rng(seed)
    p = rng.standard_normal((200, 2)) * np.exp(rng.uniform(-30.0, 30.0, (200, 1)))
    t = rng.integers(0, 200, (500, 3))
    assert np.array_equal(triangle_orient(p, t), orient(p[t[:, 0]], p[t[:, 1]], p[t[:, 2]]))


def test_single_edges_by_hand():
    """Two triangles sharing edge 1-2: its two half-edges are dropped, the four others kept in their direction."""
    edges = single_edges(np.array([[0, 1, 2], [2, 1, 3]]))
    assert sorted(map(tuple, edges.tolist())) == [(0, 1), (1, 3), (2, 0), (3, 2)]


def test_edge_keys_take_a_common_base():
    """Keys of a subset of edges in the base of the whole set: equal keys for equal edges, in either direction."""
    keys, n = edge_keys([[0, 1], [1, 5], [2, 3]])
    assert n == 6 and np.array_equal(edge_keys([[3, 2], [1, 0]], n)[0], keys[[2, 0]])
