"""Step 2 at one sharp corner decided on a grid (planar/_corner.py; docs/proofs.md, "Sharp corners").

What must hold: the merged-order lemma (consecutive cross pairs decide every cross pair); every placement
the search returns has parts in [l, 2l], ends at the far corners and keeps every cross pair l apart
(checked pair by pair here); the proof never contradicts a placement; and a corner it proves impossible has
no placement on a sampled grid either (tests/corner_sampling.py, independently of the module).  The same for two
corners sharing a side, decided jointly (planar/_coupled.py).
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from equimesh.planar import _corner, _coupled
from corner_sampling import sampled_pair, sampled_placement
from equimesh.tolerance import REL_TOL


def _cross(theta, a, b):
    """Distances between every point at distances ``a`` on one side and ``b`` on the other."""
    a, b = np.asarray(a)[:, None], np.asarray(b)[None, :]
    return np.sqrt(np.maximum(a * a + b * b - 2.0 * math.cos(theta) * a * b, 0.0))


parts = st.lists(st.floats(1.0, 2.0), min_size=1, max_size=8)


@given(st.floats(0.5, 60.0), parts, parts)
def test_consecutive_cross_pairs_in_merged_order_decide_every_cross_pair(angle, parts_a, parts_b):
    """The merged-order lemma: if every two points of different sides that are consecutive by distance from the
    corner are l apart, every two points of different sides are (parts of at least l on each side)."""
    theta = math.radians(angle)
    a, b = np.cumsum(parts_a), np.cumsum(parts_b)
    merged = sorted([(x, 0) for x in a] + [(x, 1) for x in b])
    consecutive = [_cross(theta, [u], [w])[0, 0] for (u, s), (w, t) in zip(merged, merged[1:]) if s != t]
    if min(consecutive, default=math.inf) >= 1.0:
        assert _cross(theta, a, b).min() >= 1.0 - 1e-12


def _assert_placement(theta, lengths, l, found):
    """Parts in [l, 2l], each side ending at its far end (or, cut short, at least l before it and past K l),
    every cross pair l apart; all up to REL_TOL."""
    reach = _corner.corner_reach(theta, l)
    for points, length in zip(found, lengths):
        steps = np.diff(np.concatenate([[0.0], points]))
        assert np.all(steps >= (1.0 - REL_TOL) * l) and np.all(steps <= 2.0 * (1.0 + REL_TOL) * l), points
        assert points[-1] == length or (reach <= points[-1] <= length - (1.0 - REL_TOL) * l), (points, length)
    assert _cross(theta, *found).min() >= (1.0 - REL_TOL) * l


@given(st.floats(5.0, 59.0), st.floats(1.0, 9.0), st.floats(1.0, 9.0), st.sampled_from([1.0, 1.5]))
def test_a_placement_found_meets_lemma_3_and_is_never_proven_impossible(angle, a, b, l):
    """Whatever place_corner returns is a placement (checked pair by pair), and corner_unplaceable (which claims
    a proof) never says impossible where a placement exists: the relaxation is checked against the search."""
    theta, lengths = math.radians(angle), (a * l, b * l)
    found = _corner.place_corner(theta, lengths, l)
    if found is not None:
        _assert_placement(theta, lengths, l, found)
        assert not _corner.corner_unplaceable(theta, lengths, l, (math.inf, math.inf))


def test_a_placement_off_every_grid_is_found_by_tightening():
    """17.46 degrees with sides of 4.132 l: the placements form a sliver that the grids of 1/16 to 1/64 l miss;
    the order of the relaxation's path, pushed as near the corner as it allows (_tighten), is one."""
    theta, lengths = math.radians(17.460507302465036), (4.132016938510646, 4.132016938510646)
    reach = _corner.corner_reach(theta, 1.0)
    for grid in (16, 32, 64):
        nodes = _corner._nodes(lengths, reach, 1.0, 1.0 / grid, (None, None))
        assert _corner._Graph(theta, lengths, reach, 1.0, nodes, nodes, REL_TOL / 4.0, (math.inf, math.inf)).search() is None
    found = _corner.place_corner(theta, lengths, 1.0)
    _assert_placement(theta, lengths, 1.0, found)
    assert [len(points) for points in found] == [3, 3]


