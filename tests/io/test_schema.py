"""Checks shared by the JSON schemas, and plain text for messages (``io/_schema.py``): each check returns what it was
given or refuses it in one line naming the field by its JSON path; values are shown as JSON writes them, cut when
long, never as a Python or numpy ``repr``."""

import errno
import math

import numpy as np
import pytest

from equimesh import InvalidSurfaceError
from equimesh.io._schema import (
    SHOWN_CHARS,
    SHOWN_PATH_CHARS,
    a_list,
    control_net,
    coordinates,
    described,
    finite_number,
    json_type,
    number_rows,
    os_reason,
    shown,
    shown_path,
    uv_polylines,
)


def refusal(check, *args):
    with pytest.raises(InvalidSurfaceError) as err:
        check(*args)
    return str(err.value)


@pytest.mark.parametrize(
    "value, name",
    [
        ({}, "object"),
        ([], "list"),
        ("x", "string"),
        (True, "boolean"),
        (None, "null"),
        (3, "number"),
        (1.5, "number"),
        (np.float64(2), "number"),
        (np.int64(2), "number"),
        (2j, "complex"),
        ((1, 2), "tuple"),
    ],
)
def test_json_type_names_the_json_type(value, name):
    assert json_type(value) == name


@pytest.mark.parametrize(
    "value, text",
    [
        (True, "true"),
        (False, "false"),
        (7, "7"),
        (np.int64(-7), "-7"),
        (10**SHOWN_CHARS - 1, "9" * SHOWN_CHARS),
        (-(10**SHOWN_CHARS - 1), "-" + "9" * SHOWN_CHARS),
        (10**SHOWN_CHARS, f"an integer beyond 1e{SHOWN_CHARS}"),
        (-(10**SHOWN_CHARS), f"an integer beyond 1e{SHOWN_CHARS}"),
        (1.5, "1.5"),
        (np.float32(0.5), "0.5"),
        (math.nan, "nan"),
        ("a" * SHOWN_CHARS, "a" * SHOWN_CHARS),
        ("b" * (SHOWN_CHARS + 1), "b" * (SHOWN_CHARS - 3) + "..."),
        ([1, 2], "[1, 2]"),
    ],
)
def test_values_are_shown_as_short_plain_text(value, text):
    assert shown(value) == text


@pytest.mark.parametrize(
    "value, text", [(None, "null"), (1.5, "number 1.5"), (True, "boolean true"), ("x", "string x"), ([1], "list [1]")]
)
def test_described_gives_the_json_type_and_the_value(value, text):
    assert described(value) == text


def test_a_list_returns_a_long_enough_list_and_refuses_anything_else():
    rows = [1, 2]
    assert a_list(rows, "where", "things", 2) is rows
    assert refusal(a_list, (1, 2), "where", "things", 2) == "where must be a list of things, got tuple"
    assert refusal(a_list, [1], "where", "things", 2) == "where needs at least 2 things, got 1"


def test_finite_number_is_a_float_of_any_real_number_and_refuses_others():
    for value, expected in [(3, 3.0), (np.float32(0.5), 0.5), (-2.5, -2.5), (np.int64(4), 4.0)]:
        got = finite_number(value, "x")
        assert type(got) is float and got == expected
    assert refusal(finite_number, True, "x[0]") == "x[0] must be a real number, got boolean true"
    assert refusal(finite_number, "1", "x[0]") == "x[0] must be a real number, got string 1"
    assert refusal(finite_number, None, "x[0]") == "x[0] must be a real number, got null"
    assert refusal(finite_number, math.inf, "x[0]") == "x[0] is not a finite number: inf"
    assert refusal(finite_number, -math.inf, "x[0]") == "x[0] is not a finite number: -inf"
    assert refusal(finite_number, 10**400, "x[0]") == "x[0] is not a finite number: an integer beyond 1e40"


def test_number_rows_are_equally_long_rows():
    rows = [[1, 2], [3, 4], [5, 6]]
    assert number_rows(rows, "w", "weights", 3, 2) is rows
    assert refusal(number_rows, 5, "w", "weights", 1, 1) == '"w" must be a list of rows, got number'
    assert refusal(number_rows, [[1]], "w", "weights", 2, 1) == '"w" needs at least 2 rows, got 1'
    assert refusal(number_rows, [[1, 2], [3]], "w", "weights", 1, 2) == "w[1] needs at least 2 weights, got 1"
    assert refusal(number_rows, [[1, 2], "ab"], "w", "weights", 1, 2) == "w[1] must be a list of weights, got string"
    assert refusal(number_rows, [[1], [2, 3]], "w", "weights", 1, 1) == "w[1] has 2 weights, but w[0] has 1"


