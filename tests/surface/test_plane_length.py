"""How refusals of Section 4's steps 3-4 name the spacing Problem 2 meshed the plane at (``surface/plane_length.py``):
the caller's l as before, or the larger spacing of sound joints with a bound on the caller's l that keeps it below the
length at fault."""

from hypothesis import given
from hypothesis import strategies as st

from equimesh.errors import number
from equimesh.surface.plane_length import PlaneLength, round_down

lengths = st.floats(min_value=1e-6, max_value=1e6)
factors = st.floats(min_value=1.0, max_value=1.5, exclude_min=True)


@given(lengths, lengths)
def test_at_the_callers_l_a_refusal_reads_as_before(l, bound):
    length = PlaneLength.of(l)
    assert length == PlaneLength(l) and PlaneLength.of(length) is length
    assert length.value == l and str(length) == f"l = {number(l)}" and length.symbol == "l"
    assert length.suggest(bound) == bound


@given(lengths, factors, lengths)
def test_at_a_larger_spacing_a_refusal_names_it_and_suggests_an_l_that_keeps_it_below_the_bound(l, factor, bound):
    length = PlaneLength(l, factor)
    assert str(length) == f"the spacing {number(factor, 4)} l = {number(l * factor)} meshed for sound joints " + (
        f"(l = {number(l)})"
    )
    suggested = length.suggest(bound)
    assert suggested * factor <= bound and suggested >= bound / factor * (1 - 1e-3)


@given(st.floats(min_value=1e-300, max_value=1e300))
def test_round_down_keeps_four_digits_and_never_rounds_up(x):
    assert x * (1 - 1e-3) <= round_down(x) <= x