def test_a_long_side_is_cut_past_k_l_and_kept_sides_are_kept():
    """5 degrees with sides of 40 l (K = 12): both sides stop at their first point past 12 l; with the leaving
    side given (multiples of 2 l), it is returned as given."""
    theta, lengths = math.radians(5.0), (40.0, 40.0)
    found = _corner.place_corner(theta, lengths, 1.0)
    _assert_placement(theta, lengths, 1.0, found)
    assert all(12.0 <= points[-1] < 14.0 for points in found)
    kept = np.arange(1, 8) * 2.0 - 1.0
    found = _corner.place_corner(theta, lengths, 1.0, (kept, None))
    assert found is not None and np.array_equal(found[0], kept)
    _assert_placement(theta, lengths, 1.0, found)


PROVEN = [  # (angle, leaving, arriving): the corners of results/sharp_corners.md proven by the relaxation
    (2.82807, 4.5, 3.5195),
    (10.0, 2.4, 4.5),
    (19.8177, 2.3049, 6.6),
    (5.83171, 3.5, 2.5473),
    (9.4254, 3.0, 2.0885),
    (20.0, 3.4553, 3.4553),
]


@pytest.mark.parametrize("angle, a, b", PROVEN)
def test_a_corner_proven_impossible_has_nosampled_placement(angle, a, b):
    """corner_unplaceable proves these; enumerating parts in steps of l/8 finds no placement either, and the
    search gives up (it is never handed a corner the proof refuses)."""
    theta = math.radians(angle)
    assert _corner.corner_unplaceable(theta, (a, b), 1.0, (math.inf, math.inf))
    assert _corner.place_corner(theta, (a, b), 1.0) is None
    assert sampled_placement(theta, (a, b), 1.0) is None


def test_the_enumeration_finds_placements_where_they_exist():
    """The enumeration above is not vacuous: 20 degrees with sides of 3.4 and 3 l (the thin triangle of
    results/sharp_corners.md meshed by the search) has a placement on steps of l/8."""
    assert sampled_placement(math.radians(20.0), (3.4, 3.0), 1.0) is not None


def test_visibility_radii_drop_the_pairs_beyond_them():
    """The 20-degree corner with sides 3.4553 is proven impossible with every pair checked; with no pair seen
    (radii 0) nothing is proven."""
    theta = math.radians(20.0)
    assert _corner.corner_unplaceable(theta, (3.4553, 3.4553), 1.0, (math.inf, math.inf))
    assert not _corner.corner_unplaceable(theta, (3.4553, 3.4553), 1.0, (0.0, 0.0))


# --------------------------------------------------------------------------- two sharp corners sharing a side (_coupled.py)

#: The thin triangle [[0, 0], [4.25, 0], 2.1 (cos 29.4, sin 29.4)]: corners of 29.4 and 23.07 degrees sharing the
#: side of 4.25 l, their other sides 2.1 and 2.63 l.
PAIR_THETAS = (math.radians(29.4), math.radians(23.069711979788835))
PAIR_LENGTHS = (2.1, 4.25, 2.630842730287126)


def _assert_pair(thetas, lengths, l, found):
    """A joint placement: each corner's two sides a placement (:func:`_assert_placement`), the shared side the same."""
    a, s, b = found
    _assert_placement(thetas[0], (lengths[1], lengths[0]), l, (s, a))
    _assert_placement(thetas[1], (lengths[2], lengths[1]), l, (b, lengths[1] - np.append(0.0, s[:-1])[::-1]))


