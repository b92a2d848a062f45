"""The argument checks every verb shares (``equimesh/_checks.py``): the target length l, real numbers, numbers as text.

What must hold: l is one real, positive, finite number in the supported range (numpy scalars and 0-d arrays
included); anything else is refused with one line saying what it got, an integer beyond the float range by its size
(never Python's OverflowError); a number typed as text is read only in its plain spellings.
"""

import fractions
import re

import numpy as np
import pytest

import equimesh
from equimesh import EquimeshError, InvalidLengthError, InvalidPolygonError
from equimesh._checks import (
    _beyond_floats,
    check_count,
    check_length,
    finite_rows,
    index_rows,
    number_text,
    plain_integer,
    real_array,
    real_number,
)
from equimesh.tolerance import MAX_LENGTH, MIN_LENGTH


@pytest.mark.parametrize("l", [MIN_LENGTH, MAX_LENGTH, np.float64(2.0), np.int64(3), np.array(0.5), np.float32(0.25)])
def test_lengths_at_the_ends_of_the_range_and_numpy_scalars_are_accepted(l):
    assert check_length(l) == float(l) and type(check_length(l)) is float


@pytest.mark.parametrize(
    "l, message",
    [
        (1 + 2j, "got complex value (1+2j)"),
        (np.complex128(2.0), "got complex value (2+0j)"),
        (np.array([1.0]), "got array([1.])"),
        ("1", "got '1'"),
    ],
)
def test_a_length_that_is_not_one_real_number_is_named(l, message):
    with pytest.raises(
        InvalidLengthError, match=r"^target length l must be a real number, " + re.escape(message) + "$"
    ):
        check_length(l)


SQUARE10 = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


@pytest.mark.parametrize("l", [5e-324, 1e-200, 1e200, 1.7e308])
def test_lengths_outside_the_range_are_refused(l):
    """Subnormal, tiny and huge l: InvalidLengthError from every verb, never a ZeroDivision/Overflow."""
    for verb in (
        equimesh.increment,
        equimesh.uniform_triangulation,
        equimesh.node_lower_bound,
        equimesh.best_lattice_placement,
    ):
        with pytest.raises(InvalidLengthError, match=r"outside the supported range"):
            verb(SQUARE10, l)


@pytest.mark.parametrize(
    "value, kind", [(True, "boolean True"), (np.bool_(False), "boolean False"), (1j, "complex value 1j")]
)
def test_non_real_lengths_are_named_by_their_kind(value, kind):
    """A boolean is a number to Python's numbers module; the message still says what it is."""
    with pytest.raises(equimesh.InvalidLengthError, match=f"must be a real number, got {kind}$"):
        equimesh.increment([[0, 0], [4, 0], [4, 4], [0, 4]], value)


def test_real_array_returns_floats():
    """Integers in, floats out: every later step computes in floating point."""
    out = real_array([[0, 1], [2, 3]], "x", InvalidPolygonError)
    assert out.dtype == float and out.tolist() == [[0.0, 1.0], [2.0, 3.0]]


def test_a_zero_dimensional_complex_array_is_named_complex():
    with pytest.raises(InvalidLengthError) as err:
        real_number(np.array(1j), "target length l", InvalidLengthError)
    assert str(err.value) == "target length l must be a real number, got complex value array(0.+1.j)"


def test_length_out_of_range_says_to_rescale():
    with pytest.raises(InvalidLengthError) as err:
        check_length(1e200)
    assert str(err.value) == (
        "target length l = 1e+200 is outside the supported range [1e-150, 1e+150]; rescale the coordinates"
    )


BEYOND_FLOATS = 10**400  # a Python int float() cannot hold: OverflowError, not ValueError, unless checked


