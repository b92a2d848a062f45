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
