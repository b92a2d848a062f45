"""Surface descriptions in (``io/_surfaces.py``, ``io/_bezier.py``): the surface-type registry, JSON validation, hostile
files.

Every refusal is one line of our own (an :class:`equimesh.EquimeshError`) that
names the problem in the caller's terms, with plain numbers.
"""

import json
import os
import sys

import numpy as np
import pytest
from hostile_paths import fifo
from hypothesis import given
from hypothesis import strategies as st
from refusals import assert_one_line

from equimesh import BezierSurface, InvalidSurfaceError
from equimesh.io import (
    INPUT_FORMATS,
    SURFACE_TYPES,
    load_surface,
    surface_from_dict,
    surface_to_dict,
)
from equimesh.io._schema import shown_path


def good_dict():
    return {"type": "bezier", "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]]}


# ------------------------------------------------------------------ the surface-type registry

finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False)


@given(
    st.integers(2, 4).flatmap(
        lambda rows: st.integers(2, 4).flatmap(
            lambda cols: st.lists(
                st.lists(st.lists(finite, min_size=3, max_size=3), min_size=cols, max_size=cols),
                min_size=rows,
                max_size=rows,
            )
        )
    )
)
def test_json_round_trip_is_exact(net):
    """surface_to_dict inverts surface_from_dict through JSON text, bit for bit."""
    s = surface_from_dict({"type": "bezier", "control_points": net})
    again = surface_from_dict(json.loads(json.dumps(surface_to_dict(s))))
    assert type(again) is BezierSurface
    assert np.array_equal(again.control_points, s.control_points)


def test_every_registered_type_and_format_is_complete():
    """Each table row names a class, its fields and both directions; each format a reader."""
    assert "bezier" in SURFACE_TYPES and ".json" in INPUT_FORMATS
    for kind in SURFACE_TYPES.values():
        assert kind.fields and callable(kind.from_dict) and callable(kind.to_dict)
    for fmt in INPUT_FORMATS.values():
        assert fmt.name and callable(fmt.read)


@pytest.mark.parametrize("path", [None, 5, b"dome.json"], ids=["None", "a number", "bytes"])
def test_a_path_that_is_no_path_is_refused_by_name(path):
    with pytest.raises(
        InvalidSurfaceError, match=rf"^the surface file must be given as a path, got {type(path).__name__}$"
    ):
        load_surface(path)


def test_surface_to_dict_of_an_unregistered_class():
    with pytest.raises(TypeError, match="no JSON surface type for object"):
        surface_to_dict(object())


def _cp(rows):
    return lambda d: {**d, "control_points": rows}