@pytest.mark.parametrize(
    "call, fragment",
    [
        (lambda: equimesh.increment([[0, 0], [BEYOND_FLOATS, 0], [4, 4]], 1.0), "entry [1][0] is an integer of 401"),
        (lambda: equimesh.uniform_triangulation([[0, 0], [4, 0], [4, BEYOND_FLOATS]], 1.0), "entry [2][1]"),
        (lambda: equimesh.best_lattice_placement([[0, 0], [4, 0], [-BEYOND_FLOATS, 4]], 1.0), "entry [2][0]"),
        (lambda: equimesh.node_lower_bound([[BEYOND_FLOATS, 0], [4, 0], [4, 4]], 1.0), "entry [0][0]"),
        (lambda: equimesh.uniform_triangulation(SQUARE10, 1.0, offset=(0, BEYOND_FLOATS)), "offset must be real"),
        (lambda: equimesh.uniform_triangulation(SQUARE10, 1.0, angle=BEYOND_FLOATS), "angle must be a real number"),
        (
            lambda: equimesh.BezierSurface([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, BEYOND_FLOATS]]]),
            "entry [1][1][2] is an integer of 401 digits",
        ),
        (
            lambda: equimesh.NurbsSurface((1, 1), [0, 0, 1, BEYOND_FLOATS], [0, 0, 1, 1], np.zeros((2, 2, 3))),
            "knots_u must be real numbers within the float range, but entry [3]",
        ),
        (
            lambda: equimesh.TriangulatedSurface([[0, 0, 0], [1, 0, 0], [0, BEYOND_FLOATS, 0]], [[0, 1, 2]]),
            "entry [2][1]",
        ),
        *(
            (lambda verb=verb: verb(SQUARE10, BEYOND_FLOATS), "within the float range, got an integer of 401 digits")
            for verb in (
                equimesh.increment,
                equimesh.uniform_triangulation,
                equimesh.best_lattice_placement,
                equimesh.node_lower_bound,
            )
        ),
        (lambda: equimesh.length_classes([1.0], BEYOND_FLOATS), "target length l must be a real number within"),
    ],
)
def test_integers_beyond_the_float_range_are_refused_by_the_argument_checks(call, fragment):
    """A vertex, a coordinate, a knot or l = 10**400 is an EquimeshError naming the entry and its size."""
    with pytest.raises(equimesh.EquimeshError) as err:
        call()
    assert fragment in str(err.value) and "0000000000" not in str(err.value)


@pytest.mark.parametrize(
    "text, whole, value",
    [("2.5", False, 2.5), (" -1e3 ", False, -1000.0), (".5", False, 0.5), ("5.", False, 5.0), ("-inf", False, -np.inf)]
    + [("12", True, 12), ("+3", True, 3), ("-7", True, -7)],
)
def test_numbers_as_typed_are_read(text, whole, value):
    assert number_text(text, "x", EquimeshError, whole=whole) == value


@pytest.mark.parametrize(
    "text, whole, got",
    [
        ("1_0", False, "got '1_0'"),
        ("1_000", True, "got '1_000'"),
        ("\u0661\u0662", False, "got '\u0661\u0662'"),  # Arabic-Indic digits, which float() reads as 12
        ("0x10", True, "got '0x10'"),
        ("2.5", True, "got '2.5'"),
        ("", False, "got ''"),
        ("9" * 5000, True, "got a text of 5000 characters"),
    ],
)
def test_numbers_in_other_spellings_are_refused(text, whole, got):
    """Python's float() and int() read 1_0 as 10: a person who types it meant something else, or mistyped."""
    with pytest.raises(EquimeshError, match=f"^x must be a (whole )?number, {got}$"):
        number_text(text, "x", EquimeshError, whole=whole)


def test_counts_below_the_least_show_a_short_number():
    with pytest.raises(EquimeshError, match=r"^n must be an integer of at least 1, got an integer of 31 digits$"):
        check_count(-(10**30), "n")


def test_finite_rows_returns_floats_and_names_the_shape_and_the_row():
    """An (N, width) array of finite numbers comes back as floats; a wrong shape names the array, a row with a
    non-finite entry names that row by the caller's format."""
    rows = finite_rows([[1, 2], [3, 4]], 2, "points", "point {}", EquimeshError)
    assert rows.dtype == float and rows.tolist() == [[1.0, 2.0], [3.0, 4.0]]
    with pytest.raises(EquimeshError, match=r"^points must be an \(N, 2\) array, got shape \(1, 3\)$"):
        finite_rows([[1, 2, 3]], 2, "points", "point {}", EquimeshError)
    with pytest.raises(EquimeshError, match=r"^points must be an \(N, 2\) array, got shape \(2,\)$"):
        finite_rows([1, 2], 2, "points", "point {}", EquimeshError)
    with pytest.raises(EquimeshError, match=r"^point 1 is not finite: \[1\.0, inf\]$"):
        finite_rows([[0, 0], [1, np.inf], [np.nan, 0]], 2, "points", "point {}", EquimeshError)
    assert finite_rows([[1, 2]], 2, "points", "point {}", EquimeshError, (1, "node")).tolist() == [[1.0, 2.0]]
    with pytest.raises(EquimeshError, match=r"^points must have one row per node \(3\), got 2$"):
        finite_rows([[1, 2], [3, 4]], 2, "points", "point {}", EquimeshError, (3, "node"))


