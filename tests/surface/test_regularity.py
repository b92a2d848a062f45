"""The regularity check of a surface (``surface/regularity.py``): a patch that folds, is singular or not finite is
refused in one line naming the place in (u, v); the example surfaces are regular, in any units.
"""

import json

import numpy as np
import pytest
from invariants import check_edge_lengths
from repository import SURFACES
from surface_cases import Line, Wrapped, folding_net, plane_patch, refuse

import equimesh
from equimesh._geometry import orient
from equimesh.errors import InvalidSurfaceError
from equimesh.surface.auxiliary import auxiliary_grid
from equimesh.surface.charts.bezier import BezierSurface
from equimesh.surface.regularity import check_regular


def test_folding_net_is_refused_where_it_folds():
    """A folding net (74 of 198 triangles reversed without the check) is refused near u = 0.31, where x_u = 0."""
    message = refuse(InvalidSurfaceError, folding_net(), 1.0, r"folds over near \(u, v\) = \(0\.3")
    assert "point (" in message and "overlap" in message


def test_collapsed_side_is_refused_as_singular():
    """A side collapsed to a point (a dome apex on the boundary): X_v vanishes there."""
    net = np.array(plane_patch().control_points)
    net[0, :, :] = 0.0  # side u = 0 is one point
    refuse(InvalidSurfaceError, BezierSurface(net), 3.0, r"singular at \(u, v\) = \(0, 0\).*X_v vanishes")


def test_parallel_derivatives_are_refused():
    refuse(InvalidSurfaceError, Line(), 3.0, "X_u and X_v are parallel")


def test_reference_surfaces_are_regular():
    """The surfaces of the experiments pass the regularity check on the paper's 15 x 15 grid."""
    for path in sorted(SURFACES.glob("*.json")):
        surface = BezierSurface(json.loads(path.read_text())["control_points"])
        assert check_regular(surface, auxiliary_grid(15, 15)) is None


def test_nan_on_the_grid_names_the_parameters():
    surface = Wrapped(plane_patch(), lambda u, v: u > 0.5)
    refuse(InvalidSurfaceError, surface, 3.0, r"not finite at \(u, v\) = \(0\.53")


@pytest.mark.parametrize("scale", [2.0**-400, 1e-100, 1e100, 2.0**450])
def test_surface_in_huge_or_tiny_units_is_meshed_like_in_units_of_one(scale):
    """The regularity check and the size estimate do not depend on the units.

    Before: in units of 1e-100 the saddle was refused as singular (X_u x X_v
    underflowed to 0), in units of 1e100 as folding or as needing more than
    1e308 nodes (the cross products overflowed).  A power-of-two scale gives
    the same mesh bit for bit, scaled; any other scale a valid mesh.
    """
    net = np.array(json.loads((SURFACES / "saddle.json").read_text())["control_points"])
    mesh = equimesh.mesh_surface(BezierSurface(net * scale), 10.0 * scale, optimize="none", placement="default")
    check_edge_lengths(mesh.stages.plane, 10.0 * scale)
    uv = mesh.uv[mesh.triangles]
    assert np.all(orient(uv[:, 0], uv[:, 1], uv[:, 2]) > 0)
    if np.log2(scale).is_integer():
        base = equimesh.mesh_surface(BezierSurface(net), 10.0, optimize="none", placement="default")
        np.testing.assert_array_equal(mesh.triangles, base.triangles)
        np.testing.assert_array_equal(mesh.points, base.points * scale)
