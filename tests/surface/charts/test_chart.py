"""Charts (Section 4, step 1): any parameter rectangle, sides labelled; nothing assumes [0, 1]^2."""

import numpy as np
import pytest
from surface_invariants import assert_valid_surface_mesh

import equimesh
from equimesh import InvalidSurfaceError
from equimesh.surface.auxiliary import auxiliary_grid
from equimesh.surface.charts.bezier import BezierSurface
from equimesh.surface.charts.chart import SIDES, UNIT, Chart, Domain, domain_of

SHIFTED = Domain((2.0, 5.0), (-1.0, 3.0))


def dome(size=30.0, rise=6.0):
    """A doubly curved biquadratic patch over size x size."""
    net = np.zeros((3, 3, 3))
    net[..., 0] = np.linspace(0.0, size, 3)[:, None]
    net[..., 1] = np.linspace(0.0, size, 3)[None, :]
    net[1, 1, 2] = 2 * rise
    return BezierSurface(net)


class Reparametrised:
    """``base`` on [0, 1]^2 read on the rectangle ``domain`` through the affine map onto [0, 1]^2."""

    def __init__(self, base, domain):
        self.base, self.domain = base, domain
        self._width = domain.upper - domain.lower

    def _unit(self, u, v):
        return (np.asarray(u) - self.domain.u[0]) / self._width[0], (np.asarray(v) - self.domain.v[0]) / self._width[1]

    def evaluate(self, u, v):
        return self.base.evaluate(*self._unit(u, v))

    def derivatives(self, u, v):
        su, sv = self.base.derivatives(*self._unit(u, v))
        return su / self._width[0], sv / self._width[1]


def test_unit_grid_is_the_papers_grid_bit_for_bit():
    """On [0, 1]^2 the fractions are the coordinates, so Table 1's grid is unchanged."""
    g = auxiliary_grid(15, 15)
    i, j = np.meshgrid(np.arange(16), np.arange(16), indexing="ij")
    assert np.array_equal(g.uv, np.column_stack([i.ravel() / 15, j.ravel() / 15]))
    assert g.domain == UNIT


def test_grid_on_any_rectangle_has_exact_sides_and_corners():
    g = auxiliary_grid(4, 3, SHIFTED)
    b = g.uv[g.boundary]
    assert np.array_equal(b.min(axis=0), [2.0, -1.0]) and np.array_equal(b.max(axis=0), [5.0, 3.0])
    assert np.array_equal(g.uv[g.boundary][g.boundary_corner], [[2.0, -1.0], [5.0, -1.0], [5.0, 3.0], [2.0, 3.0]])
    ends = g.uv[g.boundary_segments]
    for k, name in enumerate(SIDES):
        assert np.all(ends[g.boundary_segment_side == k][:, :, k // 2] == SHIFTED.side_values[k]), name


def test_mesh_on_a_shifted_rectangle_equals_the_unit_chart():
    """The same surface read on [2, 5] x [-1, 3]: same triangulation, same points, (u, v) in that rectangle."""
    base = dome()
    shifted = Reparametrised(base, SHIFTED)
    assert isinstance(shifted, Chart) and domain_of(shifted) is SHIFTED
    a = equimesh.mesh_surface(base, 5.0, grid=(8, 8), placement="default", optimize="none")
    b = equimesh.mesh_surface(shifted, 5.0, grid=(8, 8), placement="default", optimize="none")
    assert_valid_surface_mesh(b, shifted)
    assert np.array_equal(a.triangles, b.triangles) and a.n_boundary == b.n_boundary
    np.testing.assert_allclose(b.points, a.points, rtol=0, atol=1e-9)
    # the two flattenings start from different metric starts and agree to their convergence tolerance
    np.testing.assert_allclose((b.uv - SHIFTED.lower) / (SHIFTED.upper - SHIFTED.lower), a.uv, rtol=0, atol=1e-10)


@pytest.mark.parametrize("objective", ["paper", "bounded"])
def test_optimisation_keeps_the_nodes_in_the_chart_rectangle(objective):
    """The final step's bounds are the chart's rectangle; the objective does not grow."""
    shifted = Reparametrised(dome(rise=10.0), SHIFTED)
    mesh = equimesh.mesh_surface(shifted, 5.0, grid=(8, 8), placement="default", optimize=objective)
    assert_valid_surface_mesh(mesh, shifted)
    opt = mesh.stages.optimization
    assert opt.cost_after <= opt.cost_before


def test_refusals_name_the_sides_of_the_chart():
    """A side shorter than l is named by the chart's own bounds, not by 0 and 1."""
    with pytest.raises(equimesh.SurfaceTooSmallError) as err:
        equimesh.mesh_surface(Reparametrised(dome(), SHIFTED), 40.0, grid=(4, 4), optimize="none")
    assert "side v = -1 of the surface, from corner (u, v) = (2, -1) to corner (u, v) = (5, -1)" in str(err.value)


def test_surface_without_domain_is_on_the_unit_square():
    class Plain:
        evaluate, derivatives = dome().evaluate, dome().derivatives

    assert domain_of(Plain()) is UNIT
    Plain.domain = (0.0, 1.0)
    with pytest.raises(InvalidSurfaceError, match="surface.domain must be an equimesh Domain, got tuple"):
        domain_of(Plain())


def test_fractions_are_exact_at_both_ends():
    d = Domain((0.1, 0.7), (-3.3, 1e-3))
    assert np.array_equal(d.at_fractions([0.0, 1.0], [0.0, 1.0]), [[0.1, -3.3], [0.7, 1e-3]])


@pytest.mark.parametrize(
    "u, fragment",
    [
        ((1.0, 1.0), "parameter range of u, [1.0, 1.0], is empty or too narrow"),
        ((2.0, 1.0), "[2.0, 1.0], is empty"),
        ((1e12, 1e12 + 1e-4), "too narrow for its position"),
        ((0.0, np.inf), "must be finite, got [0.0, inf]"),
        ((0.0,), "must be a pair of numbers"),
        (("a", 1.0), "must be a pair of numbers"),
    ],
)
def test_domain_validation_messages(u, fragment):
    with pytest.raises(InvalidSurfaceError) as err:
        Domain(u, (0.0, 1.0))
    assert fragment in str(err.value) and "\n" not in str(err.value)
