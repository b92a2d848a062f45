"""The Step 2 points of each side (``planar/boundary/sides.py``): equal parts, staggered points at sharp corners,
the search for short sides and the grid search of the corners left closer than l.

What must hold: every part is in [l, 2l] (up to REL_TOL), whatever the corner angles and however short the
sides (down to l); the stagger is K = ceil(1 / sin angle) points l apart on alternating sides; the searches
are pinned by hand and by fingerprints on fixed rings, each step shown to decide the output.
"""

import math

import numpy as np
import pytest
from corner_sampling import at
from hypothesis import given
from hypothesis import strategies as st

import equimesh
from equimesh.planar.boundary import chain, corner
from equimesh.planar.boundary import sides as boundary_sides
from equimesh.planar.boundary.sides import (
    corner_gap,
    grid_chain,
    place,
    side_positions,
    split_counts,
    stagger,
    stagger_count,
    stagger_reach,
)
from equimesh.planar.boundary.sides import sharp_run as _run
from equimesh.planar.polygon import as_polygon
from equimesh.testing.shapes import sharp_dart
from equimesh.tolerance import REL_TOL, at_least

# Step 2 by hand: (l, spacing, edge length L, parts k).  k = ceil(L / (spacing l)) kept in
# [ceil(L / 2l), floor(L / l)], each bound up to REL_TOL; l = 2 tells l from 1 / l.
SPLIT_COUNTS = [
    (1.0, 2.0, 1.0, 1),  # shorter than 2l: one part
    (1.0, 2.0, 2.0, 1),  # exactly 2l: still one part
    (1.0, 2.0, 4.0, 2),  # exactly 4l: two parts of 2l, not three
    (1.0, 2.0, 4.0 * (1.0 + 0.5 * REL_TOL), 2),  # 2l up to REL_TOL
    (1.0, 2.0, 4.0 * (1.0 + 2.0 * REL_TOL), 3),
    (2.0, 2.0, 8.0, 2),
    (1.0, 1.5, 3.0, 2),  # the spacing decides: parts of 1.5 l
    (2.0, 1.5, 6.0, 2),
    (1.0, 1.5, 4.0, 3),
    (1.0, 3.0, 5.0, 3),  # spacing above 2: the lower bound ceil(L / 2l) decides
    (1.0, 0.5, 3.0, 3),  # spacing below 1: the upper bound floor(L / l) decides
    (2.0, 0.5, 6.0, 3),
    (1.0, 0.5, 3.0 * (1.0 - 0.5 * REL_TOL), 3),  # parts of l up to REL_TOL
    (1.0, 0.5, 3.0 * (1.0 - 2.0 * REL_TOL), 2),
]


@pytest.mark.parametrize("l, spacing, length, parts", SPLIT_COUNTS)
def test_split_counts_by_hand(l, spacing, length, parts):
    """Step 2: the number of equal parts of a boundary edge, each part in [l, 2l] (up to REL_TOL)."""
    assert split_counts([length], l, spacing).tolist() == [parts]
    assert split_counts([length], l, spacing).dtype.kind == "i"  # counts, for arange and repeat
    if spacing == 2.0:
        assert split_counts([length], l).tolist() == [parts]  # 2 is the default (Problem 1)


@given(
    st.lists(st.tuples(st.floats(1.0, 12.0), st.floats(5.0, 355.0)), min_size=3, max_size=6),
    st.sampled_from([1.0, 1.5, 2.0]),
)
def test_step2_parts_stay_in_l_2l_on_sides_too_short_for_their_stagger(ring, spacing):
    """docs/proofs.md, "Sharp corners": whatever the corner angles and however short the sides (down to l),
    every side's Step 2 points start at its first corner, increase, and leave parts in [l, 2l]."""
    lengths, angles = map(list, zip(*ring))
    for length, (num, den) in zip(lengths, side_positions(lengths, angles, 1.0, spacing)):
        at = np.append(num / den * length, length)
        assert at[0] == 0.0
        parts = np.diff(at)
        assert parts.min() >= 1.0 - 1e-9 and parts.max() <= 2.0 + 1e-9, (length, at)


