"""Hostile surfaces through the whole pipeline: each meshed within the pipeline's invariants or refused in one line."""

import numpy as np
import pytest
from conditions import exercised
from hypothesis import given, settings
from hypothesis import strategies as st
from invariants import check_edge_lengths
from surface_cases import STEEP_NET, vault
from surface_invariants import assert_valid_surface_mesh
from triangle_meshes import assert_on_input_surface, closed_tube, spherical_cap

import equimesh
from equimesh.surface.charts.bezier import BezierSurface
from equimesh.surface.optimize.jacobian import signed_areas

#: The condition of the fuzz test: the input is accepted.
MESHED = "a jittered net is meshed"
STEEP_MESHED = "a steep net is meshed"


@st.composite
def jittered_nets(draw):
    """Bicubic-to-quintic nets over a 40 x 40 square with every control point moved by up to 30% of a cell."""
    n = draw(st.integers(3, 5))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    net = np.zeros((n + 1, n + 1, 3))
    net[..., 0] = np.linspace(0, 40, n + 1)[:, None]
    net[..., 1] = np.linspace(0, 40, n + 1)[None, :]
    net += rng.uniform(-0.3, 0.3, size=net.shape) * 40.0 / n
    return BezierSurface(net)


@pytest.mark.exercised(MESHED, share=0.5)
@settings(max_examples=8, deadline=None)
@given(jittered_nets())
def test_jittered_nets_are_meshed_correctly_or_refused_cleanly(surface):
    try:
        mesh = equimesh.mesh_surface(surface, 6.0, grid=(8, 8), optimize="none")
    except equimesh.EquimeshError as exc:
        assert "\n" not in str(exc) and "edge (" not in str(exc)
        exercised(MESHED, False)
        return
    exercised(MESHED, True)
    assert_valid_surface_mesh(mesh, surface)
    check_edge_lengths(mesh.stages.plane, 6.0)


def _mesh_or_refusal(surface, l, **options):
    """A surface mesh, or None for a one-line refusal of ours that does not pass a library's message on."""
    try:
        return equimesh.mesh_surface(surface, l, **options)
    except equimesh.EquimeshError as exc:
        assert "\n" not in str(exc) and "Residuals" not in str(exc), str(exc)
        assert not isinstance(exc, equimesh.InternalError), str(exc)
        return None


@pytest.mark.parametrize(
    "surface",
    [closed_tube(1.0, 4.0), closed_tube(1.0, 17.0), closed_tube(1.0, 20.0), closed_tube(2.0, 12.0)]
    + [spherical_cap(3.0, degrees) for degrees in (60.0, 120.0, 170.0)],
    ids=["tube 1 x 4", "tube 1 x 17", "tube 1 x 20", "tube 2 x 12", "cap 60", "cap 120", "cap 170"],
)
def test_tubes_and_caps_flatten_and_are_meshed_or_refused_in_one_line(surface):
    """Closed-ended tubes and spherical caps: eq. (1) used not to start on some ("Residuals are not finite")."""
    mesh = _mesh_or_refusal(surface, 0.5, optimize="none", max_nodes=None)
    if mesh is not None:
        assert_on_input_surface(mesh, surface, 0.5)
        assert np.all(signed_areas(mesh.uv, mesh.triangles) > 0)
        check_edge_lengths(mesh.stages.plane, 0.5)


def test_a_surface_the_flattening_stretches_is_refused_on_its_flattened_area():
    """The size guard, again on the flattened outline: a tube estimated at 2,000 nodes flattens to 5 times its area."""
    with pytest.raises(equimesh.MeshTooLargeError, match=r"flattened surface \(area .*, .* times the surface's"):
        equimesh.mesh_surface(closed_tube(1.0, 16.0), 0.25, max_nodes=6000)


@pytest.mark.parametrize("weight", [1e8, 1e10, 1e12])
def test_weights_orders_of_magnitude_apart_are_refused_before_flattening(weight):
    """Eq. (1) cannot weigh auxiliary edges 2^26 times apart in length: refused naming both, not scipy's message."""
    with pytest.raises(
        equimesh.InvalidSurfaceError, match=r"^the auxiliary triangulation samples the surface too unevenly[^\n]*$"
    ):
        equimesh.mesh_surface(vault(weight), 2.0, optimize="none")


@pytest.mark.parametrize("u_range", [3e-300, 1e-10, 1e10, 1e300])
def test_parameter_ranges_outside_the_supported_widths_are_refused(u_range):
    with pytest.raises(equimesh.InvalidSurfaceError, match=r"^the parameter range of u, \[0, .*\], is .* wide"):
        equimesh.mesh_surface(vault(1.0, u_range), 2.0, optimize="none")


@pytest.mark.parametrize("u_range", [1e-6, 2.0**-19, 1e3, 1e6])
def test_a_chart_is_meshed_alike_on_every_supported_parameter_range(u_range):
    """As many nodes and triangles as on [0, 1], the same points up to rounding, at the ends of the supported range."""
    unit = equimesh.mesh_surface(vault(), 2.0, optimize="none")
    scaled = equimesh.mesh_surface(vault(1.0, u_range), 2.0, optimize="none")
    assert scaled.triangles.shape == unit.triangles.shape
    np.testing.assert_allclose(scaled.points, unit.points, rtol=0, atol=1e-6)


@pytest.mark.parametrize("l", [2.5, 1.5])
def test_a_flat_triangle_of_boundary_nodes_is_refused_where_the_boundary_bends(l):
    """Used to be an InternalError ("remapping inverted 2 of 320 triangles"): now refused naming the (u, v)."""
    with pytest.raises(equimesh.InvalidSurfaceError, match=r"^the flattened boundary bends so sharply near \(u, v\)"):
        equimesh.mesh_surface(BezierSurface(np.array(STEEP_NET)), l, optimize="none")


@st.composite
def steep_nets(draw):
    """Quartic nets over 22 x 32 with heights drawn in [-25, 25]: steep, random, many of them refused."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    net = np.zeros((5, 5, 3))
    net[..., 0] = np.linspace(0, 22, 5)[:, None] + rng.uniform(-1, 1, (5, 5))
    net[..., 1] = np.linspace(0, 32, 5)[None, :] + rng.uniform(-1, 1, (5, 5))
    net[..., 2] = rng.uniform(-25, 25, (5, 5))
    return BezierSurface(net)


@pytest.mark.exercised(STEEP_MESHED, share=0.1)
@settings(max_examples=6, deadline=None)
@given(steep_nets(), st.sampled_from([2.5, 3.0]))
def test_steep_random_nets_are_meshed_or_refused_in_one_line(surface, l):
    mesh = _mesh_or_refusal(surface, l, optimize="none")
    if exercised(STEEP_MESHED, mesh is not None):
        assert_valid_surface_mesh(mesh, surface)
