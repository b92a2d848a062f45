"""Length classes: the fewest classes at a tolerance (greedy sweep), tolerance parsing, the schedule's round trip."""

import itertools
import re
import warnings

import numpy as np
import pandas as pd
import pytest
from hypothesis import given
from hypothesis import strategies as st

from equimesh import G1, OTHER, EquimeshError, InvalidToleranceError, LengthClasses, classes, length_classes
from equimesh.classes import (
    CLASS_COLUMNS,
    DEFAULT_TOLERANCE,
    catalogue_classes,
    check_catalogue,
    check_tolerance,
    holds,
)
from equimesh.errors import InvalidCatalogueError
from equimesh.io import classes_path, member_schedule, write_members


def test_known_classes():
    """Lengths 5.0 (twice), 5.06, 5.12, 5.18 at +-1 % of l = 5 (class width 0.1): {5, 5, 5.06}, {5.12, 5.18}."""
    c = length_classes([5.12, 5.0, 5.06, 5.18, 5.0], 5.0, 0.01)
    assert isinstance(c, LengthClasses) and len(c) == 2 and (c.length, c.tolerance) == (5.0, 0.01)
    assert c.member_class.tolist() == [1, 0, 0, 1, 0]
    assert c.count.tolist() == [3, 2]
    assert c.min.tolist() == [5.0, 5.12] and c.max.tolist() == [5.06, 5.18]
    np.testing.assert_allclose(c.nominal, [5.03, 5.15], rtol=0, atol=1e-15)
    table = c.table()
    assert tuple(table.columns) == CLASS_COLUMNS and table["class"].tolist() == [0, 1]


def test_one_length_is_one_class_and_no_member_no_class():
    c = length_classes(np.full(7, 2.5), 2.5, "0.5%")
    assert len(c) == 1 and c.count.tolist() == [7] and c.nominal.tolist() == [2.5]
    assert len(length_classes([], 2.5)) == 0


def test_members_exactly_a_class_width_apart_share_a_class():
    """The width is inclusive: 4.0 and 4.0 + 2 tol l (= 4.04 at 0.5 % of l = 4) are both within tol l of 4.02."""
    assert length_classes([4.0, 4.04], 4.0, 0.005).count.tolist() == [2]
    assert length_classes([4.0, 4.0401], 4.0, 0.005).count.tolist() == [1, 1]


lengths_in_l_2l = st.lists(st.floats(1.0, 2.0), min_size=1, max_size=80)


@given(x=lengths_in_l_2l, tol=st.sampled_from([0.001, 0.005, 0.01, 0.05, 0.2]))
def test_classes_are_valid_and_fewest(x, tol):
    """Every member is within tol l of its class's nominal length, and no grouping has fewer classes:
    the shortest members of the classes are pairwise more than 2 tol l apart, so no class can hold two."""
    l = 1.0
    c = length_classes(x, l, tol)
    x = np.asarray(x)
    assert c.count.sum() == x.size and np.bincount(c.member_class).tolist() == c.count.tolist()
    assert np.all(np.abs(x - c.nominal[c.member_class]) <= tol * l * (1 + 1e-12))
    np.testing.assert_array_equal(c.min[c.member_class] <= x, True)
    np.testing.assert_array_equal(x <= c.max[c.member_class], True)
    assert np.all(np.diff(c.min) > 2 * tol * l)
    order = np.argsort(x, kind="stable")
    assert np.all(np.diff(c.member_class[order]) >= 0)  # ids increase with length


@given(x=lengths_in_l_2l)
def test_grouping_is_deterministic_and_ignores_member_order(x):
    """The classes depend on the multiset of lengths only; each member keeps its class when the list is reversed."""
    a, b = length_classes(x, 1.0), length_classes(x[::-1], 1.0)
    np.testing.assert_array_equal(a.member_class, b.member_class[::-1])
    np.testing.assert_array_equal(a.nominal, b.nominal)


@pytest.mark.parametrize(
    "given, value",
    [("0.5%", 0.005), (" 1 % ", 0.01), ("0.005", 0.005), (0.02, 0.02), ("49.9%", 0.499), (np.float64(0.1), 0.1)],
)
def test_tolerance_forms(given, value):
    assert check_tolerance(given) == pytest.approx(value, rel=1e-15)