@pytest.mark.parametrize(
    "mutate, fragment",
    [
        (lambda d: [d], "must be a JSON object, got list"),
        (lambda d: {"control_points": d["control_points"]}, 'missing the field "type" (one of "bezier", "nurbs")'),
        (lambda d: {**d, "type": "mesh"}, 'must be one of "bezier", "nurbs", got \'mesh\''),
        (lambda d: {**d, "type": 3}, 'must be one of "bezier", "nurbs", got number'),
        (lambda d: {"type": "bezier"}, 'missing the field "control_points"'),
        (lambda d: {**d, "colour": 1}, "unknown field 'colour'"),
        (lambda d: {**d, "description": 7}, '"description" must be a string, got number'),
        (_cp("abc"), '"control_points" must be a list of rows, got string'),
        (_cp([[[0, 0, 0], [1, 0, 0]]]), "at least 2 rows, got 1"),
        (_cp([[[0, 0, 0]], [[1, 0, 0]]]), "control_points[0] needs at least 2 points, got 1"),
        (_cp([[[0, 0, 0], [0, 1, 0]], {"x": 1}]), "control_points[1] must be a list of points, got object"),
        (
            _cp([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1], [2, 2, 2]]]),
            "control_points[1] has 3 points, but control_points[0] has 2",
        ),
        (_cp([[[0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]]), "control_points[0][0] must be a list [x, y, z] of 3"),
        (
            _cp([[[0, 0, 0], [0, 1, "z"]], [[1, 0, 0], [1, 1, 1]]]),
            "control_points[0][1][2] must be a real number, got string",
        ),
        (_cp([[[0, 0, 0], [0, 1, True]], [[1, 0, 0], [1, 1, 1]]]), "[0][1][2] must be a real number, got boolean"),
        (_cp([[[0, 0, 0], [0, 1, 2j]], [[1, 0, 0], [1, 1, 1]]]), "[0][1][2] must be a real number, got complex 2j"),
        (
            _cp([[[0, 0, 0], [0, 1, 0]], [[1, 0, np.nan], [1, 1, 1]]]),
            "control_points[1][0][2] is not a finite number: nan",
        ),
        (
            _cp([[[0, 0, 0], [0, 1, 0]], [[1, 0, np.float64(np.inf)], [1, 1, 1]]]),
            "[1][0][2] is not a finite number: inf",
        ),
        (
            _cp([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 10**400, 1]]]),
            "control_points[1][1][1] is not a finite number: an integer beyond 1e40",
        ),
    ],
)
def test_json_validation_messages(mutate, fragment):
    """The first problem is named by its JSON path, with plain values (numpy scalars and complex included)."""
    with pytest.raises(InvalidSurfaceError) as err:
        surface_from_dict(mutate(good_dict()))
    assert fragment in str(err.value)
    assert_one_line(str(err.value))


# ------------------------------------------------------------------ hostile surface files


def _file(tmp_path, text, name="s.json"):
    path = tmp_path / name
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    return path


#: Files that are no surface description -> the refusal, with ``<P>`` for the file's path.
HOSTILE_FILES = {
    "5000-digit integer": (
        '{"type": "bezier", "control_points": [[[' + "9" * 5000 + ", 0, 0]]]}",
        f"<P>: an integer has more than {sys.get_int_max_str_digits()} digits; write coordinates as ordinary numbers",
    ),
    "nested 100000 deep": (
        "[" * 100_000 + "]" * 100_000,
        "<P>: JSON nested too deeply to read (a surface needs a few levels)",
    ),
    "NaN literal": (
        json.dumps(good_dict()).replace("[1, 1, 1]", "[1, NaN, 1]"),
        "control_points[1][1][1] is not a finite number: nan",
    ),
    "Infinity literal": (
        json.dumps(good_dict()).replace("[1, 1, 1]", "[1, 1, -Infinity]"),
        "control_points[1][1][2] is not a finite number: -inf",
    ),
    "beyond the float range": (
        json.dumps(good_dict()).replace("[1, 1, 1]", "[1e400, 1, 1]"),
        "control_points[1][1][0] is not a finite number: inf",
    ),
    "duplicate field": ('{"type": "bezier", "type": "bezier"}', "surface JSON has the field 'type' twice"),
    "duplicate field inside": ('{"a": {"b": 1, "b": 2}}', "surface JSON has the field 'b' twice"),
    "malformed": ("{", "<P>: malformed JSON at line 1 column 2: Expecting property name enclosed in double quotes"),
    "not UTF-8": (b'{"type": "b\xe9zier"}', "<P> is not UTF-8 text (byte 11 cannot be decoded)"),
    "empty": ("", "<P>: malformed JSON at line 1 column 1: Expecting value"),
}


@pytest.mark.parametrize("case", sorted(HOSTILE_FILES))
def test_hostile_surface_files(case, tmp_path):
    text, message = HOSTILE_FILES[case]
    path = _file(tmp_path, text)
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(path)
    assert str(err.value) == message.replace("<P>", str(path))
    assert_one_line(str(err.value))


def test_byte_order_mark_is_accepted(tmp_path):
    path = _file(tmp_path, b"\xef\xbb\xbf" + json.dumps(good_dict()).encode())
    assert load_surface(path).degree == (1, 1)