@given(
    st.floats(1.0, 59.9),
    st.lists(st.floats(1.0, 2.0), min_size=1, max_size=8),
    st.lists(st.floats(1.0, 2.0), min_size=1, max_size=8),
)
def test_the_closest_pair_of_a_corner_pairs_each_point_with_the_next_one_across(angle, parts_a, parts_b):
    """The pairing lemma (docs/proofs.md, "Sharp corners"): the closest pair of points on the two sides of a
    corner pairs some point with the first point of the other side at least as far from the corner; and
    ``corner_gap`` is that distance whenever it is below l."""
    a, b = np.cumsum(parts_a), np.cumsum(parts_b)
    t = math.radians(angle)

    def chord(p, q):
        return np.sqrt(np.maximum(p**2 + q**2 - 2.0 * p * q * math.cos(t), 0.0))

    nearest = chord(a[:, None], b[None, :]).min()
    paired = np.inf
    for p, q in ((a, b), (b, a)):
        j = np.searchsorted(q, p)  # the first point of the other side at least as far from the corner
        paired = min(paired, chord(p[j < len(q)], q[j[j < len(q)]]).min(initial=np.inf))
    assert paired == pytest.approx(nearest, rel=1e-12)
    sides = [(np.append(0.0, a[:-1]) / a[-1], 1.0), (np.append(0.0, b[-1] - b[::-1][1:]) / b[-1], 1.0)]
    gap = corner_gap(sides, np.array([a[-1], b[-1]]), [angle, 360.0 - angle], 1.0, 0)
    assert min(gap, 1.0) == pytest.approx(min(nearest, 1.0), rel=1e-9)


# --------------------------------------------------------------------------- Step 2 at sharp corners, by hand


@pytest.mark.parametrize(
    "angle, count",
    [
        (10.0, 6),  # 1 / sin 10 = 5.76
        (30.0, 2),  # 1 / sin 30 rounds to 2.0000000000000004: K = 2 only with the (1 - REL_TOL)
        (59.0, 2),
        (60.0 * (1.0 - 2.0 * REL_TOL), 2),  # sharp up to REL_TOL
        (60.0 * (1.0 - REL_TOL), 0),  # exactly at the tolerance: not sharp
        (60.0, 0),
        (90.0, 0),
    ],
)
def teststagger_count_and_reach_by_hand(angle, count):
    """K = ceil(1 / sin angle) staggered points below SHARP_CORNER = 60 degrees (up to REL_TOL), K l from the corner."""
    assert stagger_count(angle) == count
    assert stagger_reach(angle, 2.0) == 2.0 * count


# 2 k sin(angle / 2) for k = 2 at these angles: exactly 1 + REL_TOL (found by stepping through the floats
# next to 2 asin((1 + REL_TOL) / 4)), and 1 up to rounding (2 asin(1 / 4)).
AT_BOTH = 28.955024401447265


BELOW_BOTH = math.degrees(2.0 * math.asin(0.25))


@pytest.mark.parametrize(
    "angle, l, reach, leaving, arriving",
    [
        (10.0, 2.0, 100.0, [2, 6, 10, 12], [4, 8, 12]),  # K = 6; 2 k sin 5 >= 1 from k = 6 on: 6 l on both sides
        (10.0, 2.0, 5.0, [2, 6], [4]),  # floor(reach / l) + 1 = 3 points
        (10.0, 2.0, 4.0, [2, 6], [4]),
        (10.0, 2.0, 3.99, [2], [4]),
        (AT_BOTH, 1.0, 100.0, [1, 2, 3], [2, 3]),  # K = 3; k = 2 exactly at 1 + REL_TOL: on both sides
        (BELOW_BOTH, 1.0, 100.0, [1, 3], [2, 3]),
        (60.0, 1.0, 100.0, [], []),
    ],
)
def test_stagger_by_hand(angle, l, reach, leaving, arriving):
    """``stagger``: the points k l, k = 1 .. min(K, floor(reach / l) + 1), odd k leaving the corner, even k
    arriving, and both where the two points k l are l apart already (2 k sin(angle / 2) >= 1, up to REL_TOL)."""
    assert 4.0 * math.sin(math.radians(AT_BOTH) / 2.0) == 1.0 + REL_TOL
    assert 4.0 * math.sin(math.radians(BELOW_BOTH) / 2.0) < 1.0 + REL_TOL / 2.0
    out = stagger(angle, l, reach)
    assert [x.tolist() for x in out] == [leaving, arriving]