def test_two_corners_each_placeable_alone_are_proven_unplaceable_together():
    """Each corner of the triangle alone has a placement; together none (the relaxation refutes every split of the
    shared side), and the independent enumeration of every split of the shared side (steps of l/8 and l/32)
    finds none either, nor the search."""
    for theta, sides in zip(PAIR_THETAS, [PAIR_LENGTHS[1::-1], PAIR_LENGTHS[:0:-1]]):
        assert _corner.place_corner(theta, sides, 1.0) is not None
    assert _coupled.pair_unplaceable(PAIR_THETAS, PAIR_LENGTHS, 1.0, (math.inf,) * 4)
    assert _coupled.place_pair(PAIR_THETAS, PAIR_LENGTHS, 1.0) is None
    for step in (1.0 / 8.0, 1.0 / 32.0):
        assert sampled_pair(PAIR_THETAS, PAIR_LENGTHS, 1.0, step) is None


def test_the_pair_enumeration_finds_placements_where_they_exist():
    """Not vacuous: with the shared side 5.25 l both the search and the enumeration place the pair, and the
    proof does not refuse it; with no pair seen (radii 0) nothing is proven."""
    lengths = (2.1, 5.25, 2.630842730287126)
    found = _coupled.place_pair(PAIR_THETAS, lengths, 1.0)
    _assert_pair(PAIR_THETAS, lengths, 1.0, found)
    assert sampled_pair(PAIR_THETAS, lengths, 1.0) is not None
    assert not _coupled.pair_unplaceable(PAIR_THETAS, lengths, 1.0, (math.inf,) * 4)
    assert not _coupled.pair_unplaceable(PAIR_THETAS, PAIR_LENGTHS, 1.0, (0.0,) * 4)


@given(st.floats(10.0, 59.0), st.floats(10.0, 59.0), st.floats(1.0, 4.0), st.floats(1.0, 7.0), st.floats(1.0, 4.0))
def test_a_pair_placement_found_meets_lemma_3_and_a_proven_pair_has_no_sampled_placement(angle_1, angle_2, a, s, b):
    """The proof's cells (a relaxation) never refute a pair the search places (on the two coarsest grids), whatever
    the search returns is a placement at both corners (checked pair by pair), and a pair the proof refuses has
    no placement in the enumeration either."""
    thetas, lengths = (math.radians(angle_1), math.radians(angle_2)), (a, s, b)
    if _coupled.pair_unplaceable(thetas, lengths, 1.0, (math.inf,) * 4):
        assert sampled_pair(thetas, lengths, 1.0) is None
        return
    found = _coupled.place_pair(thetas, lengths, 1.0)
    if found is not None:
        _assert_pair(thetas, lengths, 1.0, found)
        for level in (0, 1):
            assert _coupled._Pair(thetas, lengths, 1.0, level, cells=True, radii=(math.inf,) * 4).search() is not None


def test_a_single_corner_left_open_by_cells_of_l_over_64_is_proven_on_clipped_cells():
    """21.69 degrees with sides of 3.188 l (a short wedge of strategies_sharp): the last placements vanish at a
    first part of exactly 2l, so corner_unplaceable's cells of l/16 to l/64 still hold a path; the joint proof
    with no second corner, its first and last cells clipped to the ranges those points can have, refutes it, and
    the enumeration finds no placement either."""
    theta, sides = math.radians(21.693585695037463), (3.18837772, 3.18837772)
    assert not _corner.corner_unplaceable(theta, sides, 1.0, (math.inf, math.inf))
    assert _coupled.pair_unplaceable((theta, None), (sides[1], sides[0], 0.0), 1.0, (math.inf,) * 4)
    assert sampled_placement(theta, sides, 1.0) is None


def test_a_shared_side_too_long_to_couple_the_corners_is_not_decided_jointly():
    """Past K_1 l + K_2 l + 4l no point of the shared side matters to both corners: neither the search nor the
    proof takes the pair (K = 3 at 29.4 and 23.07 degrees: up to 10 l)."""
    lengths = (2.1, 10.25, 2.630842730287126)
    assert not _coupled._coupled(PAIR_THETAS, lengths, 1.0) and _coupled._coupled(PAIR_THETAS, PAIR_LENGTHS, 1.0)
    assert _coupled.place_pair(PAIR_THETAS, lengths, 1.0) is None
    assert not _coupled.pair_unplaceable(PAIR_THETAS, lengths, 1.0, (math.inf,) * 4)
