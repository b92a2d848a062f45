"""Tiny final-optimisation problems for direct tests of ``surface/optimize`` (a few nodes, known by hand).

By default a 4 x 4 grid of nodes on the parameter square [0, 1]^2 of a small doubly curved Bezier patch (30 x 30, rise
``rise``), each cell split into two triangles: 16 nodes, the 12 of the rim first in counter-clockwise order,
the 4 inner ones free; 24 grid edges (G1) and 9 diagonals (OTHER).  On the flat patch (``rise=0``) a grid edge
is 10 long and a diagonal 10 sqrt(2).
"""

from dataclasses import replace

import numpy as np

from equimesh.mesh import G1, OTHER
from equimesh.surface.charts.bezier import BezierSurface
from equimesh.surface.optimize import UVProblem
from equimesh.surface.optimize.slide import along_polygon

#: The nodes of the default grid's rim (the first ones).
RIM = 12


def _order(n):
    """The grid points (i, j) of an n x n grid: the rim counter-clockwise from (0, 0), then the inner ones."""
    m = n - 1
    rim = [(i, 0) for i in range(m)] + [(m, j) for j in range(m)] + [(i, m) for i in range(m, 0, -1)]
    rim += [(0, j) for j in range(m, 0, -1)]
    return rim + [(i, j) for j in range(1, m) for i in range(1, m)]


def patch(rise=6.0, size=30.0):
    """A biquadratic Bezier patch over a ``size x size`` square, its middle control point ``rise`` high."""
    i, j = np.meshgrid(np.arange(3) / 2, np.arange(3) / 2, indexing="ij")
    z = np.zeros((3, 3))
    z[1, 1] = rise
    return BezierSurface(np.stack([size * i, size * j, z], axis=-1))


def grid(n=4):
    """``(uv, triangles, edges, edge_groups)`` of the n x n grid (counter-clockwise triangles), grid (i, j) at uv
    (i, j) / (n - 1): the 4 (n - 1) nodes of the rim first, counter-clockwise from (0, 0)."""
    order = _order(n)
    index = {ij: k for k, ij in enumerate(order)}
    uv = np.array(order, dtype=float) / (n - 1)
    triangles, edges, groups = [], [], []
    for i in range(n - 1):
        for j in range(n - 1):
            a, b, c, d = index[i, j], index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]
            triangles += [[a, b, c], [a, c, d]]
            edges.append([a, c])
            groups.append(OTHER)
    for i in range(n):
        for j in range(n):
            for di, dj in ((1, 0), (0, 1)):
                if i + di < n and j + dj < n:
                    edges.append([index[i, j], index[i + di, j + dj]])
                    groups.append(G1)
    return uv, np.array(triangles), np.array(edges), np.array(groups)


def problem(rise=6.0, length=8.0, seed=None, spread=0.02, slides=False, surface_tolerance=0.0, n=4):
    """The n x n grid's :class:`UVProblem` on :func:`patch`: the inner nodes free (moved by ``spread`` normal draws
    of ``seed``, if given), the rim fixed or (``slides``) sliding along the square between its corners."""
    uv, triangles, edges, groups = grid(n)
    rim = 4 * (n - 1)
    if seed is not None:
        uv[rim:] += spread * np.random.default_rng(seed).standard_normal(uv[rim:].shape)
    free = np.zeros(len(uv), dtype=bool)
    free[rim:] = True
    p = UVProblem(patch(rise), uv, edges, groups, float(length), free, surface_tolerance=surface_tolerance)
    if slides:
        square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
        slide, _ = along_polygon(np.arange(rim), square, uv[:rim])
        p = replace(p, slides=(slide,))
    return p, triangles


def moved(p, seed, size=0.01, offset=0.0):
    """``p.x0`` moved by ``size`` normal draws of ``seed``, its offsets (if any) drawn in ``[-offset, offset]``."""
    rng = np.random.default_rng(seed)
    x = p.x0 + size * rng.standard_normal(len(p.x0))
    k = len(p.offset_nodes)
    if k:
        x[len(x) - k :] = offset * rng.uniform(-1.0, 1.0, k)
    return x


def finite_difference(fun, x, h=1e-7):
    """The central-difference Jacobian of ``fun`` at ``x``, (len(fun(x)), len(x))."""
    columns = []
    for k in range(len(x)):
        d = np.zeros_like(x)
        d[k] = h
        columns.append((np.asarray(fun(x + d)) - np.asarray(fun(x - d))).ravel() / (2 * h))
    return np.column_stack(columns)
