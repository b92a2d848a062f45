"""The variables of the final optimisation: which parameters of which nodes move, and how far they may.

A free node's two parameters are variables, kept in the chart's domain by
bounds (:func:`parameter_box`); a node sliding along a closed polyline in
(u, v) has one variable, its arc position (:mod:`~equimesh.surface.optimize.slide`),
its Jacobian column the chain rule through ``d uv / d s``.
"""

from dataclasses import dataclass

import numpy as np
import scipy.optimize
import scipy.sparse

from ..charts.chart import domain_of
from ..regularity import derivatives


@dataclass(frozen=True)
class UVProblem:
    """The data every objective builder sees.

    Attributes
    ----------
    surface : Chart
    uv : (N, 2) float array
        Start parameters of all nodes (after remapping, step 4).
    edges : (E, 2) int array
    edge_groups : (E,) int array
        :data:`~equimesh.mesh.G1` or :data:`~equimesh.mesh.OTHER` per edge.
    length : float
        The target length l.
    free : (N,) bool array
        True for the nodes whose two parameters are variables.
    slides : tuple of :class:`~equimesh.surface.optimize.slide.Slide`
        Nodes that slide along a closed polyline by their arc position (their
        ``free`` entries False): one variable each, after the free parameters.
    """

    surface: object
    uv: np.ndarray
    edges: np.ndarray
    edge_groups: np.ndarray
    length: float
    free: np.ndarray
    slides: tuple = ()

    @property
    def variables(self):
        """(2N,) bool mask of the entries of ``uv.ravel()`` that are variables themselves."""
        return np.repeat(np.asarray(self.free, dtype=bool), 2)

    @property
    def moving(self):
        """(2N,) bool mask of the entries of ``uv.ravel()`` that depend on the variables (the Jacobians' columns)."""
        moving = self.variables.copy()
        for slide in self.slides:
            moving[2 * slide.nodes] = moving[2 * slide.nodes + 1] = True
        return moving

    @property
    def sliding_variables(self):
        """Bool mask of the variables that move boundary nodes: the arc positions."""
        n = int(np.count_nonzero(self.free))
        return np.concatenate(
            [np.zeros(2 * n, dtype=bool), *(np.ones(len(slide.nodes), dtype=bool) for slide in self.slides)]
        )

    @property
    def x0(self):
        """The start as a variable vector: ``(u_0, v_0, u_1, v_1, ...)`` over free nodes, then the arc positions."""
        return np.concatenate([self.uv.ravel()[self.variables], *(slide.s for slide in self.slides)])

    def uv_of(self, x):
        """All nodes' (u, v) with the free ones taken from the variable vector ``x``."""
        variables = self.variables
        full = self.uv.ravel().copy()
        n = int(variables.sum())
        full[variables] = x[:n]
        full = full.reshape(-1, 2)
        for slide in self.slides:
            full[slide.nodes] = slide.uv(x[n : n + len(slide.nodes)])
            n += len(slide.nodes)
        return full

    def chain(self, jacobian, x):
        """``jacobian`` over the :attr:`moving` entries as one over the variables ``x`` (chain rule), on its structure.

        A free node's two columns are its two variables'; a sliding node's
        column pair ``(d/du, d/dv)`` becomes its one column, the two entries
        scaled by the loop's direction ``d uv / d s`` at its ``s`` and kept
        side by side in the row, to be summed (as every product with the
        matrix sums them).  So the result has the Jacobian's structure
        whatever the values: the product with the matrix ``d uv / d x``
        dropped the sums that came out exactly zero, a new structure whenever
        a barrier triangle woke or slept, and the normal equations were
        analysed anew at nearly every iteration
        (docs/decisions.md, "One pattern for the normal matrix, three factorisations").
        """
        if not self.slides:
            return jacobian
        moving, variables = self.moving, self.variables
        n = int(variables.sum())
        entry = np.cumsum(moving) - 1  # column of each moving entry in ``jacobian``
        column, factor = np.empty(int(moving.sum()), dtype=np.int64), np.ones(int(moving.sum()))
        column[entry[variables]] = np.arange(n)
        for slide in self.slides:
            k = len(slide.nodes)
            direction = slide.direction(x[n : n + k])
            for axis in (0, 1):
                column[entry[2 * slide.nodes + axis]] = np.arange(n, n + k)
                factor[entry[2 * slide.nodes + axis]] = direction[:, axis]
            n += k
        jacobian = jacobian.tocsr()
        return scipy.sparse.csr_matrix(
            (jacobian.data * factor[jacobian.indices], column[jacobian.indices], jacobian.indptr),
            shape=(jacobian.shape[0], n),
        )

    def step_limit(self, radius):
        """A trust region per node: ``direction -> step`` with every node's move on the surface at most ``radius``.

        A node's move is taken to first order at its start (the tangent
        lengths ``|X_u|``, ``|X_v|`` at :attr:`uv` times its steps in u and v,
        or ``max(|X_u|, |X_v|)`` times its step along its loop, which is in
        (u, v) arc length), and the steps of a node that would move further
        are scaled down together (its direction in (u, v) is kept).
        """
        su, sv = derivatives(self.surface, self.uv)
        tangent = np.column_stack([np.linalg.norm(su, axis=1), np.linalg.norm(sv, axis=1)])
        variables = self.variables
        node = np.concatenate([np.repeat(np.arange(len(self.uv)), 2)[variables], *(s.nodes for s in self.slides)])
        scale = np.concatenate([tangent.ravel()[variables], *(tangent[s.nodes].max(axis=1) for s in self.slides)])

        def limit(direction):
            move = np.sqrt(np.bincount(node, (scale * direction) ** 2, len(self.uv)))
            factor = np.ones_like(move)
            far = move > radius
            factor[far] = radius / move[far]
            return direction * factor[node]

        return limit

    @property
    def bounds(self):
        """``(lower, upper)`` of the variables: the parameter domain, and each sliding node's range of arc positions."""
        lower, upper = parameter_box(self.surface)
        variables = self.variables
        return (
            np.concatenate([np.tile(lower, len(self.uv))[variables], *(slide.lower for slide in self.slides)]),
            np.concatenate([np.tile(upper, len(self.uv))[variables], *(slide.upper for slide in self.slides)]),
        )


def parameter_box(surface):
    """The chart's parameter domain as ``(lower, upper)``, each ``(u, v)``
    (:func:`~equimesh.surface.charts.chart.domain_of`)."""
    domain = domain_of(surface)
    return np.asarray(domain.lower, dtype=float), np.asarray(domain.upper, dtype=float)


def free_nodes(n, fixed, slides):
    """(n,) mask of the nodes whose two parameters are variables: all but the ``fixed`` ones and the sliding ones."""
    free = np.ones(n, dtype=bool)
    fixed = np.asarray(fixed)
    free[np.flatnonzero(fixed) if fixed.dtype == bool else fixed.astype(np.int64)] = False
    for slide in slides:
        free[slide.nodes] = False
    return free