@pytest.mark.parametrize(
    "length, start, end, points, denominator",
    [
        # both chains end at 3: the start chain gives way first, its 3 dropped; middle 1 .. 2 (one part)
        (5.0, [1.0, 3.0], [2.0, 3.0], [0, 1, 2, 3], 5.0),
        # no point from the first corner: the middle 0 .. 1.5 is long enough, the point 2 from the end stays
        (3.5, [], [2.0], [0, 1.5], 3.5),
        # 6 = 6 (start first), 6 > 4, 5 > 4, 4 > 3, then 7 - 3 - 2 = 2 >= l: one part between 3 and 5
        (7.0, [1.0, 3.0, 5.0, 6.0], [2.0, 4.0, 6.0], [0, 1, 3, 5], 7.0),
        # middle 12 .. 20 split into 2 parts of 4 (spacing 2, l = 2)
        (20.0, [2.0, 6.0, 10.0, 12.0], [], [0, 2, 6, 10, 12, 16], 20.0),
        # one chain empty: the other gives way, whatever l (here 1 and 0.5)
        (1.5, [], [1.0], [0], 1.0),
        (0.75, [0.5], [], [0], 1.0),
    ],
)
def test_place_drops_the_farthest_staggered_point_until_the_middle_is_l(length, start, end, points, denominator):

    l = {20.0: 2.0, 0.75: 0.5}.get(length, 1.0)
    num, den = place(length, np.array(start), np.array(end), l, 2.0)
    assert num.tolist() == points and den == denominator


def test_side_positions_by_hand():
    """A ring of sides 20, 3, 20 with a 10 degree corner at 0: its stagger (K = 6, reach 20) leaving
    [1, 3, 5, 6], arriving [2, 4, 6], the rest in parts of 2 (l = 1) or 4 (l = 2); the short side alone."""
    for l, expected in [
        (
            1.0,
            [
                ([0, 1, 3, 5, 6, 8, 10, 12, 14, 16, 18], 20.0),
                ([0, 1], 2.0),
                ([0, 2, 4, 6, 8, 10, 12, 14, 16, 18], 20.0),
            ],
        ),
        (2.0, [([0, 2, 6, 10, 12, 16], 20.0), ([0], 1.0), ([0, 4, 8, 12, 16], 20.0)]),
    ]:
        sides = side_positions([20.0, 3.0, 20.0], [10.0, 85.0, 85.0], l)
        assert [(num.tolist(), float(den)) for num, den in sides] == expected


def test_corner_gap_reads_only_the_points_within_k_l():
    """A 10 degree corner (K = 6) at l = 2: points at 2 and 6 on one side, 4 on the other, within K l = 12, give the
    gap |c(2) - c(4)|; points from K l on are at least l from the whole other side and are left out."""
    lengths, angles = np.array([20.0, 20.0]), [10.0, 350.0]
    sides = [(np.array([0.0, 2.0, 6.0]), 20.0), (np.array([0.0, 16.0]), 20.0)]
    expected = math.sqrt(4.0 + 16.0 - 16.0 * math.cos(math.radians(10.0)))
    assert corner_gap(sides, lengths, angles, 2.0, 0) == pytest.approx(expected, rel=1e-12)
    far = [(np.array([0.0, 12.0]), 20.0), (np.array([0.0, 8.0]), 20.0)]  # 12 = K l on one side, 12 on the other
    assert corner_gap(far, lengths, angles, 2.0, 0) == math.inf
    assert corner_gap(sides, lengths, [60.0, 300.0], 2.0, 0) == math.inf  # not sharp


def _fingerprint(lengths, angles, l, spacing):
    """``side_positions`` of a ring, its parts checked in [l, 2l]: (number of points, sum of i times the i-th
    position)."""
    points = []
    for length, (num, den) in zip(lengths, side_positions(lengths, angles, l, spacing)):
        ends = np.append(num / den * length, length)
        assert np.all(np.diff(ends) >= (1.0 - 1e-9) * l) and np.all(np.diff(ends) <= (2.0 + 1e-9) * l)
        points.extend(ends[:-1])
    return len(points), math.fsum(
        float(x) * k for k, x in enumerate(np.round(points, 9), start=1)
    )  # exactly rounded: no BLAS order


