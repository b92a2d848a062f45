"""The JSON description of a NURBS surface (``io/_nurbs.py``): an exact round trip, and every malformed field refused
in one line naming it.
"""

import json

import numpy as np
import pytest
from hostile_files import degree_399
from hostile_files import small_nurbs as good
from refusals import assert_one_line

from equimesh import InvalidSurfaceError, NurbsSurface
from equimesh.io import surface_from_dict, surface_to_dict


def test_json_round_trip():
    s = surface_from_dict(json.loads(json.dumps(good())))
    assert isinstance(s, NurbsSurface) and s.domain.u == (0.0, 1.0)
    again = surface_from_dict(json.loads(json.dumps(surface_to_dict(s))))
    uv = np.random.default_rng(0).uniform(0, 1, (5, 2))
    assert np.array_equal(again.evaluate(*uv.T), s.evaluate(*uv.T))


def _with(**fields):
    return lambda d: {**d, **fields}


@pytest.mark.parametrize(
    "mutate, fragment",
    [
        (_with(degree=[0, 1]), "degree[0] must be at least 1, got 0"),
        (_with(degree=[2, 1.5]), "degree[1] must be an integer, got number 1.5"),
        (_with(degree=[True, 1]), "degree[0] must be an integer, got boolean true"),
        (_with(degree=[26, 1]), "degree[0] = 26 is above 25, the highest degree supported: evaluating the surface"),
        (_with(degree=[2, 10**400]), "degree[1] = an integer of 401 digits is above 25"),
        (_with(degree=[2]), '"degree" needs at least 2 integers [p, q], got 1'),
        (_with(degree=[2, 1, 1]), '"degree" must be a list of 2 integers [p, q], got 3 entries'),
        (
            _with(knots_u=[0, 0, 0, 0.5, 0.4, 1, 1]),
            "knots_u must be non-decreasing, but knots_u[4] = 0.4 < knots_u[3] = 0.5",
        ),
        (_with(knots_u=[0, 0, 0, 1, 1, 1]), "knots_u must hold 7 knots (4 control points + degree 2 + 1), got 6"),
        (_with(knots_v=[0, 0, 1, "x"]), "knots_v[3] must be a real number, got string"),
        (_with(knots_v=[0, 0, 0, 0]), "knots_v spans no domain: knots_v[1] = knots_v[2] = 0.0"),
        (
            _with(knots_u=[0, 0, 0.5, 0.5, 1, 1], degree=[1, 1]),
            "knots_u repeats 0.5 2 times inside the domain, more than the degree 1",
        ),
        (_with(weights=[[1, 1], [0.5, 0], [1, 1], [3, 1]]), "weights[1][1] must be positive, got 0.0"),
        (_with(weights=[[1, 1], [0.5, -2], [1, 1], [3, 1]]), "weights[1][1] must be positive, got -2.0"),
        (_with(weights=[[1, 1], [0.5, 2], [1, 1]]), "weights must have shape (4, 2) like the control net, got (3, 2)"),
        (_with(weights=[[1, 1], [0.5], [1, 1], [3, 1]]), "weights[1] has 1 weights, but weights[0] has 2"),
        (_with(weights=[[1, 1], [0.5, float("nan")], [1, 1], [3, 1]]), "weights[1][1] is not a finite number: nan"),
        (_with(degree=[4, 1]), "control_points must have shape (n_u, n_v, 3) with n_u >= p + 1 = 5"),
        (
            _with(control_points=[[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1]]]),
            "control_points[1][1] must be a list [x, y, z]",
        ),
        (lambda d: {k: v for k, v in d.items() if k != "weights"}, 'missing the field "weights"'),
    ],
)
def test_bad_nurbs_are_refused_in_one_line_naming_the_field(mutate, fragment):
    with pytest.raises(InvalidSurfaceError) as err:
        surface_from_dict(mutate(good()))
    assert fragment in str(err.value)
    assert_one_line(str(err.value))


def test_degree_above_the_bound_is_refused_before_any_evaluation(monkeypatch):
    """Degree (399, 2): one line saying why, from the constructor, so no point is evaluated."""
    from equimesh.surface.charts import nurbs

    monkeypatch.setattr(nurbs.NurbsSurface, "_rational", lambda *args: pytest.fail("evaluated"))
    with pytest.raises(InvalidSurfaceError, match=r"^degree\[0\] = 399 is above 25, .* square of the degree"):
        surface_from_dict(degree_399())


