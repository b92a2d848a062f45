"""The nested-dissection order of SuperLU's normal matrices: a permutation, less fill than a band, the same steps."""

import numpy as np
import scipy.sparse
import scipy.sparse.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh.surface.optimize.ordering import nested_dissection
from equimesh.surface.optimize.solver import FACTORISATIONS


def _grid(k):
    """The adjacency matrix of the k x k grid graph (node ``i k + j``), symmetric, no diagonal."""
    index = np.arange(k * k).reshape(k, k)
    across = np.column_stack([index[:, :-1].ravel(), index[:, 1:].ravel()])
    down = np.column_stack([index[:-1].ravel(), index[1:].ravel()])
    pairs = np.concatenate([across, down])
    rows, cols = np.concatenate([pairs[:, 0], pairs[:, 1]]), np.concatenate([pairs[:, 1], pairs[:, 0]])
    return scipy.sparse.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(k * k, k * k))


def _fill(graph, order):
    """The entries of the LU factors of ``graph``'s Laplacian plus the identity, eliminated in ``order``."""
    n = graph.shape[0]
    laplacian = scipy.sparse.diags(np.asarray(graph.sum(axis=1)).ravel() + 1.0) - graph
    permuted = scipy.sparse.csc_matrix(laplacian[order][:, order])
    options = {"SymmetricMode": True}
    lu = scipy.sparse.linalg.splu(permuted, permc_spec="NATURAL", diag_pivot_thresh=0.0, options=options)
    return lu.L.nnz + lu.U.nnz - n


@settings(deadline=None)
@given(
    n=st.integers(1, 120),
    edges=st.lists(st.tuples(st.integers(0, 119), st.integers(0, 119)), max_size=400),
    leaf=st.integers(1, 8),
)
def test_the_order_is_a_permutation_of_any_graph(n, edges, leaf):
    """Disconnected parts, isolated nodes and self-loops included."""
    pairs = np.array([(a % n, b % n) for a, b in edges], dtype=np.int64).reshape(-1, 2)
    rows, cols = np.concatenate([pairs[:, 0], pairs[:, 1]]), np.concatenate([pairs[:, 1], pairs[:, 0]])
    graph = scipy.sparse.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    order = nested_dissection(graph, leaf)
    assert order.dtype == np.int64 and np.array_equal(np.sort(order), np.arange(n))


def test_a_grid_fills_less_than_in_its_band_order():
    """On the 40 x 40 grid the dissected order fills the factors less than row by row (a band) does: 59,074 entries
    against 126,478."""
    graph = _grid(40)
    assert _fill(graph, nested_dissection(graph)) < 0.6 * _fill(graph, np.arange(40 * 40))


@settings(max_examples=10, deadline=None)
@given(k=st.integers(2, 30), seed=st.integers(0, 2**32 - 1))
def test_superlu_solves_alike_in_either_order(k, seed):
    """A grid Laplacian plus a random positive diagonal: the solutions in the dissected order and in SuperLU's
    minimum-degree order agree to 1e-12 relative."""
    rng = np.random.default_rng(seed)
    graph = scipy.sparse.triu(_grid(k), k=1).tocoo()
    n = k * k
    rows = np.concatenate([np.arange(n), graph.row])
    cols = np.concatenate([np.arange(n), graph.col])
    key = np.lexsort((cols, rows))
    rows, cols = rows[key], cols[key]
    degree = np.bincount(graph.row, minlength=n) + np.bincount(graph.col, minlength=n)
    values = np.where(rows == cols, degree[rows] + rng.uniform(1e-3, 1.0, len(rows)), -1.0)
    b = rng.standard_normal(n)
    solutions = [
        FACTORISATIONS["superlu"](rows, cols, n, ordering=ordering).factorise(values)(b)
        for ordering in ("nested dissection", "MMD_AT_PLUS_A")
    ]
    assert np.linalg.norm(solutions[0] - solutions[1]) <= 1e-12 * np.linalg.norm(solutions[1])