def test_short_side_search_fingerprint():
    """The search for short sides and the grid search after it (docs/proofs.md, "Sharp corners") on 60 fixed
    rings of 3 to 5 sides of 1 to 8 l and corners of 5 to 70 degrees, at both spacings: every part in [l, 2l], and
    its output pinned by two sums (a fingerprint, as in dmsh's tests; a change to the search changes them)."""
    rng = np.random.default_rng(11)
    count, weighted = 0, 0.0
    for _ in range(60):
        n = int(rng.integers(3, 6))
        lengths, angles = np.round(rng.uniform(1.0, 8.0, n), 2), np.round(rng.uniform(5.0, 70.0, n), 1)
        for spacing in (1.5, 2.0):
            c, w = _fingerprint(lengths, angles, 1.0, spacing)
            count, weighted = count + c, weighted + w
    assert (count, round(weighted, 6)) == (1498, 22813.755)


# Rings on which a step of the search decides the output (each found by changing that step, mutation testing):
# a staggered point exactly at a side's end (8 = 8 l), the neighbours marked again after a change, the corners
# compared after a trial, the sides near a mirrored corner, the chain of a non-sharp corner at l = 1.5 and 0.5.
SEARCH_RINGS = [
    ([3.0, 8.0, 2.0, 8.0, 7.0], [29.3, 36.0, 48.3, 7.1, 40.2], 1.0, 2.0, (20, 590.0)),
    ([3.0, 8.0, 2.0, 1.0, 3.0], [61.3, 18.2, 63.0, 61.4, 4.2], 1.0, 2.0, (11, 98.0)),
    ([7.0, 1.0, 5.0, 3.0], [18.4, 7.2, 39.3, 32.6], 1.0, 2.0, (11, 108.0)),
    ([4.61, 3.0, 1.38, 3.68, 3.86], [6.0, 6.3, 69.9, 46.7, 18.7], 1.0, 1.5, (12, 82.72)),
    ([4.61, 3.0, 1.38, 3.68, 3.86], [6.0, 6.3, 69.9, 46.7, 18.7], 1.5, 1.5, (12, 124.08)),
    ([4.61, 3.0, 1.38, 3.68, 3.86], [6.0, 6.3, 69.9, 46.7, 18.7], 0.5, 1.5, (12, 41.36)),
    ([3.0, 4.0, 3.0, 2.0, 5.0], [59.2, 18.2, 14.0, 37.8, 13.0], 1.0, 1.5, (12, 102.0)),
    ([2.6, 4.51, 5.25, 1.49, 7.58], [43.0, 9.9, 36.6, 66.4, 64.9], 1.0, 1.5, (16, 329.141666667)),
    ([7.05, 4.14, 5.79, 3.28, 3.36], [54.7, 26.1, 20.8, 21.2, 24.1], 1.5, 1.5, (17, 350.97)),
]


# The same rings after the grid search of the corners the short-side search leaves closer than l (None: unchanged).
# The second has no side too short for its staggers but its corners of 18.2 and 4.2 degrees are closer than l
# (0.949 and 0.073): the grid search places them too (1.096 and 1.005).
GRID_RINGS = [(18, 456.0), (10, 88.0), (10, 90.9375), None, None, None, (10, 57.0), None, (17, 354.1425)]


@pytest.mark.parametrize("ring, grid", list(zip(SEARCH_RINGS, GRID_RINGS)))
def test_short_side_search_on_rings_where_each_step_matters(ring, grid, monkeypatch):
    """Pinned without the grid search (so that each step of the short-side search still decides the output),
    then with it."""
    lengths, angles, l, spacing, pinned = ring
    with monkeypatch.context() as patch:
        patch.setattr(equimesh.planar.boundary.sides, "place_corners_on_a_grid", lambda *args: None)
        assert _fingerprint(np.array(lengths) * l, angles, l, spacing) == pinned
    assert _fingerprint(np.array(lengths) * l, angles, l, spacing) == (grid or pinned)