@pytest.mark.parametrize(
    "bad, match",
    [
        ("0", "above 0"),
        ("0%", "above 0"),
        ("-1%", "above 0"),
        ("50%", "below 50%"),
        ("0.5", "below 50%"),
        ("75%", "below 50%"),
        ("nan", "above 0"),
        ("inf%", "above 0"),
        ("abc", "a number"),
        ("%", "a number"),
        ("", "a number"),
        (None, "must be a real number, got None"),
        (True, "must be a real number, got boolean True"),
        (10**400, "within the float range, got an integer of 401 digits"),
        ("1_0%", "a number such as 0.005 or a percentage such as 0.5%, got .1_0%."),
        ("0.5 %%", "a number such as"),
        (-0.001, "got -0.001"),
        ("1e400", "above 0"),
        ("75%", "below 50% of l, got 75%$"),
        (1, r"below 50% of l, got 1\.0$"),
        (np.float64(0.75), r"below 50% of l, got 0\.75$"),
    ],
)
def test_bad_tolerances_are_refused_in_one_line(bad, match):
    """A text is shown as given, a number as the float read from it."""
    with pytest.raises(InvalidToleranceError, match=match) as info:
        length_classes([1.0], 1.0, bad)
    assert str(info.value).startswith("tolerance must be ")
    assert "\n" not in str(info.value) and "np." not in str(info.value)


@pytest.mark.parametrize(
    "lengths, fragment",
    [
        ([1, np.nan, 1.001, np.inf, -5], "length 1 is nan"),
        ([1, 1.001, np.inf], "length 2 is inf"),
        ([1, -5], "length 1 is -5.0"),
        ([0.0, 1], "length 0 is 0.0"),
        ([1, 10**400], "entry [1] is an integer of 401 digits"),
        (["a", 1], "member lengths must be an array of numbers"),
    ],
)
def test_lengths_that_are_no_member_are_refused(lengths, fragment):
    """A NaN, infinite, negative or zero length would make a class of its own with that nominal length."""
    with pytest.raises(EquimeshError) as info:
        length_classes(lengths, 1.0, 0.005)
    assert fragment in str(info.value) and "\n" not in str(info.value)


def test_schedule_and_classes_round_trip(tmp_path):
    """The written schedule reads back to the same bits, and regrouping its lengths gives its class column
    and the classes CSV exactly."""
    rng = np.random.default_rng(7)
    points = rng.uniform(0.0, 3.0, size=(40, 3))
    edges = np.array([(i, j) for i in range(40) for j in range(i + 1, 40) if (i * 7 + j) % 11 == 0])
    groups = np.where(np.arange(len(edges)) % 3 == 0, G1, OTHER)
    path = tmp_path / "s.csv"
    write_members(path, points, edges, groups, 1.5, tolerance="1%")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.classes.csv", "s.csv"]
    assert classes_path(path) == tmp_path / "s.classes.csv"

    read = pd.read_csv(path)
    expected = member_schedule(
        points,
        edges,
        groups,
        1.5,
        length_classes(np.linalg.norm(points[edges[:, 1]] - points[edges[:, 0]], axis=1), 1.5, 0.01),
    )
    pd.testing.assert_frame_equal(read, expected, check_exact=True)

    again = length_classes(read["length"].to_numpy(), 1.5, 0.01)
    np.testing.assert_array_equal(again.member_class, read["class"].to_numpy())
    pd.testing.assert_frame_equal(pd.read_csv(classes_path(path)), again.table(), check_exact=True)


def test_default_tolerance_is_valid():
    assert check_tolerance(DEFAULT_TOLERANCE) == DEFAULT_TOLERANCE


def test_catalogue_classes_of_known_lengths():
    """Stock lengths 5 and 6 at +-1 % of l = 5 (+-0.05): 5.0, 5.04 to 5; 6.03 to 6; 5.5 and 5.52 are off the catalogue,
    one class of their own."""
    c = catalogue_classes([5.0, 5.5, 6.03, 5.04, 5.52], 5.0, [6.0, 5.0], 0.01)
    assert c.count.tolist() == [2, 1, 2] and c.stock.tolist() == [True, True, False]
    assert c.member_class.tolist() == [0, 2, 1, 0, 2]
    np.testing.assert_allclose(c.nominal, [5.0, 6.0, 5.51], rtol=0, atol=1e-15)
    assert c.min.tolist() == [5.0, 6.03, 5.5] and c.max.tolist() == [5.04, 6.03, 5.52]
    assert (c.length, c.tolerance) == (5.0, 0.01)
    assert c.off_catalogue() == 2 and c.table()["stock"].tolist() == ["yes", "yes", "no"]
    assert length_classes([5.0], 5.0).off_catalogue() == 0


