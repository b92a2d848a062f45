"""The benchmark set (equimesh.testing.benchmark): its surfaces, the methods' protocol and how a method is loaded."""

import numpy as np
import pytest
from repository import SURFACES

from equimesh import InvalidMethodError, load_surface
from equimesh.mesh import edge_lengths, unique_edges
from equimesh.metrics import comparison_figures
from equimesh.testing.benchmark import BENCHMARK, SPAN, load_method, parameter_grid, triangle_mesh


def test_five_surfaces_over_the_same_square_each_with_its_l():
    assert list(BENCHMARK) == ["reference dome", "steep dome", "hyperbolic paraboloid", "wave", "barrel"]
    for name, entry in BENCHMARK.items():
        assert entry.name == name and entry.length == SPAN / 16 and entry.about
        corners = entry.surface.evaluate(np.array([0.0, 1.0, 0.0, 1.0]), np.array([0.0, 0.0, 1.0, 1.0]))
        assert np.allclose(corners[:, :2], [[0, 0], [SPAN, 0], [0, SPAN], [SPAN, SPAN]])
        du, dv = entry.surface.derivatives(np.array([0.5]), np.array([0.5]))
        assert np.linalg.norm(np.cross(du, dv)) > 0  # a regular chart


def test_the_reference_dome_is_the_file_of_table_1_to_the_bit():
    dome = load_surface(SURFACES / "reference_dome.json")
    assert np.array_equal(BENCHMARK["reference dome"].surface.control_points, dome.control_points)


def test_a_method_of_the_protocol_is_measured_like_any_other():
    """parameter_grid, the example method, uses the chart alone; its cells are about l long on the middle curves."""
    for entry in BENCHMARK.values():
        points, triangles = triangle_mesh(parameter_grid(entry.surface, entry.length), "parameter grid")
        figures = comparison_figures(points, triangles, entry.length)
        nodes = len(points)
        assert figures["members"] == nodes + len(triangles) - 1  # Euler: a disc
        assert 0 < figures["angle_min"] <= figures["angle_max"] < 180
        median = np.median(edge_lengths(points, unique_edges(triangles)))
        assert 0.75 * entry.length <= median <= 1.5 * entry.length  # cell sides about l, diagonals longer


NOT_MESHES = {
    "not a pair": (None, "returned NoneType, not a triangle mesh"),
    "three items": ((1, 2, 3), "returned tuple, not a triangle mesh"),
    "2-D points": ((np.zeros((3, 2)), [[0, 1, 2]]), r"points of shape \(3, 2\)"),
    "non-finite points": ((np.full((3, 3), np.nan), [[0, 1, 2]]), "not \\(N, 3\\) finite numbers"),
    "quads": ((np.zeros((4, 3)), [[0, 1, 2, 3]]), r"triangles of shape \(1, 4\)"),
    "no triangles": ((np.zeros((3, 3)), np.zeros((0, 3), int)), "M >= 1"),
    "fractional indices": ((np.zeros((3, 3)), [[0, 1, 1.5]]), "not whole numbers"),
    "text indices": ((np.zeros((3, 3)), [["a", "b", "c"]]), "not whole numbers"),
    "index out of range": ((np.zeros((3, 3)), [[0, 1, 3]]), r"outside 0\.\.2"),
    "ragged": (([[0, 0, 0], [1, 1]], [[0, 1, 2]]), "not arrays of numbers"),
}


@pytest.mark.parametrize("case", sorted(NOT_MESHES))
def test_an_answer_that_is_not_a_triangle_mesh_is_refused_in_one_line(case):
    result, message = NOT_MESHES[case]
    with pytest.raises(InvalidMethodError, match=message) as caught:
        triangle_mesh(result, "mine")
    assert "method mine" in str(caught.value) and "\n" not in str(caught.value)


def test_whole_float_indices_are_accepted():
    points, triangles = triangle_mesh((np.eye(3), np.array([[0.0, 1.0, 2.0]])), "mine")
    assert triangles.dtype == np.int64 and triangles.tolist() == [[0, 1, 2]]


def test_a_method_is_loaded_by_module_and_function():
    assert load_method("equimesh.testing.benchmark:triangle_mesh") is triangle_mesh
    assert (
        load_method("equimesh:BezierSurface.evaluate")
        is load_method("equimesh.surface.charts.bezier:BezierSurface").evaluate
    )


@pytest.mark.parametrize(
    "spec, message",
    [
        ("no_colon", "expected package.module:function"),
        ("no_such_module_here:run", "cannot import no_such_module_here \\(ModuleNotFoundError"),
        ("equimesh.testing.benchmark:no_such_function", "has no no_such_function"),
        ("equimesh.testing.benchmark:SPAN", "is a float, not a function"),
    ],
)
def test_a_method_that_cannot_be_loaded_is_refused_in_one_line(spec, message):
    with pytest.raises(InvalidMethodError, match=message):
        load_method(spec)