def test_a_run_of_sharp_corners_goes_on_through_coupling_sides_only():
    """The dart of 30 degrees (corners 30, 30, 270, 30; sides 3.5, 1.28, 1.28, 3.5): the run through the tip is
    barb, tip, barb (3, 0, 1), from any of them.  With a tip side longer
    than 2 l + 2 l + 4 l (K = 2) it is cut there."""
    angles, lengths = [30.0, 30.0, 270.0, 30.0], [3.5, 1.28, 1.28, 3.5]
    for c in (3, 0, 1):
        assert _run(lengths, angles, 1.0, c) == [3, 0, 1]
    assert _run([8.5, 1.28, 1.28, 3.5], angles, 1.0, 3) == [3, 0] and _run([8.5, 1.28, 1.28, 8.5], angles, 1.0, 0) == [
        0
    ]
    assert _run([8.0, 1.28, 1.28, 8.0], angles, 1.0, 0) == [3, 0, 1]  # 8 l is the limit, included


def test_a_pair_placed_jointly_takes_the_shared_sides_points_and_completes_the_others():
    """The triangle of 29.4 and 23.07 degrees on a base of 5.25 l (placeable together): the base takes place_chain's
    points of T_1, the other two sides are completed; every part in [l, 2l], both corners' sides l apart.  A run with
    a corner that is not sharp is not placed."""
    apex = 5.25 * math.sin(math.radians(23.069711979788835)) / math.sin(math.radians(180.0 - 29.4 - 23.069711979788835))
    ring = as_polygon([[0.0, 0.0], [5.25, 0.0], at(29.4, apex)], 1.0).rings[0]
    lengths, angles = ring.local_edge_lengths, [ring.inner_angle(i) for i in range(3)]
    found = chain.place_chain(tuple(math.radians(a) for a in angles[:2]), tuple(lengths[[2, 0, 1]]), 1.0)
    sides = side_positions(lengths, angles, 1.0)
    trial = grid_chain(sides, lengths, angles, 1.0, 2.0, [0, 1])
    assert trial[0][1] == lengths[0] and np.array_equal(trial[0][0], np.concatenate([[0.0], found[1][:-1]]))
    for (num, den), length in zip(trial, lengths):
        parts = np.diff(np.append(num / den * length, length))
        assert np.all(parts >= (1.0 - REL_TOL)) and np.all(parts <= 2.0 * (1.0 + REL_TOL))
    assert min(corner_gap(trial, lengths, angles, 1.0, c) for c in (0, 1)) >= 1.0 - REL_TOL
    assert grid_chain(sides, lengths, angles, 1.0, 2.0, [1, 2]) is None


@pytest.mark.parametrize(
    "angles, lengths, run",
    [
        ([29.4, 23.07, 150.0, 157.53], [5.25, 10.0, 6.0, 2.6], [0, 1]),
        ([30.0, 30.0, 30.0, 150.0, 120.0], [3.5, 3.5, 10.0, 6.0, 3.5], [0, 1, 2]),
    ],
)
def test_a_long_last_side_placed_jointly_keeps_its_points_beyond_the_cut(angles, lengths, run):
    """The side leaving the run's last corner is 10 l long with uneven points (parts 1, 1.5, 2, 2, 2, 1.5 l from that
    corner): place_chain cuts it past K l, its own points at least l beyond the cut are kept, read from that corner
    (the middle is split again), for a pair and for a run of three."""
    far = run[-1]
    sides = [(np.arange(math.ceil(x / 2.0)) * (x / math.ceil(x / 2.0)), x) for x in lengths]
    sides[far] = np.array([0.0, 1.0, 2.5, 4.5, 6.5, 8.5]), 10.0
    num, den = grid_chain(sides, np.array(lengths), angles, 1.0, 2.0, run)[far]
    assert den == 10.0 and num[0] == 0.0 and set(num[-3:]) == {4.5, 6.5, 8.5}
    assert np.all(np.diff(np.append(num, den)) >= 1.0 - REL_TOL) and np.all(
        np.diff(np.append(num, den)) <= 2.0 + REL_TOL
    )


def test_a_short_side_takes_the_fewest_multiples_from_a_corner_that_is_not_sharp():
    """The triangle (0, 0), (2.42, 0), (4.64, 2.35) at l = 1, spacing 1.5: corners of 26.9 (sharp), 133.4 (not) and
    19.8 degrees (sharp).  Side 1 (3.23 long, from the 133-degree corner to the 19.8-degree one) is separated with
    one multiple of l from its first corner and one staggered point from its last: points at 0, 1 and length - 1;
    the candidate with two multiples (0, 1, 2) is tried after it."""
    poly = as_polygon(np.array([(0.0, 0.0), (2.42, 0.0), (4.64, 2.35)]), 1.0)
    ring = poly.rings[0]
    angles = [ring.inner_angle(i) for i in range(3)]
    np.testing.assert_allclose(angles, [26.861, 133.371, 19.769], atol=1e-3)
    lengths = ring.local_edge_lengths
    numerators, denominator = side_positions(lengths, angles, 1.0, 1.5)[1]
    assert denominator == lengths[1]
    np.testing.assert_allclose(numerators, [0.0, 1.0, lengths[1] - 1.0], atol=1e-12)