@pytest.mark.parametrize(
    "make, fragment",
    [
        (lambda d: d / "missing.json", "surface file not found"),
        (lambda d: d / "surface.txt", "unknown surface file extension '.txt'"),
        (lambda d: d / "x.json" / "y.json", "surface file not found"),
        (lambda d: (d / "folder.json").mkdir() or d / "folder.json", "is not a regular file"),
        (lambda d: fifo(d / "pipe.json"), "is not a regular file"),
        (lambda d: d / ("a" * 300 + ".json"), "path too long"),
        (lambda d: d.joinpath(*["a" * 200] * 30, "s.json"), "path too long"),
    ],
)
def test_unreadable_surface_paths(make, fragment, tmp_path):
    """Every path that is not a readable regular .json file is one line naming the reason (and the known formats)."""
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(make(tmp_path))
    assert fragment in str(err.value)
    assert_one_line(str(err.value))
    assert len(str(err.value)) < 400  # a 6,000-character path is cut in the middle


def test_unknown_extension_lists_the_known_ones(tmp_path):
    with pytest.raises(
        InvalidSurfaceError, match=r"use one of \['\.3dm', '\.json', '\.obj', '\.ply', '\.stl', '\.vtk', '\.vtu'\]"
    ):
        load_surface(tmp_path / "s.igs")


def test_a_file_larger_than_any_description_is_refused_before_it_is_parsed(tmp_path, monkeypatch):
    """Above MAX_JSON_BYTES the file is refused on its size, never parsed (that would take seconds)."""
    from equimesh.io import _surfaces

    monkeypatch.setattr(_surfaces.json, "loads", lambda *args, **kwargs: pytest.fail("parsed"))
    path = _file(tmp_path, b"")
    os.truncate(path, _surfaces.MAX_JSON_BYTES + 1)  # a sparse file: nothing is written
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(path)
    assert str(err.value) == (
        f"{path} has {_surfaces.MAX_JSON_BYTES + 1} bytes, more than the {_surfaces.MAX_JSON_BYTES} of the largest "
        "surface description read (a control net of the most points allowed takes a third of that)"
    )


def test_a_file_of_the_largest_size_read_is_parsed(tmp_path, monkeypatch):
    from equimesh.io import _surfaces

    path = _file(tmp_path, json.dumps(good_dict()))
    monkeypatch.setattr(_surfaces, "MAX_JSON_BYTES", path.stat().st_size)
    assert load_surface(path).degree == (1, 1)


def test_a_bezier_net_above_the_degree_bound_is_refused_on_its_shape():
    from equimesh.surface.charts.bezier import MAX_DEGREE

    d = {"type": "bezier", "control_points": [["not a point"] * 2] * (MAX_DEGREE + 2)}
    with pytest.raises(InvalidSurfaceError, match=rf"degree {MAX_DEGREE + 1} x 1; at most degree {MAX_DEGREE}"):
        surface_from_dict(d)


# ------------------------------------------------------------------ whole messages, the tables' rows


@pytest.mark.parametrize(
    "d, message",
    [
        ("bezier", "surface must be a JSON object, got string"),
        ({"type": ["bezier"]}, 'surface "type" must be one of "bezier", "nurbs", got list'),
        ({"type": "b" * 50}, f'surface "type" must be one of "bezier", "nurbs", got \'{"b" * 37}...\''),
        ({**good_dict(), "zeta": 1, "alpha": 2}, "surface has unknown field 'alpha'"),
        ({**good_dict(), "description": None}, 'surface "description" must be a string, got null'),
        ({"type": "nurbs", "degree": [1, 1], "knots_v": []}, 'surface is missing the field "knots_u"'),
        ({"type": "bezier", "description": 1}, 'surface "description" must be a string, got number'),
        ({"type": "bezier"}, 'surface is missing the field "control_points"'),
        ({**good_dict(), "holes": [[[0.1, 0.1], [0.2, 0.1]]]}, "holes[0] needs at least 3 [u, v] points, got 2"),
        ({**good_dict(), "holes": "none"}, '"holes" must be a list of polylines, got string'),
    ],
)
def test_refusals_of_a_description_are_whole_lines(d, message):
    with pytest.raises(InvalidSurfaceError) as err:
        surface_from_dict(d)
    assert str(err.value) == message


