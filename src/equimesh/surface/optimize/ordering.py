"""A fill-reducing order of the normal matrix for SuperLU: nested dissection by level structures.

George, "Nested dissection of a regular finite element mesh" (SIAM J. Numer.
Anal. 10, 1973), found automatically as in George and Liu, *Computer
Solution of Large Sparse Positive Definite Systems* (1981), chapter 8: a
connected part of the matrix's graph is split by a level set of a
breadth-first search from a far node (a pseudo-peripheral node: the last
one reached from the part's first node), the level at which half of the
part's nodes are reached; every path between the nodes below and above that
level crosses it, so it is a separator.  The two sides are ordered first, each
the same way, then the separator; a part of at most :data:`LEAF` nodes keeps
its order.  On the optimisation's meshes the separators are about the square
root of a part's size, as for a plane grid.

SuperLU's own minimum-degree order (``MMD_AT_PLUS_A``) fills the factors
about as little, but in long thin columns: the dissected order's separators
are dense blocks (supernodes), which its factorisation runs faster on
(docs/decisions.md, "SuperLU in a nested-dissection order"), from
:data:`DISSECT_FROM` variables on.  Deterministic: breadth-first
searches and stable sorts only.
"""

import numpy as np
import scipy.sparse
import scipy.sparse.csgraph

#: A part of the graph with at most this many nodes is not dissected further (measured on the reference dome's
#: normal matrices at 22,382 and 73,234 variables: 16 to 64 factorised about as fast, 256 a fifth slower).
LEAF = 64
#: SuperLU's factorisations take this order from this many variables on, its minimum-degree order below
#: (``"bounded"`` with SuperLU, CPU seconds per Jacobian against the minimum-degree order: 1.10 times as long on
#: experiments/surfaces/nurbs_roof.json at l = 1.5, about 2,500 variables; the same on the reference dome at l = 1.66,
#: about 6,500; 0.78 times at l = 0.9, 22,382; 0.62 times at l = 0.5, 73,234).
DISSECT_FROM = 8_000


def nested_dissection(graph, leaf=LEAF):
    """The nodes of ``graph`` (a symmetric sparse adjacency matrix, diagonal ignored) in nested-dissection order.

    Returns
    -------
    order : (n,) int64 array
        A permutation of ``range(n)``: ``order[k]`` is the k-th node eliminated.
    """
    graph = scipy.sparse.csr_matrix(graph)
    parts, stack = [], [(np.arange(graph.shape[0]), False)]
    while stack:  # depth first, the part below a separator before the part above it, then the separator
        nodes, final = stack.pop()
        if final or len(nodes) <= leaf:
            parts.append(nodes)
            continue
        sub = graph[nodes][:, nodes]
        count, label = scipy.sparse.csgraph.connected_components(sub, directed=False)
        if count > 1:
            stack.extend((nodes[label == c], False) for c in reversed(range(count)))
            continue
        far = int(np.argmax(_levels(sub, 0)))
        level = _levels(sub, far)
        middle = np.sort(level, kind="stable")[len(nodes) // 2]
        stack.extend([(nodes[level == middle], True), (nodes[level > middle], False), (nodes[level < middle], False)])
    return np.concatenate(parts).astype(np.int64)


def _levels(graph, start):
    """The breadth-first level (distance in edges) of every node of the connected ``graph`` from node ``start``."""
    return scipy.sparse.csgraph.shortest_path(graph, unweighted=True, indices=[start])[0]
