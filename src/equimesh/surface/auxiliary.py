"""The auxiliary triangulation of a chart's parameter rectangle (Section 4, step 1).

"Divide the parameter plane (u, v) into a n_u x n_v grid, and further divide
each rectangular unit to two right triangles."  The paper's parameter plane is
[0, 1]^2; here it is the chart's :class:`~equimesh.surface.charts.chart.Domain`
``[u0, u1] x [v0, v1]`` (default [0, 1]^2).  The nodes are u_i^0, the
triangles and edges are reused unchanged on the surface (step 2) and on the
plane (steps 2-4).
"""

from dataclasses import dataclass

import numpy as np

from .._checks import check_count
from ..mesh import unique_edges
from .charts.chart import UNIT, Domain


@dataclass(frozen=True)
class AuxiliaryGrid:
    """An ``n_u x n_v`` grid on a domain ``[u0, u1] x [v0, v1]``, each cell cut into two right triangles.

    Node numbering: node ``k = i * (n_v + 1) + j`` sits at the fractions
    ``(i / n_u, j / n_v)`` of the domain (:meth:`Domain.at_fractions`; on
    [0, 1]^2 exactly ``(i / n_u, j / n_v)``), ``0 <= i <= n_u``, ``0 <= j <= n_v``.

    Diagonal: the cell ``[u_i, u_{i+1}] x [v_j, v_{j+1}]`` is cut along the
    diagonal from ``(u_i, v_j)`` to ``(u_{i+1}, v_{j+1})`` into the triangles
    ``(i, j) (i+1, j) (i+1, j+1)`` and ``(i, j) (i+1, j+1) (i, j+1)``; both are
    counter-clockwise with ``u`` as the first and ``v`` as the second axis and
    have their right angle at ``(i+1, j)`` and ``(i, j+1)`` respectively.

    Attributes
    ----------
    n_u, n_v : int
        Number of cells along ``u`` and ``v``.
    uv : ((n_u+1)(n_v+1), 2) float array
        The nodes u_i^0; coordinates on the border are exactly the domain's
        bounds (0.0 or 1.0 on [0, 1]^2).
    triangles : (2 n_u n_v, 3) int array
        Counter-clockwise in (u, v).
    edges : (E, 2) int array
        Unique, each row sorted, rows sorted;
        ``E = n_u (n_v+1) + n_v (n_u+1) + n_u n_v``.
    boundary : (2 (n_u + n_v),) int array
        The boundary node loop, counter-clockwise in (u, v), starting at
        ``(u0, v0)``: along ``v=v0`` to ``(u1, v0)``, along ``u=u1`` to
        ``(u1, v1)``, along ``v=v1`` back to ``(u0, v1)``, along ``u=u0`` down
        to the start.
    boundary_sides : (2 (n_u + n_v), 4) bool array
        For each node of :attr:`boundary`, the sides it lies on, columns in
        the order of :data:`~equimesh.surface.charts.chart.SIDES` (``u=u0, u=u1, v=v0, v=v1``).
    domain : Domain
        The parameter rectangle.
    """

    n_u: int
    n_v: int
    uv: np.ndarray
    triangles: np.ndarray
    edges: np.ndarray
    boundary: np.ndarray
    boundary_sides: np.ndarray
    domain: Domain = UNIT

    @property
    def n_nodes(self):
        return len(self.uv)

    @property
    def boundary_corner(self):
        """(B,) bool: the boundary node is a corner of the domain (on two sides)."""
        return self.boundary_sides.sum(axis=1) == 2

    @property
    def boundary_segments(self):
        """(B, 2) int array: the boundary edges ``(boundary[k], boundary[k+1])`` in loop order."""
        return np.column_stack([self.boundary, np.roll(self.boundary, -1)])

    @property
    def boundary_segment_side(self):
        """(B,) int: index into :data:`~equimesh.surface.charts.chart.SIDES` of the side carrying each boundary
        segment."""
        both = self.boundary_sides & np.roll(self.boundary_sides, -1, axis=0)
        return np.argmax(both, axis=1)

    def node(self, i, j):
        """Index of the node at the fractions ``(i / n_u, j / n_v)`` of the domain."""
        return i * (self.n_v + 1) + j


def auxiliary_grid(n_u, n_v, domain=UNIT):
    """Build the auxiliary triangulation of step 1 (see :class:`AuxiliaryGrid`).

    Parameters
    ----------
    n_u, n_v : int
        Number of grid cells along ``u`` and ``v``, each at least 1.
    domain : Domain
        The chart's parameter rectangle (:func:`~equimesh.surface.charts.chart.domain_of`).
    """
    n_u, n_v = check_grid_size(n_u, n_v)
    i, j = np.meshgrid(np.arange(n_u + 1), np.arange(n_v + 1), indexing="ij")
    uv = domain.at_fractions(i.ravel() / n_u, j.ravel() / n_v)

    node = np.arange((n_u + 1) * (n_v + 1)).reshape(n_u + 1, n_v + 1)
    a = node[:-1, :-1].ravel()  # (i, j)
    b = node[1:, :-1].ravel()  # (i+1, j)
    c = node[1:, 1:].ravel()  # (i+1, j+1)
    d = node[:-1, 1:].ravel()  # (i, j+1)
    triangles = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])

    boundary = np.concatenate(
        [
            node[:-1, 0],  # v = v0, u increasing
            node[-1, :-1],  # u = u1, v increasing
            node[:0:-1, -1],  # v = v1, u decreasing
            node[0, :0:-1],  # u = u0, v decreasing
        ]
    )
    buv = uv[boundary]
    sides = buv[:, np.arange(4) // 2] == domain.side_values  # columns in the order of SIDES
    return AuxiliaryGrid(n_u, n_v, uv, triangles, unique_edges(triangles), boundary, sides, domain)


def check_grid_size(n_u, n_v):
    """``(n_u, n_v)`` as ints, each a positive integer (the cell counts of step 1)."""
    return tuple(check_count(n, f"auxiliary grid size {name}") for name, n in (("n_u", n_u), ("n_v", n_v)))
