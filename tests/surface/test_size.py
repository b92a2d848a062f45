"""The size guard of mesh_surface (``surface/size.py``): the estimate before the flattening and again after it."""

from types import SimpleNamespace

import numpy as np
import pytest

from equimesh.errors import MeshTooLargeError
from equimesh.surface.size import check_plane_size, check_surface_size

#: A unit square in space, two triangles (area 1).
SQUARE = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]])
TRIANGLES = np.array([[0, 1, 2], [0, 2, 3]])


def outline(side, hole=None):
    ring = [[0.0, 0.0], [side, 0.0], [side, side], [0.0, side]]
    return SimpleNamespace(vertices=ring, holes=[SimpleNamespace(points=hole)] if hole is not None else [])


def test_a_chart_whose_outline_is_stretched_is_refused_saying_how_much():
    """At l = 0.1 the square needs about 116 nodes; its outline flattened to 4 x 4 (16 times the area) about 1,850."""
    check_surface_size(SQUARE, TRIANGLES, 0.1, 200)
    check_plane_size(SQUARE, TRIANGLES, outline(1.0), 0.1, 200)
    with pytest.raises(MeshTooLargeError, match=r"flattened surface \(area 16, 16 times the surface's 1: eq\. \(1\)"):
        check_plane_size(SQUARE, TRIANGLES, outline(4.0), 0.1, 200)
    check_plane_size(SQUARE, TRIANGLES, outline(4.0), 0.1, None)  # no limit


def test_the_openings_of_an_outline_are_not_counted():
    hole = [[0.5, 0.5], [3.5, 0.5], [3.5, 3.5], [0.5, 3.5]]  # leaves 16 - 9 = 7
    with pytest.raises(MeshTooLargeError, match=r"area 7, 7 times"):
        check_plane_size(SQUARE, TRIANGLES, outline(4.0, hole), 0.1, 200)


def test_a_mesh_whose_flattened_triangles_are_stretched_is_refused():
    flattened = SQUARE[:, :2] * 4.0
    check_surface_size(SQUARE, TRIANGLES, 0.1, 200, flattened=SQUARE[:, :2])
    with pytest.raises(MeshTooLargeError, match=r"flattened surface \(area 16, 16 times the surface's 1"):
        check_surface_size(SQUARE, TRIANGLES, 0.1, 200, flattened=flattened)
