"""Conditional properties (tests/conditions.py, counted by tests/conftest.py): a test whose condition never held
fails, and so does one below its share.

The checks run in a pytest of their own (``pytester``, in a subprocess so that its ``conftest`` is not ours
already imported), plain, under pytest-xdist, and as two sessions in one process (as mutmut runs them).
"""

import sys
from pathlib import Path

import pytest
from conditions import unexercised

pytest_plugins = ["pytester"]

CASES = """
import pytest
from conditions import exercised
from hypothesis import given
from hypothesis import strategies as st


@given(st.integers(0, 10))
def test_never_held(n):
    exercised("n is negative", n < 0)


@pytest.mark.exercised("n is even", share=0.9)
@given(st.integers(0, 10))
def test_held_too_rarely(n):
    exercised("n is even", n % 2 == 0)


@pytest.mark.exercised("n is large", share=0.5)
def test_never_evaluated():
    pass


@pytest.mark.exercised("n is even", share=0.2)
@given(st.integers(0, 10))
def test_held_often_enough(n):
    exercised("n is even", n % 2 == 0)


@pytest.mark.parametrize("odd", [False, True])
@given(st.integers(0, 10))
def test_each_case_counts_on_its_own(odd, n):
    exercised("n has the parity asked", n % 2 == odd)
"""


def test_unexercised_names_what_never_held_and_what_held_too_rarely():
    counts = {"b held once": (5, 1), "a never held": (3, 0)}
    assert unexercised(counts, {}) == [
        "conditional property never exercised: 'a never held' never held in 3 evaluation(s)"
    ]
    assert unexercised(counts, {"b held once": 0.2}) == unexercised(counts, {})
    assert unexercised({"b": (5, 1)}, {"b": 0.5, "c": 0.1}) == [
        "condition 'b' held in 1 of 5 evaluations (20%), less than the 50% expected",
        "condition 'c' was never evaluated (expected to hold in 10% or more)",
    ]


@pytest.mark.parametrize("xdist", [[], ["-n", "2"]], ids=["one process", "pytest-xdist"])
def test_a_condition_never_held_or_held_too_rarely_fails_its_test(pytester, xdist):
    _cases(pytester)
    result = pytester.runpytest_subprocess("-p", "no:cacheprovider", "-p", "no:randomly", *xdist)
    result.assert_outcomes(passed=3, failed=3)
    result.stdout.fnmatch_lines_random(
        [
            "FAILED *::test_never_held - Failed: *",
            "FAILED *::test_held_too_rarely - Failed: *",
            "FAILED *::test_never_evaluated - Failed: *",
            "conditional property never exercised: 'n is negative' never held in * evaluation(s)",
            "condition 'n is even' held in * of * evaluations (*%), less than the 90% expected",
            "condition 'n is large' was never evaluated (expected to hold in 50% or more)",
        ]
    )
    assert "PytestUnknownMarkWarning" not in result.stdout.str()


def test_a_second_session_in_one_process_counts_as_the_first(pytester):
    """pytest imports the conftest anew for a second session while the test module stays imported: the counts are
    still those the hook reads, so a condition that held passes and one that never held fails, in both sessions."""
    _cases(pytester)
    pytester.makepyfile(
        run_twice="""
import sys
import pytest
args = ["-q", "-p", "no:cacheprovider", "-p", "no:randomly", "test_cases.py"]
sys.exit(10 * pytest.main(args) + pytest.main(args))
"""
    )
    result = pytester.run(sys.executable, "run_twice.py")
    assert result.ret == 11  # each session: tests failed (exit 1), the same three
    assert result.stdout.str().count("3 failed, 3 passed") == 2


def _cases(pytester):
    """The cases above with this folder's conftest and conditions."""
    here = Path(__file__).parent
    pytester.makeconftest((here / "conftest.py").read_text())
    pytester.makepyfile(conditions=(here / "conditions.py").read_text(), test_cases=CASES)
