"""Length classes: the fewest classes at a tolerance (greedy sweep), tolerance parsing, the schedule's round trip."""

import numpy as np
import pandas as pd
import pytest
from hypothesis import given
from hypothesis import strategies as st

from equimesh import G1, OTHER, EquimeshError, InvalidToleranceError, LengthClasses, length_classes
from equimesh.classes import CLASS_COLUMNS, DEFAULT_TOLERANCE, check_tolerance
from equimesh.io import classes_path, member_schedule, write_members


def test_known_classes():
    """Lengths 5.0 (twice), 5.06, 5.12, 5.18 at +-1 % of l = 5 (class width 0.1): {5, 5, 5.06}, {5.12, 5.18}."""
    c = length_classes([5.12, 5.0, 5.06, 5.18, 5.0], 5.0, 0.01)
    assert isinstance(c, LengthClasses) and len(c) == 2
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
    ],
)
def test_bad_tolerances_are_refused_in_one_line(bad, match):
    with pytest.raises(InvalidToleranceError, match=match) as info:
        length_classes([1.0], 1.0, bad)
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