def _graph(n, pairs, values=None):
    """The symmetric adjacency matrix of ``n`` nodes and the undirected edges ``pairs``, of ``values`` (ones)."""
    pairs = np.asarray(pairs, dtype=np.int64).reshape(-1, 2)
    values = np.ones(len(pairs)) if values is None else np.asarray(values, dtype=float)
    rows, cols = np.concatenate([pairs[:, 0], pairs[:, 1]]), np.concatenate([pairs[:, 1], pairs[:, 0]])
    return scipy.sparse.csr_matrix((np.concatenate([values, values]), (rows, cols)), shape=(n, n))


def _path(nodes):
    """The edges of the path through ``nodes`` in their order."""
    return list(zip(nodes[:-1], nodes[1:], strict=True))


def test_a_path_is_cut_at_its_middle_level_from_its_far_end():
    """The path 0-1-...-5: from node 0 the far node is 5, whose levels are 5 - i; the sorted levels' entry 6 // 2 = 3
    is level 3, node 2, the separator, last; below it {3, 4, 5}, cut at node 4 (levels 2, 1, 0 from node 5, entry 1),
    then above it {0, 1}, cut at node 0 (levels 1, 0 from node 1, entry 1)."""
    assert nested_dissection(_graph(6, _path(range(6))), leaf=1).tolist() == [5, 3, 4, 1, 0, 2]


def test_the_far_node_is_the_last_reached_from_node_0():
    """The path 2-0-3-4-5-1: from node 0 the last node reached is 1 (from node 1 it would be 2); the levels from node
    1 are 4, 0, 5, 3, 2, 1, the separator is node 3 (level 3), below it {1, 4, 5} and above it {0, 2}."""
    order = nested_dissection(_graph(6, _path([2, 0, 3, 4, 5, 1])), leaf=3)
    assert order.tolist() == [1, 4, 5, 0, 2, 3]


def test_a_part_of_leaf_nodes_keeps_its_order():
    """The path 0-1-2-3 stays whole with leaf = 4; with leaf = 3 it is cut at node 1 (levels 3, 2, 1, 0 from node 3,
    entry 2)."""
    graph = _graph(4, _path(range(4)))
    assert nested_dissection(graph, leaf=4).tolist() == [0, 1, 2, 3]
    assert nested_dissection(graph, leaf=3).tolist() == [2, 3, 0, 1]


def test_components_are_ordered_one_after_the_other_each_dissected():
    """The paths 0-2-4 and 1-3-5: the component of node 0 first, each cut at its middle node (placed last)."""
    order = nested_dissection(_graph(6, _path([0, 2, 4]) + _path([1, 3, 5])), leaf=1)
    assert order.tolist() == [4, 0, 2, 5, 1, 3]


def test_the_separator_is_not_dissected():
    """Node 0 joined to the path 1-2-3, joined to node 4: from node 4 (the far node from 0) the level of 5 // 2 = 2
    sorted is 1, the path, which stays whole and last, though longer than the leaf."""
    graph = _graph(5, [(0, 1), (0, 2), (0, 3), (1, 4), (2, 4), (3, 4)] + _path([1, 2, 3]))
    assert nested_dissection(graph, leaf=1).tolist() == [4, 0, 1, 2, 3]


@settings(deadline=None)
@given(
    n=st.integers(1, 60),
    edges=st.lists(st.tuples(st.integers(0, 59), st.integers(0, 59), st.floats(0.01, 100.0)), max_size=200),
    leaf=st.integers(1, 8),
)
def test_only_the_pattern_counts(n, edges, leaf):
    """Levels count edges: any positive values, and a diagonal, give the order of the pattern's ones."""
    pairs = [(a % n, b % n) for a, b, _ in edges]
    weighted = _graph(n, pairs, [value for *_, value in edges]) + scipy.sparse.identity(n)
    pattern = _graph(n, [(a, b) for a, b in pairs if a != b])
    pattern.data[:] = 1.0
    assert np.array_equal(nested_dissection(weighted, leaf), nested_dissection(pattern, leaf))