def test_from_corner_measures_a_side_from_either_end():
    """Side 1 (5 long, points at 0, 1 and 3 of it) measured from corner 1, which it leaves, and from corner 2, where it
    arrives; the far end is included."""
    sides, lengths = [None, (np.array([0.0, 1.0, 3.0]), 5.0), None], [4.0, 5.0, 6.0]
    np.testing.assert_array_equal(boundary_sides.from_corner(sides, lengths, 1, 1), [1.0, 3.0, 5.0])
    np.testing.assert_array_equal(boundary_sides.from_corner(sides, lengths, 2, 1), [2.0, 4.0, 5.0])


@pytest.mark.parametrize(
    "leaving, expected", [(True, [0.0, 1.0, 2.5, 3.5, 5.0, 7.0]), (False, [0.0, 2.0, 4.0, 5.5, 6.5, 8.0])]
)
def test_grid_side_keeps_the_points_at_least_l_past_the_cut(leaving, expected):
    """A side 9 long (l = 1) that the grid cut at 2.5 (points 1 and 2.5 from the corner): of its current points 1.5,
    2.5, 3.5, 5 and 7, those at least l past the cut are kept, 3.5 (exactly l past it) included, and the middle
    between, exactly l, is one part.  Positions are from the side's first corner: the corner itself if it leaves
    it, the far end if it arrives."""
    numerators, length = boundary_sides.grid_side(
        9.0, np.array([1.0, 2.5]), np.array([1.5, 2.5, 3.5, 5.0, 7.0, 9.0]), leaving, 1.0, 1.5
    )
    assert length == 9.0
    np.testing.assert_array_equal(numerators, expected)


def test_grid_side_drops_the_points_within_l_of_the_cut():
    """A side 10 long cut at 6: its current point 5.5, before the cut but less than l from it, is not kept (else the
    middle would be too short and the grid's own last point dropped); 7.5 is."""
    numerators, _ = boundary_sides.grid_side(
        10.0, np.array([1.5, 3.0, 4.5, 6.0]), np.array([1.0, 2.5, 4.0, 5.5, 7.5, 10.0]), True, 1.0, 1.5
    )
    np.testing.assert_array_equal(numerators, [0.0, 1.5, 3.0, 4.5, 6.0, 7.5])


def test_grid_side_ending_at_the_far_end_is_the_grid_points():
    """Points ending at the side's far end are the side (from its first corner either way)."""
    for leaving, expected in ((True, [0.0, 1.5, 3.0]), (False, [0.0, 1.0, 2.5])):
        numerators, length = boundary_sides.grid_side(
            4.0, np.array([1.5, 3.0, 4.0]), np.array([4.0]), leaving, 1.0, 1.5
        )
        np.testing.assert_array_equal(numerators, expected)


# --------------------------------------------------------------------------- the grid search of a ring's sharp corners

#: A ring of sides 5.25, 9, 7 and 9 l with corners of 29.4, 23.07, 100 and 207.5 degrees (side_positions reads lengths
#: and angles only): corners 0 and 1 share the side 5.25 l, their other sides are long (cut past K l = 3 l).
GRID_LENGTHS, GRID_ANGLES = np.array([5.25, 9.0, 7.0, 9.0]), [29.4, 23.069711979788835, 100.0, 207.5]


def positions(sides):
    return [np.round(num, 9).tolist() for num, _ in sides]


