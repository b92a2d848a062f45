"""The checks of every mesh ``mesh_surface`` returns, and of its fabrication options, on meshes of a few nodes.

Each check passes an output exactly at its bound and fires just beyond it, with the message that names what broke.
A member's bound is [l, 2l] up to ``REL_TOL`` (1e-9 of l), a node's distance from the surface the surface
tolerance up to ``REL_TOL`` of it; an angle's bound and a triangle's orientation have no slack.
"""

import math
import re

import numpy as np
import pytest

from equimesh.errors import EquimeshError, InternalError, InvalidCatalogueError, InvalidToleranceError
from equimesh.mesh import PlanarMesh
from equimesh.surface.output_checks import (
    check_catalogue_holds,
    check_deviation,
    check_fabrication_options,
    check_joints,
    check_members,
    check_orientation,
    check_surface_tolerance,
)

L = 4.0


def _on_a_line(*xs):
    """Points on the x-axis of space at ``xs`` and the members between neighbours."""
    points = np.column_stack([xs, np.zeros(len(xs)), np.zeros(len(xs))])
    return points, np.column_stack([np.arange(len(xs) - 1), np.arange(1, len(xs))])


def test_members_of_exactly_l_and_2l_pass():
    check_members(*_on_a_line(0.0, L, 3 * L), L)


def test_members_within_rel_tol_of_the_band_pass():
    check_members(*_on_a_line(0.0, L * (1 - 0.5e-9), L * (3 - 0.5e-9) + L * 1e-9), L)


@pytest.mark.parametrize(
    "ratio, shown",
    [(1 - 1.2345e-9, "from 0.9999999988 l to 2 l"), (0.95, "from 0.95 l to 2 l"), (0.5, "from 0.5 l to 2 l")],
)
def test_a_member_below_l_is_an_internal_error(ratio, shown):
    """A member shorter than (1 - REL_TOL) l, the range shown with 10 significant digits."""
    points, edges = _on_a_line(0.0, L * ratio, L * ratio + 2 * L)
    message = f"the bounded optimisation returned 1 of 2 members outside [l, 2l] (lengths {shown}); please report"
    with pytest.raises(InternalError, match="^" + re.escape(message) + " this surface$"):
        check_members(points, edges, L)


@pytest.mark.parametrize("ratio, shown", [(2 + 4.2345e-9, "2.000000004"), (2.5, "2.5"), (3.0, "3")])
def test_a_member_above_2l_is_an_internal_error(ratio, shown):
    points, edges = _on_a_line(0.0, L, L + L * ratio, 2 * L + L * ratio, 3 * L + L * ratio)
    with pytest.raises(
        InternalError, match=re.escape(f"returned 1 of 4 members outside [l, 2l] (lengths from 1 l to {shown} l)")
    ):
        check_members(points, edges, L)


def test_every_member_outside_the_band_is_counted():
    with pytest.raises(
        InternalError, match=re.escape("returned 2 of 3 members outside [l, 2l] (lengths from 0.5 l to 3 l)")
    ):
        check_members(*_on_a_line(0.0, 0.5 * L, 2.5 * L, 5.5 * L), L)


def _off(distances):
    """Nodes at ``distances`` above their points on the surface (the plane z = 0)."""
    on_surface = np.column_stack(
        [np.arange(len(distances), dtype=float), np.ones(len(distances)), np.zeros(len(distances))]
    )
    return on_surface + np.column_stack([np.zeros(len(distances)), np.zeros(len(distances)), distances]), on_surface


def test_nodes_on_the_surface_or_within_its_tolerance_pass():
    check_deviation(*_off([0.0, 0.0]), 0.0)
    check_deviation(*_off([0.0, 0.5, -0.5, 0.5 * (1 + 0.5e-9)]), 0.5)


@pytest.mark.parametrize(
    "distances, tolerance, count, shown",
    [
        ([0.0, 1e-12], 0.0, 1, "0 from the surface (up to 1e-12)"),
        ([0.5, 0.5 + 1.2345e-9, -0.7, 0.25], 0.5, 2, "0.5 from the surface (up to 0.7)"),
        ([0.5, 0.5 + 1.2345e-9, 0.0], 0.5, 1, "0.5 from the surface (up to 0.5000000012)"),
    ],
)
def test_a_node_beyond_the_surface_tolerance_is_an_internal_error(distances, tolerance, count, shown):
    message = (
        f"the optimisation put {count} nodes farther than the surface tolerance {shown}; please report this surface"
    )
    with pytest.raises(InternalError, match="^" + re.escape(message) + "$"):
        check_deviation(*_off(distances), tolerance)


