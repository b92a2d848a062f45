"""Triangle meshes of roofs, for the triangle-mesh input of Section 4 (tests, examples, benchmarks)."""

import numpy as np


def roof_mesh(width, depth, cells, rise, opening=None):
    """A vault ``z = rise sin(pi x / width) sin(pi y / depth)`` over ``[0, width] x [0, depth]``, triangulated on a grid.

    Parameters
    ----------
    width, depth : float
    cells : (int, int)
        Grid cells along x and y; each cell is cut into two triangles.
    rise : float
        Height of the crown (0: a flat rectangle).
    opening : (i0, i1, j0, j1), optional
        The cells ``i0 <= i < i1``, ``j0 <= j < j1`` are left out (an opening;
        keep it one cell away from the border).

    Returns
    -------
    vertices : (N, 3) float array, triangles : (M, 3) int array
        Counter-clockwise seen from above; vertices no triangle uses are kept
        (the reader drops them).
    """
    nx, ny = cells
    x, y = np.meshgrid(np.linspace(0.0, width, nx + 1), np.linspace(0.0, depth, ny + 1), indexing="ij")
    z = rise * np.sin(np.pi * x / width) * np.sin(np.pi * y / depth)
    vertices = np.column_stack([x.ravel(), y.ravel(), z.ravel()])
    node = np.arange((nx + 1) * (ny + 1)).reshape(nx + 1, ny + 1)
    keep = np.ones((nx, ny), dtype=bool)
    if opening is not None:
        i0, i1, j0, j1 = opening
        keep[i0:i1, j0:j1] = False
    a, b, c, d = (n[keep] for n in (node[:-1, :-1], node[1:, :-1], node[1:, 1:], node[:-1, 1:]))
    triangles = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    return vertices, triangles
