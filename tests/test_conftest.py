"""The note on conditional properties (tests/conftest.py): a condition reached but never held is listed."""

from conftest import _CONDITIONS, exercised, never_exercised
from hypothesis import assume, given
from hypothesis import strategies as st


def test_never_exercised_lists_only_conditions_that_never_held():
    lines = never_exercised({"b held once": (5, 1), "a never held": (3, 0)})
    assert lines == ["a never held: never held in 3 evaluation(s)"]


@given(st.integers(0, 10))
def test_exercised_counts_and_passes_the_condition_through(n):
    before = tuple(_CONDITIONS["test_conftest: n is even"])
    assume(exercised("test_conftest: n is even", n % 2 == 0))
    reached, held = _CONDITIONS["test_conftest: n is even"]
    assert n % 2 == 0 and (reached, held) == (before[0] + 1, before[1] + 1)
