"""The argument checks every verb shares (``equimesh/_checks.py``): the target length l and real numbers.

What must hold: l is one real, positive, finite number in the supported range (numpy scalars and 0-d arrays
included); anything else is refused with one line saying what it got.
"""

import re

import numpy as np
import pytest

import equimesh
from equimesh import InvalidLengthError, InvalidPolygonError
from equimesh._checks import check_length, real_array, real_number
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
