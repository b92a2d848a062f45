"""Tiny final-optimisation problems for direct tests of ``surface/optimize`` (a few nodes, known by hand).

A 4 x 4 grid of nodes on the parameter square [0, 1]^2 of a small doubly curved Bezier patch (30 x 30, rise
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

#: The rim of the 4 x 4 grid, counter-clockwise from (0, 0), then the inner nodes: grid (i, j) at uv (i, j) / 3.
_ORDER = [(0, 0), (1, 0), (2, 0), (3, 0), (3, 1), (3, 2), (3, 3), (2, 3), (1, 3), (0, 3), (0, 2), (0, 1)]
_ORDER += [(1, 1), (2, 1), (1, 2), (2, 2)]
RIM = 12


def patch(rise=6.0, size=30.0):
    """A biquadratic Bezier patch over a ``size x size`` square, its middle control point ``rise`` high."""
    i, j = np.meshgrid(np.arange(3) / 2, np.arange(3) / 2, indexing="ij")
    z = np.zeros((3, 3))
    z[1, 1] = rise
    return BezierSurface(np.stack([size * i, size * j, z], axis=-1))


def grid():
    """``(uv, triangles, edges, edge_groups)`` of the 4 x 4 grid (counter-clockwise triangles)."""
    index = {ij: k for k, ij in enumerate(_ORDER)}
    uv = np.array(_ORDER, dtype=float) / 3.0
    triangles, edges, groups = [], [], []
    for i in range(3):
        for j in range(3):
            a, b, c, d = index[i, j], index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]
            triangles += [[a, b, c], [a, c, d]]
            edges.append([a, c])
            groups.append(OTHER)
    for i in range(4):
        for j in range(4):
            for di, dj in ((1, 0), (0, 1)):
                if i + di < 4 and j + dj < 4:
                    edges.append([index[i, j], index[i + di, j + dj]])
                    groups.append(G1)
    return uv, np.array(triangles), np.array(edges), np.array(groups)


def problem(rise=6.0, length=8.0, seed=None, spread=0.02, slides=False, surface_tolerance=0.0):
    """The grid's :class:`UVProblem` on :func:`patch`: the inner nodes free (moved by ``spread`` normal draws of
    ``seed``, if given), the rim fixed or (``slides``) sliding along the square between its corners."""
    uv, triangles, edges, groups = grid()
    if seed is not None:
        uv[RIM:] += spread * np.random.default_rng(seed).standard_normal(uv[RIM:].shape)
    free = np.zeros(len(uv), dtype=bool)
    free[RIM:] = True
    p = UVProblem(patch(rise), uv, edges, groups, float(length), free, surface_tolerance=surface_tolerance)
    if slides:
        square = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
        slide, _ = along_polygon(np.arange(RIM), square, uv[:RIM])
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
