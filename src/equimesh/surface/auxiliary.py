"""The auxiliary triangulation of the parameter square (Section 4, step 1).

"Divide the parameter plane (u, v) into a n_u x n_v grid, and further divide
each rectangular unit to two right triangles."  The nodes are u_i^0, the
triangles and edges are reused unchanged on the surface (step 2) and on the
plane (steps 2-4).
"""

from dataclasses import dataclass

import numpy as np

from ..errors import EquimeshError
from ..mesh import unique_edges

#: Column order of :attr:`AuxiliaryGrid.boundary_sides`.
SIDES = ("u=0", "u=1", "v=0", "v=1")


@dataclass(frozen=True)
class AuxiliaryGrid:
    """An ``n_u x n_v`` grid on [0, 1]^2, each cell cut into two right triangles.

    Node numbering: node ``k = i * (n_v + 1) + j`` sits at
    ``(u, v) = (i / n_u, j / n_v)``, ``0 <= i <= n_u``, ``0 <= j <= n_v``.

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
        The nodes u_i^0; coordinates on the border are exactly 0.0 or 1.0.
    triangles : (2 n_u n_v, 3) int array
        Counter-clockwise in (u, v).
    edges : (E, 2) int array
        Unique, each row sorted, rows sorted;
        ``E = n_u (n_v+1) + n_v (n_u+1) + n_u n_v``.
    boundary : (2 (n_u + n_v),) int array
        The boundary node loop, counter-clockwise in (u, v), starting at
        ``(0, 0)``: along ``v=0`` to ``(1, 0)``, along ``u=1`` to ``(1, 1)``,
        along ``v=1`` back to ``(0, 1)``, along ``u=0`` down to the start.
    boundary_sides : (2 (n_u + n_v), 4) bool array
        For each node of :attr:`boundary`, the sides it lies on, columns in
        the order of :data:`SIDES` (``u=0, u=1, v=0, v=1``).
    """

    n_u: int
    n_v: int
    uv: np.ndarray
    triangles: np.ndarray
    edges: np.ndarray
    boundary: np.ndarray
    boundary_sides: np.ndarray

    @property
    def n_nodes(self):
        return len(self.uv)

    @property
    def boundary_corner(self):
        """(B,) bool: the boundary node is a corner of [0, 1]^2 (on two sides)."""
        return self.boundary_sides.sum(axis=1) == 2

    @property
    def boundary_segments(self):
        """(B, 2) int array: the boundary edges ``(boundary[k], boundary[k+1])`` in loop order."""
        return np.column_stack([self.boundary, np.roll(self.boundary, -1)])

    @property
    def boundary_segment_side(self):
        """(B,) int: index into :data:`SIDES` of the side carrying each boundary segment."""
        both = self.boundary_sides & np.roll(self.boundary_sides, -1, axis=0)
        return np.argmax(both, axis=1)

    def node(self, i, j):
        """Index of the node at ``(i / n_u, j / n_v)``."""
        return i * (self.n_v + 1) + j


def auxiliary_grid(n_u, n_v):
    """Build the auxiliary triangulation of step 1 (see :class:`AuxiliaryGrid`).

    Parameters
    ----------
    n_u, n_v : int
        Number of grid cells along ``u`` and ``v``, each at least 1.
    """
    n_u, n_v = _check_count("n_u", n_u), _check_count("n_v", n_v)
    i, j = np.meshgrid(np.arange(n_u + 1), np.arange(n_v + 1), indexing="ij")
    uv = np.column_stack([i.ravel() / n_u, j.ravel() / n_v])

    node = np.arange((n_u + 1) * (n_v + 1)).reshape(n_u + 1, n_v + 1)
    a = node[:-1, :-1].ravel()  # (i, j)
    b = node[1:, :-1].ravel()  # (i+1, j)
    c = node[1:, 1:].ravel()  # (i+1, j+1)
    d = node[:-1, 1:].ravel()  # (i, j+1)
    triangles = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])

    boundary = np.concatenate(
        [
            node[:-1, 0],  # v = 0, u increasing, (0,0) .. (1-1/n_u, 0)
            node[-1, :-1],  # u = 1, v increasing
            node[:0:-1, -1],  # v = 1, u decreasing
            node[0, :0:-1],  # u = 0, v decreasing
        ]
    )
    buv = uv[boundary]
    sides = np.column_stack([buv[:, 0] == 0.0, buv[:, 0] == 1.0, buv[:, 1] == 0.0, buv[:, 1] == 1.0])
    return AuxiliaryGrid(n_u, n_v, uv, triangles, unique_edges(triangles), boundary, sides)


def _check_count(name, value):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
        shown = value.item() if isinstance(value, np.generic) else value
        raise EquimeshError(f"auxiliary grid size {name} must be a positive integer, got {shown!r}")
    return int(value)