def test_a_control_net_is_checked_for_its_shape_before_its_points():
    shapes = []
    net = [[[0, 0, 0], [0, 1, 0], [0, 2, 0]], [[1, 0, 0], [1, 1, 1], [1, 2, 0]]]
    assert control_net(net, lambda *shape: shapes.append(shape), "cp") is net
    assert shapes == [(2, 3)]

    def too_large(rows, columns):
        raise InvalidSurfaceError(f"{rows} x {columns} is too large")

    assert refusal(control_net, [["no point"] * 2] * 2, too_large) == "2 x 2 is too large"
    bad = [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, "z"]]]
    assert refusal(control_net, bad, lambda *_: None, "cp") == "cp[1][1][2] must be a real number, got string z"
    assert refusal(control_net, bad, lambda *_: None).startswith("control_points[1][1][2] must be")
    assert refusal(control_net, [[[0, 0, 0], [0, 1]], [[1, 0, 0], [1, 1, 1]]], lambda *_: None) == (
        "control_points[0][1] must be a list [x, y, z] of 3 numbers, got list [0, 1]"
    )
    assert refusal(control_net, [[[0, 0, 0]], [[1, 0, 0]]], lambda *_: None) == (
        "control_points[0] needs at least 2 points, got 1"
    )
    assert refusal(control_net, [[[0, 0, 0], [0, 1, 0]]], lambda *_: None) == (
        '"control_points" needs at least 2 rows, got 1'
    )


def test_uv_polylines_are_closed_polylines_of_uv_pairs():
    holes = [[[0.1, 0.1], [0.2, 0.1], [0.2, 0.2]], [[0.5, 0.5], [0.6, 0.5], [0.6, 0.6], [0.5, 0.6]]]
    assert uv_polylines(holes) is holes
    assert uv_polylines([]) == []
    assert refusal(uv_polylines, {"a": 1}) == '"holes" must be a list of polylines, got object'
    assert refusal(uv_polylines, {"a": 1}, "cuts") == '"cuts" must be a list of polylines, got object'
    assert refusal(uv_polylines, [holes[0], holes[1][:2]]) == "holes[1] needs at least 3 [u, v] points, got 2"
    assert refusal(uv_polylines, [[[0, 0], [1, 0], [1, 1, 1]]]) == (
        "holes[0][2] must be a list [u, v] of 2 numbers, got list [1, 1, 1]"
    )
    assert refusal(uv_polylines, [[[0, 0], [1, 0], [1, "v"]]]) == "holes[0][2][1] must be a real number, got string v"


def test_coordinates_are_a_list_of_as_many_finite_numbers_as_names():
    point = [1, 2.5, -3]
    assert coordinates(point, "p", "xyz") is point
    assert refusal(coordinates, (1, 2, 3), "p", "xyz") == "p must be a list [x, y, z] of 3 numbers, got tuple (1, 2, 3)"
    assert refusal(coordinates, [1, 2], "p", "xyz") == "p must be a list [x, y, z] of 3 numbers, got list [1, 2]"
    assert refusal(coordinates, [1, 2, 3], "q", "uv") == "q must be a list [u, v] of 2 numbers, got list [1, 2, 3]"
    assert refusal(coordinates, [1, math.nan], "q", "uv") == "q[1] is not a finite number: nan"


def test_long_paths_are_cut_in_the_middle():
    half = SHOWN_PATH_CHARS // 2
    short = "d/" * (SHOWN_PATH_CHARS // 2)
    assert shown_path(short) == short and len(short) == SHOWN_PATH_CHARS
    long = "a" * half + "m" + "z" * half
    assert shown_path(long) == f"{'a' * half}...{'z' * half} ({SHOWN_PATH_CHARS + 1} characters)"


@pytest.mark.parametrize(
    "exc, reason",
    [
        (OSError(errno.ENAMETOOLONG, "File name too long"), "path too long"),
        (PermissionError(errno.EACCES, "Permission denied"), "Permission denied"),
        (OSError(errno.EIO, ""), "OSError"),
        (FileNotFoundError(), "FileNotFoundError"),
    ],
)
def test_the_reason_of_a_system_error_is_plain_words(exc, reason):
    assert os_reason(exc) == reason