def test_index_rows_returns_int64_and_names_the_shape_and_the_row():
    """A (K, width) array of integers in 0 .. count - 1 comes back as int64 (an empty one as (0, width) whatever its
    dtype); other dtypes or shapes name the array, an index out of range its row, in the caller's dtype."""
    rows = index_rows(np.array([[0, 1], [1, 2]], dtype=np.uint8), 2, 3, "edges", "edge {}", "node", EquimeshError)
    assert rows.dtype == np.int64 and rows.tolist() == [[0, 1], [1, 2]]
    empty = index_rows([], 2, 3, "edges", "edge {}", "node", EquimeshError)
    assert empty.dtype == np.int64 and empty.shape == (0, 2)
    with pytest.raises(
        EquimeshError, match=r"^edges must be an \(M, 2\) array of node indices, got shape \(1, 2\) of fl"
    ):
        index_rows([[0.0, 1.0]], 2, 3, "edges", "edge {}", "node", EquimeshError)
    with pytest.raises(
        EquimeshError, match=r"^edges must be an \(M, 2\) array of node indices, got shape \(3,\) of int"
    ):
        index_rows([0, 1, 2], 2, 3, "edges", "edge {}", "node", EquimeshError)
    for row in ([0, 3], [-1, 0]):
        with pytest.raises(EquimeshError, match=rf"^edge 1 refers to a node outside 0 \.\. 2: \[{row[0]}, {row[1]}\]$"):
            index_rows([[0, 1], row, [0, 9]], 2, 3, "edges", "edge {}", "node", EquimeshError)
    wrapped = np.array([[0, 2**64 - 1]], dtype=np.uint64)  # -1 as uint64: out of range, not node -1
    with pytest.raises(EquimeshError, match=r"^edge 0 refers to a node outside 0 \.\. 2"):
        index_rows(wrapped, 2, 3, "edges", "edge {}", "node", EquimeshError)


def test_the_messages_of_the_number_checks_by_hand():
    """Up to 20 digits an integer is shown, beyond them counted; a count below its least is refused; a number as
    text is read as a float unless ``whole``, and a text of more than 40 characters is shown by its length."""
    assert plain_integer(10**20 - 1) == "9" * 20 and plain_integer(-(10**20 - 1)) == "-" + "9" * 20
    assert plain_integer(10**20) == "an integer of 21 digits"
    assert plain_integer(10**25 - 1) == "an integer of 25 digits" and plain_integer(10**25) == "an integer of 26 digits"
    assert _beyond_floats(10**400) == "an integer of 401 digits"
    assert _beyond_floats(fractions.Fraction(10**400, 3)) == "a number beyond it"
    assert check_count(1, "n") == 1
    with pytest.raises(EquimeshError, match=r"^n must be an integer of at least 1, got 0$"):
        check_count(0, "n")
    with pytest.raises(EquimeshError, match=r"^n must be an integer of at least 1, got 2\.5$"):
        check_count(np.float64(2.5), "n")
    assert number_text("2.5", "x", EquimeshError) == 2.5
    with pytest.raises(EquimeshError, match=r"^x must be a number, got 'a'$"):
        number_text("a", "x", EquimeshError)
    with pytest.raises(EquimeshError, match=r"^x must be a whole number, got '2\.5'$"):
        number_text("2.5", "x", EquimeshError, whole=True)
    forty = "1" * 39 + "x"
    with pytest.raises(EquimeshError, match=rf"^x must be a number, got '{forty}'$"):
        number_text(forty, "x", EquimeshError)
    with pytest.raises(EquimeshError, match=r"^x must be a number, got a text of 41 characters$"):
        number_text(forty + "x", "x", EquimeshError)
    with pytest.raises(EquimeshError, match=r"^x must be real numbers within the float range, but it is an integer of"):
        real_array(10**400, "x", EquimeshError)
    with pytest.raises(EquimeshError, match=r"^points must be an array of numbers$"):
        finite_rows("abc", 2, "points", "point {}", EquimeshError)