def test_catalogue_classes_of_integer_lengths_and_of_none():
    """Lengths given as integers are grouped as the same floats; no member, no class."""
    c = catalogue_classes([5, 6, 7, 5], 5.0, [5.0, 6.0], 0.01)
    assert c.member_class.tolist() == [0, 1, 2, 0] and c.count.tolist() == [2, 1, 1]
    assert c.nominal.dtype == c.min.dtype == c.max.dtype == float
    assert c.table().to_csv(index=False).splitlines()[1:] == [
        "0,2,5.0,5.0,5.0,yes",
        "1,1,6.0,6.0,6.0,yes",
        "2,1,7.0,7.0,7.0,no",
    ]
    on = catalogue_classes([6, 5], 5.0, [5.0, 6.0], 0.01)
    assert on.table().to_csv(index=False).splitlines()[1:] == ["0,1,5.0,5.0,5.0,yes", "1,1,6.0,6.0,6.0,yes"]
    empty = catalogue_classes([], 5.0, [5.0, 6.0], 0.01)
    assert len(empty) == 0 and empty.member_class.size == 0 and empty.off_catalogue() == 0


def test_members_off_the_catalogue_are_grouped_at_the_tolerance():
    """5.5 and 5.58 are 0.08 apart: one class at +-1 % of l = 5 (width 0.1), two at +-0.5 % (width 0.05)."""
    assert catalogue_classes([5.5, 5.58, 5.0], 5.0, [5.0], 0.01).count.tolist() == [1, 2]
    assert catalogue_classes([5.5, 5.58, 5.0], 5.0, [5.0], 0.005).count.tolist() == [1, 1, 1]


def test_a_member_exactly_the_tolerance_from_a_stock_length_is_on_it():
    """At l = 1 and a tolerance of 1/4 (exact in binary), 1.75 is 1/4 from the stock length 1.5: on the catalogue."""
    c = catalogue_classes([1.75, np.nextafter(1.75, 2.0)], 1.0, [1.5], 0.25)
    assert c.stock.tolist() == [True, False] and c.member_class.tolist() == [0, 1]


def test_top_share():
    """Classes of 3, 2, 1 and 1 members: the largest holds 3 of 7, the two largest 5, all of them every member."""
    c = length_classes([1.0, 1.0, 1.0, 1.2, 1.2, 1.4, 1.6], 1.0, 0.01)
    assert c.count.tolist() == [3, 2, 1, 1]
    assert [c.top_share(k) for k in (1, 2, 4, 10)] == [3 / 7, 5 / 7, 1.0, 1.0] and c.top_share() == 1.0
    assert length_classes(np.linspace(1.0, 1.99, 12), 1.0, 0.001).top_share() == 10 / 12
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no 0 / 0
        assert np.isnan(length_classes([], 1.0).top_share())


@pytest.mark.parametrize(
    "catalogue, message",
    [
        ([], "lengths: the catalogue is empty; give at least one stock length in [l, 2l]"),
        ("", "lengths must be numbers separated by commas, such as 5,5.8,7.1, got ''"),
        ("5,x", "lengths must be numbers separated by commas, such as 5,5.8,7.1, got '5,x'"),
        ([5.0, None], "lengths must be numbers separated by commas, such as 5,5.8,7.1, got [5.0, None]"),
        (5.0, "lengths must be numbers separated by commas, such as 5,5.8,7.1, got 5.0"),
        ([4.9], "lengths: 4.9 is outside [l, 2l] = [5, 10]"),
        ([6.0, 10.2], "lengths: 10.2 is outside [l, 2l] = [5, 10]"),
        ([np.nan], "lengths: nan is outside [l, 2l] = [5, 10]"),
    ],
)
def test_bad_catalogues_are_refused(catalogue, message):
    ending = "; every stock length must be a member length the mesh may have" if "outside" in message else ""
    with pytest.raises(InvalidCatalogueError, match="^" + re.escape(message + ending) + "$"):
        check_catalogue(catalogue, 5.0)


