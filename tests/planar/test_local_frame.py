"""Problems 1 and 2 run in the polygon's local frame (``planar/polygon.py``): far from the origin or in huge or tiny
units the mesh is the one at the origin in units of l, and what the frame cannot hold is refused in one line.
"""

import numpy as np
import pytest
from invariants import check_edge_lengths

import equimesh
from equimesh import InvalidPolygonError

SQUARE10 = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


@pytest.mark.parametrize("shift", [1e7, 1e9, 1e10, (872696995.0, 727022114.0)])
def test_problem1_far_from_the_origin_is_the_same_local_mesh(shift):
    """Validation and meshing run relative to the polygon: a translated square gives the same local mesh."""
    base = equimesh.increment(SQUARE10, 1.0)
    far = equimesh.increment(SQUARE10 + shift, 1.0)
    assert np.array_equal(far.local_points, base.local_points)
    assert np.array_equal(far.edge_lengths(), base.edge_lengths())
    assert np.allclose(far.points, base.points + shift, rtol=0, atol=4 * np.spacing(np.max(np.abs(far.points))))


@pytest.mark.parametrize("shift", [1e7, 1e9, (872696995.0, 727022114.0)])
def test_problem2_far_from_the_origin_keeps_theorem3_and_exact_g1(shift):
    """Theorem 3 and G1 edges of length l (to 1e-12) hold at +1e9 as at the origin; polygon vertices are exact."""
    vertices = SQUARE10 + shift
    mesh = equimesh.uniform_triangulation(vertices, 1.0)
    check_edge_lengths(mesh, 1.0)
    g1 = mesh.edge_lengths()[mesh.g1_mask]
    assert g1.size and np.max(np.abs(g1 - 1.0)) <= 1e-12
    assert all(any(np.array_equal(v, p) for p in mesh.points[: mesh.n_boundary]) for v in vertices)


@pytest.mark.parametrize("factor", [1e80, 1e-90, 2.0**-300, 1e140])
def test_scaled_coordinates_with_scaled_l_are_meshed(factor, capfd):
    """Coordinates scaled by 1e80 or 1e-90 (with l scaled alike) run in the local frame: valid, silent."""
    for verb in (equimesh.increment, equimesh.uniform_triangulation):
        check_edge_lengths(verb(SQUARE10 * factor, factor), factor)
    assert capfd.readouterr().out == ""


@pytest.mark.parametrize("factor", [1e80, 1e-90, 1e300])
def test_scaled_coordinates_with_l_unscaled_are_refused(factor, capfd):
    """Scaled coordinates with l = 1: too wide (precision range) or too short, a clear error, nothing printed."""
    with pytest.raises(InvalidPolygonError, match=r"spans .* l, more than|shorter than l"):
        equimesh.uniform_triangulation(SQUARE10 * factor, 1.0)
    assert capfd.readouterr().out == ""