#: A right isosceles triangle and its mirror image: angles pi/2 at node 0 (or 3) and pi/4 at the other two, exactly.
RIGHT = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [2.0, 1.0, 1.0], [1.0, 1.0, 1.0], [2.0, 0.0, 1.0]])
RIGHT_TRIANGLES = np.array([[0, 1, 2], [3, 4, 5]])
RIGHT_ANGLES = np.array([[math.pi / 2, math.pi / 4, math.pi / 4]] * 2)


def test_angles_at_their_bounds_pass():
    check_joints(RIGHT, RIGHT_TRIANGLES, RIGHT_ANGLES)
    check_joints(RIGHT, RIGHT_TRIANGLES, np.zeros((2, 3)))


@pytest.mark.parametrize("triangle, corner", [(0, 0), (1, 2), (1, 1)])
def test_an_angle_below_its_bound_is_an_internal_error(triangle, corner):
    """One bound a bit above its angle, each other angle exactly at its bound; the smallest angle of all is shown."""
    bounds = RIGHT_ANGLES.copy()
    bounds[triangle, corner] = np.nextafter(bounds[triangle, corner], 4.0)
    message = "the optimisation returned 1 of 2 triangles with an angle below its bound (smallest 45 degrees)"
    with pytest.raises(InternalError, match="^" + re.escape(message) + "; please report this surface$"):
        check_joints(RIGHT, RIGHT_TRIANGLES, bounds)


def test_every_triangle_below_its_bounds_is_counted():
    with pytest.raises(InternalError, match=r"^the optimisation returned 2 of 2 triangles with an angle below"):
        check_joints(RIGHT, RIGHT_TRIANGLES, RIGHT_ANGLES + 1e-9)


#: A unit square in (u, v) cut into two counter-clockwise triangles.
SQUARE_UV = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


def test_counter_clockwise_triangles_pass():
    check_orientation(SQUARE_UV, np.array([[0, 1, 2], [0, 2, 3]]), "the optimisation")


@pytest.mark.parametrize(
    "triangles, message",
    [
        ([[0, 1, 2], [0, 3, 2]], "the optimisation inverted 1 of 2 triangles in (u, v) (first: [0, 3, 2])"),
        (
            [[0, 1, 2], [0, 2, 2], [1, 0, 3], [0, 1, 3]],
            "the optimisation inverted 2 of 4 triangles in (u, v) (first: [0, 2, 2])",
        ),
    ],
)
def test_a_clockwise_or_flat_triangle_is_an_internal_error(triangles, message):
    with pytest.raises(InternalError, match="^" + re.escape(message) + "; please report this surface$"):
        check_orientation(SQUARE_UV, np.array(triangles), "the optimisation")


def _rings():
    """A plane mesh's boundary (only its rings matter to the check) and the boundary nodes that stay put.

    The outer ring, a 6 x 4 rectangle started in the middle of its lower side: corners at nodes 2, 4, 8, 10, sides
    (from node 2) of 4 (two members of 2), 6 (four of 1.5), 4 (two of 2) and 6 (four of 1.5).  Opening 0, a unit
    square, all four nodes corners: sides of 1.  Opening 1, a square of side 1.2 whose nodes all slide: one side,
    4.8 long.
    """
    outer = [(3, 0), (4.5, 0), (6, 0), (6, 2), (6, 4), (4.5, 4), (3, 4), (1.5, 4), (0, 4), (0, 2), (0, 0), (1.5, 0)]
    square = [(1, 1), (1, 2), (2, 2), (2, 1)]
    slanted = [(4, 1), (4, 2.2), (5.2, 2.2), (5.2, 1)]
    uv = np.array(outer + square + slanted, dtype=float)
    plane = PlanarMesh.build(uv, np.zeros((0, 3)), 1.0, len(uv), info={"boundary_rings": [12, 4, 4]})
    return np.column_stack([uv, np.zeros(len(uv))]), plane, [2, 4, 8, 10, 12, 13, 14, 15]


def test_a_catalogue_that_holds_every_side_passes():
    points, plane, corners = _rings()
    check_catalogue_holds(np.array([1.0, 1.2, 2.0]), points, plane, corners, 1.0, 0.005)
    check_catalogue_holds(np.array([1.0, 1.5, 1.6]), points, plane, corners, 1.0, 0.005)