def test_catalogue_is_sorted_once():
    assert check_catalogue("6, 5,6", 5.0).tolist() == [5.0, 6.0]


@pytest.mark.parametrize(
    "total, expected",
    [(0.0, True), (5.05, True), (10.0, True), (11.1, True), (16.1, True), (16.2, False), (9.0, False), (4.0, False)],
)
def test_holds_sums_of_stock_lengths(total, expected):
    """Stock 5 and 6 at +-1 % of l = 5: one member in [4.95, 5.05] or [5.95, 6.05]; two in [9.9, 10.1], [10.9, 11.1]
    or [11.9, 12.1]; three in [14.85, 15.15], [15.85, 16.15], ...: 16.2 and 9.0 fall between, 4.0 below all."""
    assert holds(total, [5.0, 6.0], 5.0, 0.01) is expected


def _sums_hold(total, stock, l, tolerance):
    """``holds`` by enumeration: some multiset of stock lengths whose sums of the widened lengths bracket ``total``."""
    low = min(stock) - tolerance * l
    for m in range(int(total // low) + 2):
        for chosen in itertools.combinations_with_replacement(stock, m):
            if sum(c - tolerance * l for c in chosen) <= total <= sum(c + tolerance * l for c in chosen):
                return True
    return False


#: Stock lengths, tolerances and totals in sixty-fourths of l = 4: every sum is exact, ends included.
dyadic_stock = st.lists(st.integers(64, 128), min_size=1, max_size=3, unique=True).map(
    lambda k: [4.0 * i / 64 for i in k]
)
dyadic_tolerances = st.sampled_from([1 / 64, 1 / 16, 1 / 8, 1 / 4])
dyadic_totals = st.integers(-8, 64 * 5).map(lambda k: 4.0 * k / 64)


@given(total=dyadic_totals, stock=dyadic_stock, tolerance=dyadic_tolerances)
def test_holds_is_the_sums_of_stock_lengths(total, stock, tolerance):
    assert holds(total, stock, 4.0, tolerance) is _sums_hold(total, stock, 4.0, tolerance)


@given(total=dyadic_totals, stock=dyadic_stock, tolerance=dyadic_tolerances, cap=st.integers(1, 3))
def test_holds_errs_towards_holds_beyond_the_interval_cap(total, stock, tolerance, cap):
    """With the sums merged into at most ``cap`` intervals a total that some members add up to still holds."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(classes, "MAX_SUM_INTERVALS", cap)
        capped = holds(total, stock, 4.0, tolerance)
    assert capped or not _sums_hold(total, stock, 4.0, tolerance)


@pytest.mark.parametrize(
    "cap, total, expected",
    [(3, 2.125, False), (2, 2.125, True), (1, 2.125, True), (3, 2.625, False), (2, 2.625, False), (1, 2.625, True)]
    + [(1, 1.984375, True), (1, 1.85, False)],
)
def test_the_interval_cap_closes_the_narrowest_gaps(cap, total, expected, monkeypatch):
    """Stock 1, 1.25 and 1.75 at +-1/64 of l = 1: one member in A = [0.984375, 1.015625], B = [1.234375, 1.265625]
    or C = [1.734375, 1.765625] (gaps of 0.21875 and 0.46875), two in [1.96875, 2.03125] (A + A), [2.21875,
    2.28125] (A + B), [2.46875, 2.53125] (B + B), [2.71875, 2.78125] (A + C) or from 2.96875 up: 2.125 and 2.625
    are no sum.  Kept in two intervals, the members' lengths close the narrower gap, A to B, and [A, B] + [A, B]
    holds 2.125, not 2.625; kept in one, [A, C] + [A, C] = [1.96875, 3.53125] holds both (and 1.984375 from its
    start).  1.85 lies beyond every length of one member and below every sum of two."""
    monkeypatch.setattr(classes, "MAX_SUM_INTERVALS", cap)
    assert holds(total, [1.0, 1.25, 1.75], 1.0, 1 / 64) is expected


@pytest.mark.parametrize("cap, expected", [(3, False), (2, True), (1, True)])
def test_the_interval_cap_closes_equal_gaps_together(cap, expected, monkeypatch):
    """Stock 1, 1.25 and 1.5 at +-1/64 of l = 1: one member in [0.984375, 1.015625], [1.234375, 1.265625] or
    [1.484375, 1.515625], two gaps of 0.21875.  Kept in two intervals, both gaps close: [0.984375, 1.515625] twice
    holds 2.125, which no two members add up to (A + A ends at 2.03125, A + B starts at 2.21875)."""
    monkeypatch.setattr(classes, "MAX_SUM_INTERVALS", cap)
    assert holds(2.125, [1.0, 1.25, 1.5], 1.0, 1 / 64) is expected


@pytest.mark.parametrize("cap, expected", [(3, False), (2, False), (1, True)])
def test_the_interval_cap_closes_gaps_by_their_width(cap, expected, monkeypatch):
    """Stock 1, 1.25 and 1.46875 to 1.53125 in steps of 1/32 at +-1/64 of l = 1: one member in A = [0.984375,
    1.015625], B = [1.234375, 1.265625] or C = [1.453125, 1.546875], gaps of 0.21875 and 0.1875 (though B ends
    0.25 after A and C 0.28125 after B).  Two intervals close the gap B to C, so that no two members add up to
    2.125 (A + A ends at 2.03125, A + B starts at 2.21875); one interval does."""
    monkeypatch.setattr(classes, "MAX_SUM_INTERVALS", cap)
    assert holds(2.125, [1.0, 1.25, 1.46875, 1.5, 1.53125], 1.0, 1 / 64) is expected


def test_holds_at_the_ends_of_the_sums():
    """Stock 1.5 at +-1/4 of l = 1: sums of two members in [2.5, 3.5], ends included, of three from 3.75."""
    assert [holds(t, [1.5], 1.0, 0.25) for t in (1.25, 2.5, 3.5, 3.75)] == [True, True, True, True]
    assert holds(0.75, [0.75], 0.5, 0.25)  # one member of at most 1: l = 0.5
    assert [holds(t, [1.5], 1.0, 0.25) for t in (np.nextafter(2.5, 0.0), np.nextafter(3.5, 4.0))] == [False, False]


def test_the_union_of_sums_holds_an_interval_inside_another():
    """The sums' intervals widen with the sum, so one can lie inside another: [1, 2] and [5, 6] inside [0, 10] are
    one interval, [0, 10], and [12, 13] stays apart."""
    union = classes._merge(np.array([[0.0, 10.0], [1.0, 2.0], [5.0, 6.0], [12.0, 13.0]]))
    np.testing.assert_array_equal(union, [[0.0, 10.0], [12.0, 13.0]])


def test_the_largest_classes_come_largest_first_and_of_equals_the_shorter():
    """Counts 2, 3, 3, 1 (classes in increasing length): the largest are class 1, then 2 (as large, longer), then 0;
    all four for k None; the share in the two largest is 6 of 9."""
    found = length_classes([1.0, 1.0, 1.1, 1.1, 1.1, 1.2, 1.2, 1.2, 1.5], 1.0, 0.005)
    np.testing.assert_array_equal(found.count, [2, 3, 3, 1])
    np.testing.assert_array_equal(found.largest(3), [1, 2, 0])
    np.testing.assert_array_equal(found.largest(None), [1, 2, 0, 3])
    assert found.top_share(2) == 6 / 9


def test_the_largest_of_many_equal_classes_keep_their_order():
    """83 classes, three of 2 members among 80 of one: the three first, in order of length, then the first of the
    others; a sort that does not keep the order of equals (numpy's default) gives another."""
    lengths = np.concatenate([1.0 + 0.02 * np.arange(40), np.repeat(1.9, 2), np.repeat(1.92, 2), np.repeat(1.94, 2)])
    found = length_classes(np.concatenate([lengths, 2.0 + 0.02 * np.arange(40)]), 1.0, 0.005)
    assert len(found) == 83 and list(found.count[40:43]) == [2, 2, 2]
    np.testing.assert_array_equal(found.largest(8), [40, 41, 42, 0, 1, 2, 3, 4])