def test_degree_at_the_bound_is_read():
    from equimesh.surface.charts.nurbs import MAX_DEGREE

    d = {**degree_399(), "degree": [MAX_DEGREE, 2], "knots_u": [0.0] * (MAX_DEGREE + 1) + [1.0] * (MAX_DEGREE + 1)}
    d["control_points"], d["weights"] = d["control_points"][: MAX_DEGREE + 1], d["weights"][: MAX_DEGREE + 1]
    assert surface_from_dict(d).degree == (MAX_DEGREE, 2)


def test_net_above_the_bound_is_refused_before_its_points_are_read():
    """A net of more than MAX_NET_POINTS points is refused on its shape: the points (here not even numbers) are not
    read."""
    from equimesh.surface.charts.nurbs import MAX_NET_POINTS

    rows = MAX_NET_POINTS // 1000 + 1
    d = {**good(), "control_points": [["not a point"] * 1000] * rows}
    with pytest.raises(InvalidSurfaceError, match=rf"has {rows} x 1000 = {rows * 1000} points, more than the"):
        surface_from_dict(d)


@pytest.mark.parametrize(
    "fields, message",
    [
        ({"degree": [2]}, '"degree" needs at least 2 integers [p, q], got 1'),
        ({"degree": 2}, '"degree" must be a list of integers [p, q], got number'),
        ({"degree": [2, 1, 1]}, '"degree" must be a list of 2 integers [p, q], got 3 entries'),
        ({"degree": [2, "1"]}, "degree[1] must be an integer, got string 1"),
        ({"degree": [False, 1]}, "degree[0] must be an integer, got boolean false"),
        ({"degree": [None, 1]}, "degree[0] must be an integer, got null"),
        ({"knots_u": []}, '"knots_u" needs at least 1 numbers, got 0'),
        ({"knots_v": {"0": 0}}, '"knots_v" must be a list of numbers, got object'),
        ({"knots_v": [0, 0, 1, None]}, "knots_v[3] must be a real number, got null"),
        ({"knots_u": [0, 0, 0, 0.5, 1, 1, float("inf")]}, "knots_u[6] is not a finite number: inf"),
        ({"weights": []}, '"weights" needs at least 1 rows, got 0'),
        ({"weights": [[], [], [], []]}, "weights[0] needs at least 1 weights, got 0"),
        ({"weights": [[1, 1], [0.5, 2], [1, "1"], [3, 1]]}, "weights[2][1] must be a real number, got string 1"),
        ({"weights": [[1, 1], [0.5, 2], [1, 1], [float("-inf"), 1]]}, "weights[3][0] is not a finite number: -inf"),
        (
            {"control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, None]]]},
            "control_points[1][1][2] must be a real number, got null",
        ),
    ],
)
def test_refusals_of_the_nurbs_fields_are_whole_lines(fields, message):
    with pytest.raises(InvalidSurfaceError) as err:
        surface_from_dict({**good(), **fields})
    assert str(err.value) == message


def test_the_net_is_read_before_the_knots_and_the_weights():
    """Its size bounds what reading the rest may cost: with every field wrong, the net is named."""
    d = {**good(), "control_points": [[[0, 0, 0]]], "knots_u": "x", "knots_v": "y", "weights": "z"}
    with pytest.raises(InvalidSurfaceError, match='^"control_points" needs at least 2 rows, got 1$'):
        surface_from_dict(d)
    with pytest.raises(InvalidSurfaceError, match='^"knots_u" must be a list'):
        surface_from_dict({**d, "control_points": good()["control_points"]})


def test_the_fields_are_read_into_the_surface():
    s = surface_from_dict(good())
    assert s.degree == (2, 1)
    np.testing.assert_array_equal(s.knots_u, good()["knots_u"])
    np.testing.assert_array_equal(s.knots_v, good()["knots_v"])
    np.testing.assert_array_equal(s.control_points, good()["control_points"])
    np.testing.assert_array_equal(s.weights, good()["weights"])
    assert surface_to_dict(s) == good()