@pytest.mark.parametrize(
    "catalogue, side",
    [
        ([1.5], "side 0 of the outer boundary, 4 long"),
        ([4 / 3], "side 1 of the outer boundary, 6 long"),
        ([1.5, 2.0], "side 0 of opening 0, 1 long"),
        ([1.0, 2.0], "side 0 of opening 1, 4.8 long"),
    ],
)
def test_a_side_no_stock_lengths_add_up_to_is_refused(catalogue, side):
    points, plane, corners = _rings()
    stock = ", ".join(f"{c:g}" for c in catalogue)
    message = f"lengths: no count of the stock lengths {stock} within 0.005 l of each adds up to {side} on the surface"
    with pytest.raises(InvalidCatalogueError, match="^" + re.escape(message) + "; add a length or choose another l$"):
        check_catalogue_holds(np.array(catalogue), points, plane, corners, 1.0, 0.005)


def test_rings_whose_nodes_all_slide_are_one_side_each():
    """Without corners the outer ring is one side of 20, the openings of 4 and 4.8."""
    points, plane, _ = _rings()
    check_catalogue_holds(np.array([1.0, 1.2]), points, plane, [], 1.0, 0.005)
    with pytest.raises(
        InvalidCatalogueError,
        match=re.escape("stock lengths 2 within 0.005 l of each adds up to side 0 of opening 1, 4.8 long"),
    ):
        check_catalogue_holds(np.array([2.0]), points, plane, [], 1.0, 0.005)


def test_the_sides_are_measured_on_the_surface():
    """The same rings lifted onto a slope of 1 in x: the upper side (four members of 1.5 in the plane) is 6 sqrt(2)
    long on it, which no count of the stock lengths 1 and 2 adds up to (it holds every side in the plane but the
    second opening's)."""
    points, plane, corners = _rings()
    points[:, 2] = points[:, 0]
    with pytest.raises(InvalidCatalogueError, match=re.escape("side 1 of the outer boundary, 8.48528 long")):
        check_catalogue_holds(np.array([1.0, 2.0]), points, plane, corners, 1.0, 0.005)


def test_fabrication_options_of_a_run():
    assert check_fabrication_options("paper", None, 0, 1.0) == (None, 0.0)
    catalogue, tolerance = check_fabrication_options("classes", "1.5, 1.2,1.5", "0.25", 1.0)
    assert catalogue.tolist() == [1.2, 1.5] and tolerance == 0.25 and type(tolerance) is float
    assert check_fabrication_options("bounded", None, 0.5, 4.0) == (None, 0.5)


@pytest.mark.parametrize("optimize", ["bounded", "paper", "none"])
def test_a_catalogue_is_for_the_classes_objective_only(optimize):
    with pytest.raises(
        EquimeshError, match=f"^lengths= is a catalogue for optimize='classes', got optimize='{optimize}'$"
    ):
        check_fabrication_options(optimize, [1.5], 0.0, 1.0)


@pytest.mark.parametrize("optimize, tolerance", [("paper", 0.5), ("none", 1e-300), ("none", 3.0)])
def test_a_surface_tolerance_needs_sliding_boundary_nodes(optimize, tolerance):
    message = (
        "surface_tolerance= lets the optimisation move nodes off the surface: use optimize='bounded' or 'classes', "
        f"got optimize='{optimize}'"
    )
    with pytest.raises(EquimeshError, match="^" + re.escape(message) + "$"):
        check_fabrication_options(optimize, None, tolerance, 4.0)


@pytest.mark.parametrize(
    "value, expected",
    [(0, 0.0), ("0.25", 0.25), (np.float32(0.5), 0.5), (math.nextafter(4.0, 0), math.nextafter(4.0, 0))],
)
def test_surface_tolerances_in_0_to_l_are_taken(value, expected):
    assert check_surface_tolerance(value, 4.0) == expected


@pytest.mark.parametrize(
    "value, shown",
    [
        (None, "must be a number, got None"),
        ("abc", "must be a number, got 'abc'"),
        (10**400, "must be a number, got 1000"),
        (-0.1, "must be at least 0 and below l = 4, got -0.1"),
        (4.0, "must be at least 0 and below l = 4, got 4"),
        (float("nan"), "must be at least 0 and below l = 4, got nan"),
        ("-inf", "must be at least 0 and below l = 4, got -inf"),
        (float("inf"), "must be at least 0 and below l = 4, got inf"),
    ],
)
def test_a_surface_tolerance_outside_0_to_l_is_refused(value, shown):
    with pytest.raises(InvalidToleranceError, match="^" + re.escape("surface_tolerance " + shown)):
        check_surface_tolerance(value, 4.0)