def test_a_description_and_no_openings_are_accepted():
    s = surface_from_dict({**good_dict(), "description": "a test dome", "holes": []})
    assert surface_to_dict(s) == {**good_dict(), "holes": []}


def test_openings_round_trip_through_json():
    """A surface with openings is the chart perforated; its description gives it back, openings and all."""
    d = {
        **good_dict(),
        "holes": [[[0.2, 0.2], [0.4, 0.2], [0.3, 0.4]], [[0.6, 0.6], [0.8, 0.6], [0.8, 0.8], [0.6, 0.8]]],
    }
    s = surface_from_dict(d)
    assert type(s.chart) is BezierSurface and len(s.holes) == 2
    assert surface_to_dict(s) == {**d, "control_points": good_dict()["control_points"]}
    assert json.loads(json.dumps(surface_to_dict(s))) == d


def test_a_perforated_chart_of_no_json_type_is_named():
    from equimesh.surface.charts.openings import Perforated

    class Other(BezierSurface):
        pass

    with pytest.raises(TypeError, match="^no JSON surface type for Perforated$"):
        surface_to_dict(Perforated(Other(np.array(good_dict()["control_points"], dtype=float)), []))


def test_every_surface_type_reads_back_as_itself():
    from hostile_files import small_nurbs

    for d in (good_dict(), small_nurbs()):
        s = surface_from_dict(d)
        assert type(s) is SURFACE_TYPES[d["type"]].cls
        assert surface_to_dict(s)["type"] == d["type"]


def test_paths_are_read_whatever_the_case_of_their_extension(tmp_path):
    path = _file(tmp_path, json.dumps(good_dict()), "S.JSON")
    assert load_surface(path).degree == (1, 1)
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(tmp_path / "s.IGS")
    assert str(err.value) == (
        f"unknown surface file extension '.IGS' for {tmp_path / 's.IGS'}; use one of "
        "['.3dm', '.json', '.obj', '.ply', '.stl', '.vtk', '.vtu']"
    )


@pytest.mark.parametrize("choice", [0, "vault"])
def test_an_object_is_chosen_only_in_files_of_several_surfaces(tmp_path, monkeypatch, choice):
    """The choice reaches the reader of a format that holds several surfaces (0 is a choice); any other format
    refuses it, naming the formats that take one."""
    chosen = []
    fmt = INPUT_FORMATS[".3dm"]
    monkeypatch.setitem(
        INPUT_FORMATS, ".3dm", type(fmt)(fmt.name, lambda path, object: chosen.append(object), fmt.options)
    )
    monkeypatch.setitem(INPUT_FORMATS, ".step", type(fmt)("STEP file", lambda path, object: None, ("object",)))
    (tmp_path / "s.3dm").write_bytes(b"")
    load_surface(tmp_path / "s.3dm", object=choice)
    assert chosen == [choice]
    for name, kind in [("s.json", "equimesh surface JSON"), ("s.obj", "Wavefront OBJ triangle mesh")]:
        with pytest.raises(InvalidSurfaceError) as err:
            load_surface(tmp_path / name, object=choice)
        assert str(err.value) == (
            f"choosing an object applies to files with several surfaces (.3dm, .step), not to {kind} {tmp_path / name}"
        )


def test_unreadable_paths_are_named_whole(tmp_path):
    long = tmp_path / ("a" * 300 + ".json")
    for path, message in [
        (tmp_path / "missing.json", f"surface file not found: {tmp_path / 'missing.json'}"),
        (fifo(tmp_path / "pipe.json"), f"surface file is not a regular file: {tmp_path / 'pipe.json'}"),
        (long, f"cannot read surface file {shown_path(long)}: path too long"),
    ]:
        with pytest.raises(InvalidSurfaceError) as err:
            load_surface(path)
        assert str(err.value) == message