@pytest.mark.parametrize(
    "last, placed",
    [
        (
            9.0,
            [
                [0.0, 1.0, 2.0, 3.25],
                [0.0, 1.0, 3.0, 4.5, 6.0, 7.5],
                [0.0, 1.0, 2.0, 3.0, 4.0],
                [0.0, 1.5, 3.0, 4.5, 6.0, 7.0625],
            ],
        ),
        (2.1, [[0.0, 1.75, 2.75, 4.0625], [0.0, 2.0, 3.0, 4.5, 6.0, 7.5], [0.0, 1.0, 2.0, 3.0, 4.0], [0.0, 1.1]]),
    ],
)
def test_grid_chain_places_the_three_sides_of_two_corners(last, placed):
    """grid_chain at corners 0 and 1: side 3 (arriving at 0, ``last`` long), 0 (shared) and 1 (leaving 1) placed
    jointly, a long side kept past its cut from where it was; both corners then l apart, side 2 untouched; None when
    the next corner is not sharp."""
    lengths = np.append(GRID_LENGTHS[:3], last)
    sides = side_positions(lengths, GRID_ANGLES, 1.0, 1.5)
    trial = boundary_sides.grid_chain(sides, lengths, GRID_ANGLES, 1.0, 1.5, [0, 1])
    assert positions(trial) == placed
    assert trial[2] is sides[2]
    assert all(at_least(boundary_sides.corner_gap(trial, lengths, GRID_ANGLES, 1.0, c), 1.0) for c in (0, 1))
    assert boundary_sides.grid_chain(sides, lengths, GRID_ANGLES, 1.0, 1.5, [1, 2]) is None


@pytest.mark.parametrize(
    "keep, first, last",
    [
        ((False, False), [0.0, 1.25, 3.25], [0.0, 1.5, 3.0, 4.5, 6.0, 7.0625]),
        ((True, False), [0.0, 1.0, 2.0, 3.25], [0.0, 1.5, 3.0, 4.5, 6.0, 7.0625]),
        ((False, True), [0.0, 1.25, 3.25], [0.0, 1.5, 3.0, 4.5, 6.0, 7.0]),
    ],
)
def test_grid_sides_places_a_corners_two_sides_keeping_those_asked(keep, first, last):
    """grid_sides at corner 0: its leaving side 0 and arriving side 3 placed on the grid, a side flagged in ``keep``
    passed as it is (up to the cut past K l of a long side); the other sides untouched."""
    sides = side_positions(GRID_LENGTHS, GRID_ANGLES, 1.0, 1.5)
    trial = boundary_sides.grid_sides(sides, GRID_LENGTHS, GRID_ANGLES, 1.0, 1.5, 0, keep)
    assert positions(trial) == [first, positions(sides)[1], positions(sides)[2], last]
    if keep[0]:
        assert positions(trial)[0] == positions(sides)[0]


def test_place_corners_on_a_grid_tries_the_trials_in_order(monkeypatch):
    """Every corner reported closer than l, in turn, goes through the trials of the docstring in order: itself free,
    leaving side kept, arriving side kept, the next (previous) corner first then this one keeping the shared side,
    this one first then the next (previous), jointly with the next, jointly with the previous, with its whole run of
    three or more (when it has one); a trial with a corner
    that is not sharp (corner 2, 100 degrees) is skipped, the others still tried (corner 2's own joint trial with the
    previous corner too).
    (The grid placements are stubbed: each returns its input, and no trial separates anything.)"""
    calls, angles = [], [29.4, 23.0, 100.0, 20.0, 15.0]
    sides = side_positions(np.full(5, 4.0), angles, 1.0, 1.5)
    monkeypatch.setattr(corner, "corner_unplaceable", lambda *args: False)
    monkeypatch.setattr(equimesh.planar.boundary.sides, "corner_gap", lambda *args: 0.0)
    monkeypatch.setattr(
        equimesh.planar.boundary.sides, "grid_sides", lambda sides, *args: calls.append((args[-2], args[-1])) or sides
    )
    monkeypatch.setattr(
        equimesh.planar.boundary.sides, "grid_chain", lambda sides, *args: calls.append((args[-1], "chain")) or sides
    )
    boundary_sides.place_corners_on_a_grid(sides, np.full(5, 4.0), angles, 1.0, 1.5)
    free, leaving, arriving = (False, False), (True, False), (False, True)

    def trials(c, after, before):
        """Each trial as its steps ``(corner, call recorded)``."""
        run = boundary_sides.sharp_run(np.full(5, 4.0), angles, 1.0, c)
        return [
            [(c, (c, free))],
            [(c, (c, leaving))],
            [(c, (c, arriving))],
            [(after, (after, free)), (c, (c, leaving))],
            [(before, (before, free)), (c, (c, arriving))],
            [(c, (c, free)), (after, (after, arriving))],
            [(c, (c, free)), (before, (before, leaving))],
            [(c, ([c, after], "chain"))],
            [(before, ([before, c], "chain"))],
            *([[(c, (run, "chain"))]] if len(run) > 2 else []),
        ]

    expected = [
        call
        for c in range(5)
        for trial in trials(c, (c + 1) % 5, (c - 1) % 5)
        if all(corner != 2 for corner, _ in trial)
        for _, call in trial
    ]
    assert calls == expected
    assert any(keep == "chain" and len(run) > 2 for run, keep in calls)  # a run of three or more was tried


def test_place_corners_on_a_grid_checks_every_corner_a_trial_touched(monkeypatch):
    """A trial is taken when the corners it touched and their neighbours are l apart: for a joint trial the two
    corners and one neighbour on each side (here the first trial that returns anything, the joint one)."""
    checked = []
    sides = side_positions(np.full(5, 4.0), [20.0] * 5, 1.0, 1.5)
    monkeypatch.setattr(corner, "corner_unplaceable", lambda *args: False)
    monkeypatch.setattr(
        equimesh.planar.boundary.sides,
        "corner_gap",
        lambda trial, *args: 0.0 if trial is sides else checked.append(args[-1]),
    )
    monkeypatch.setattr(equimesh.planar.boundary.sides, "grid_sides", lambda *args: None)
    monkeypatch.setattr(equimesh.planar.boundary.sides, "grid_chain", lambda trial, *args: list(trial))
    monkeypatch.setattr(boundary_sides, "at_least", lambda value, l: value is None)
    boundary_sides.place_corners_on_a_grid(sides, np.full(5, 4.0), [20.0] * 5, 1.0, 1.5)
    assert [set(checked[k : k + 4]) for k in range(0, 20, 4)] == [
        {4, 0, 1, 2},
        {0, 1, 2, 3},
        {1, 2, 3, 4},
        {2, 3, 4, 0},
        {3, 4, 0, 1},
    ]


def test_place_corners_on_a_grid_checks_a_lone_corner_and_its_neighbours(monkeypatch):
    """For a trial of one corner (here the first, its two sides free) the corner itself and its two neighbours are
    checked, each once."""
    checked = []
    sides = side_positions(np.full(5, 4.0), [20.0] * 5, 1.0, 1.5)
    monkeypatch.setattr(corner, "corner_unplaceable", lambda *args: False)
    monkeypatch.setattr(
        equimesh.planar.boundary.sides,
        "corner_gap",
        lambda trial, *args: 0.0 if trial is sides else checked.append(args[-1]),
    )
    monkeypatch.setattr(equimesh.planar.boundary.sides, "grid_sides", lambda trial, *args: list(trial))
    monkeypatch.setattr(boundary_sides, "at_least", lambda value, l: value is None)
    boundary_sides.place_corners_on_a_grid(sides, np.full(5, 4.0), [20.0] * 5, 1.0, 1.5)
    assert sorted(checked[:3]) == [0, 1, 4] and [sorted(checked[k : k + 3]) for k in range(3, 15, 3)] == [
        [0, 1, 2],
        [1, 2, 3],
        [2, 3, 4],
        [0, 3, 4],
    ]


def test_a_dart_separated_only_by_its_run_of_three_is_meshed(monkeypatch):
    """A dart (tip 23.97 degrees, barbs 30.55 and 38.91, sides 4.42 l) whose three sharp corners no single corner or
    pair trial separates: the trial of the whole run places it (a chain of three returned), and it is meshed with
    every edge in [l, 2l] (found by a random search over darts; without the run trial it is refused)."""
    placed, real = [], boundary_sides.grid_chain
    monkeypatch.setattr(
        equimesh.planar.boundary.sides,
        "grid_chain",
        lambda *args: placed.append((len(args[-1]), real(*args))) or placed[-1][1],
    )
    dart = sharp_dart(23.97192472430486, (30.54743423844858, 38.9057900966436), 4.424429730465021)
    mesh = equimesh.uniform_triangulation(dart, 1.0)
    assert any(n == 3 and found is not None for n, found in placed)
    lengths = mesh.edge_lengths()
    assert at_least(lengths.min(), 1.0) and lengths.max() <= 2.0 * (1.0 + REL_TOL)
