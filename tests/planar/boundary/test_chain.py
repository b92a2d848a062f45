"""Step 2 at sharp corners in a row decided jointly (``planar/boundary/chain.py``; docs/proofs.md, "Sharp corners").

What must hold: two or more sharp corners sharing sides are placed or refused together; whatever the search
returns is a placement at every corner (checked pair by pair), the proof's cells never refute a chain the search
places, and a chain it proves impossible has no placement in the independent enumeration
(``tests/corner_sampling.py``).  The pieces they are built of are pinned one by one, so that mutation testing
(tools/mutation) sees each rule decide something.
"""

import math

import numpy as np
import pytest
from conditions import exercised
from corner_sampling import assert_placement, sampled_chain, sampled_placement
from hypothesis import given
from hypothesis import strategies as st

from equimesh.planar.boundary import chain, corner
from equimesh.tolerance import REL_TOL

# --------------------------------------------------------------------------- two sharp corners sharing a side

#: The thin triangle [[0, 0], [4.25, 0], 2.1 (cos 29.4, sin 29.4)]: corners of 29.4 and 23.07 degrees sharing the
#: side of 4.25 l, their other sides 2.1 and 2.63 l.
PAIR_THETAS = (math.radians(29.4), math.radians(23.069711979788835))


PAIR_LENGTHS = (2.1, 4.25, 2.630842730287126)


def _assert_pair(thetas, lengths, l, found):
    """A joint placement: each corner's two sides a placement (:func:`assert_placement`), the shared side the same."""
    a, s, b = found
    assert_placement(thetas[0], (lengths[1], lengths[0]), l, (s, a))
    assert_placement(thetas[1], (lengths[2], lengths[1]), l, (b, lengths[1] - np.append(0.0, s[:-1])[::-1]))


def test_two_corners_each_placeable_alone_are_proven_unplaceable_together():
    """Each corner of the triangle alone has a placement; together none (the relaxation refutes every split of the
    shared side), and the independent enumeration of every split of the shared side (steps of l/8 and l/32)
    finds none either, nor the search."""
    for theta, sides in zip(PAIR_THETAS, [PAIR_LENGTHS[1::-1], PAIR_LENGTHS[:0:-1]]):
        assert corner.place_corner(theta, sides, 1.0) is not None
    assert chain.chain_unplaceable(PAIR_THETAS, PAIR_LENGTHS, 1.0, (math.inf,) * 4)
    assert chain.place_chain(PAIR_THETAS, PAIR_LENGTHS, 1.0) is None
    for step in (1.0 / 8.0, 1.0 / 32.0):
        assert sampled_chain(PAIR_THETAS, PAIR_LENGTHS, 1.0, step) is None


def test_the_pair_enumeration_finds_placements_where_they_exist():
    """Not vacuous: with the shared side 5.25 l both the search and the enumeration place the pair, and the
    proof does not refuse it; with no pair seen (radii 0) nothing is proven."""
    lengths = (2.1, 5.25, 2.630842730287126)
    found = chain.place_chain(PAIR_THETAS, lengths, 1.0)
    _assert_pair(PAIR_THETAS, lengths, 1.0, found)
    assert sampled_chain(PAIR_THETAS, lengths, 1.0) is not None
    assert not chain.chain_unplaceable(PAIR_THETAS, lengths, 1.0, (math.inf,) * 4)
    assert not chain.chain_unplaceable(PAIR_THETAS, PAIR_LENGTHS, 1.0, (0.0,) * 4)


@given(st.floats(10.0, 59.0), st.floats(10.0, 59.0), st.floats(1.0, 4.0), st.floats(1.0, 7.0), st.floats(1.0, 4.0))
def test_a_pair_placement_found_meets_lemma_3_and_a_proven_pair_has_no_sampled_placement(angle_1, angle_2, a, s, b):
    """The proof's cells (a relaxation) never refute a pair the search places (on the two coarsest grids), whatever
    the search returns is a placement at both corners (checked pair by pair), and a pair the proof refuses has
    no placement in the enumeration either."""
    thetas, lengths = (math.radians(angle_1), math.radians(angle_2)), (a, s, b)
    if chain.chain_unplaceable(thetas, lengths, 1.0, (math.inf,) * 4):
        assert sampled_chain(thetas, lengths, 1.0) is None
        return
    found = chain.place_chain(thetas, lengths, 1.0)
    if found is not None:
        _assert_pair(thetas, lengths, 1.0, found)
        for level in (0, 1):
            assert chain.Chain(thetas, lengths, 1.0, level, cells=True, radii=(math.inf,) * 4).search() is not None


def test_a_single_corner_left_open_by_cells_of_l_over_64_is_proven_on_clipped_cells():
    """21.69 degrees with sides of 3.188 l (a short wedge of strategies_sharp): the last placements vanish at a
    first part of exactly 2l, so corner_unplaceable's cells of l/16 to l/64 still hold a path; the joint proof
    with no second corner, its first and last cells clipped to the ranges those points can have, refutes it, and
    the enumeration finds no placement either."""
    theta, sides = math.radians(21.693585695037463), (3.18837772, 3.18837772)
    assert not corner.corner_unplaceable(theta, sides, 1.0, (math.inf, math.inf))
    assert chain.chain_unplaceable((theta, None), (sides[1], sides[0], 0.0), 1.0, (math.inf,) * 4)
    assert sampled_placement(theta, sides, 1.0) is None


def test_a_shared_side_too_long_to_couple_the_corners_is_not_decided_jointly():
    """Past K_1 l + K_2 l + 4l no point of the shared side matters to both corners: neither the search nor the
    proof takes the pair (K = 3 at 29.4 and 23.07 degrees: up to 10 l)."""
    lengths = (2.1, 10.25, 2.630842730287126)
    assert not chain.coupled(PAIR_THETAS, lengths, 1.0) and chain.coupled(PAIR_THETAS, PAIR_LENGTHS, 1.0)
    assert chain.place_chain(PAIR_THETAS, lengths, 1.0) is None
    assert not chain.chain_unplaceable(PAIR_THETAS, lengths, 1.0, (math.inf,) * 4)


# --------------------------------------------------------------------------- sharp corners in a row (chains)

#: The dart sharp_dart(30, (30, 30), 3.5): three corners of 30 degrees in a row (barb, tip, barb), the tip's sides
#: 3.5 l shared, the barbs' other sides 1.2811 l (to the notch).
DART_THETAS = (math.radians(30.0),) * 3


DART_LENGTHS = (1.2810889132455352, 3.5, 3.5, 1.2810889132455352)


def _assert_chain(thetas, lengths, l, found):
    """A placement at every corner of the chain (:func:`assert_placement`), each shared side the same at both ends."""
    assert len(found) == len(lengths) == len(thetas) + 1
    for k, theta in enumerate(thetas):
        arriving = found[k] if k == 0 else lengths[k] - np.append(0.0, found[k][:-1])[::-1]
        assert_placement(theta, (lengths[k + 1], lengths[k]), l, (found[k + 1], arriving))


def test_three_corners_each_pair_placeable_are_proven_unplaceable_together():
    """The dart: each two of its corners sharing a side have a placement (search and enumeration), the three
    together none (the chain's proof refutes every split of the two shared sides, and the independent enumeration of
    every split in steps of l/8 and l/16 finds none), nor the search."""
    for pair in (slice(0, 2), slice(1, 3)):
        lengths = DART_LENGTHS[pair.start : pair.stop + 1]
        _assert_chain(DART_THETAS[pair], lengths, 1.0, chain.place_chain(DART_THETAS[pair], lengths, 1.0))
        assert sampled_chain(DART_THETAS[pair], lengths, 1.0) is not None
    assert chain.chain_unplaceable(DART_THETAS, DART_LENGTHS, 1.0, (math.inf,) * 6)
    assert chain.place_chain(DART_THETAS, DART_LENGTHS, 1.0) is None
    for step in (1.0 / 8.0, 1.0 / 16.0):
        assert sampled_chain(DART_THETAS, DART_LENGTHS, 1.0, step) is None
    assert not chain.chain_unplaceable(DART_THETAS, DART_LENGTHS, 1.0, (math.inf,) * 4 + (0.0,) * 2)


@given(
    st.lists(st.floats(10.0, 59.0), min_size=3, max_size=4),
    st.floats(1.0, 3.0),
    st.lists(st.floats(1.0, 5.0), min_size=3, max_size=3),
    st.floats(1.0, 3.0),
)
def test_a_chain_placement_found_meets_lemma_3_at_every_corner_and_a_proven_chain_has_no_sampled_placement(
    angles, a, shared, b
):
    """Three or four sharp corners in a row: whatever the search returns is a placement at every corner (checked
    pair by pair), the proof's cells never refute a chain it places (two coarsest grids), and a chain the proof
    refuses has no placement in the enumeration either."""
    thetas, lengths = tuple(math.radians(x) for x in angles), (a, *shared[: len(angles) - 1], b)
    if chain.chain_unplaceable(thetas, lengths, 1.0, (math.inf,) * (2 * len(thetas))):
        assert sampled_chain(thetas, lengths, 1.0) is None
        return
    found = chain.place_chain(thetas, lengths, 1.0)
    if exercised("a chain of three is placed", found is not None):
        _assert_chain(thetas, lengths, 1.0, found)
        for level in (0, 1):
            assert (
                chain.Chain(thetas, lengths, 1.0, level, cells=True, radii=(math.inf,) * (2 * len(thetas))).search()
                is not None
            )


def test_a_pair_left_open_by_the_old_step_bound_is_proven_on_cells_of_l_over_128():
    """The triangle with corners of 16 and 24 degrees on a base of 5.5 l: cells of l/64 hold a path, the nodes no
    placement; on cells of l/128 every split is refuted, which the enumeration of whole splits in PAIR_STEPS could
    not reach (67884 split tests); the sampled enumeration finds no placement either."""
    thetas = (math.radians(16.0), math.radians(24.0))
    lengths = (3.4802343778963283, 5.5, 2.358485811095189)
    inf = (math.inf,) * 4
    assert chain.Chain(thetas, lengths, 1.0, 2, cells=True, radii=inf).search() is not None
    assert chain.Chain(thetas, lengths, 1.0, 2, cells=False, radii=inf).search() is None
    finest = chain.Chain(thetas, lengths, 1.0, 3, cells=True, radii=inf)
    assert finest.search() is None and finest.steps <= chain.PAIR_STEPS
    assert chain.chain_unplaceable(thetas, lengths, 1.0, inf)
    assert sampled_chain(thetas, lengths, 1.0) is None


#: The pair above with the shared side 5.25 l: placeable.
PLACEABLE = (PAIR_LENGTHS[0], 5.25, PAIR_LENGTHS[2])


def _chain(n, extra=()):
    """``parts`` of n positions, each to the next, and the ``extra`` pairs."""
    parts = np.zeros((n, n), dtype=bool)
    parts[np.arange(n - 1), np.arange(1, n)] = True
    for i, j in extra:
        parts[i, j] = True
    return parts


def test_reaches_takes_the_shortest_path_through_the_positions_left():
    """Breadth first: the shortcut 0 -> 2 is taken; without position 2 the chain is cut, with no end nothing."""
    parts, ends = _chain(4, [(0, 2)]), np.array([False, False, False, True])
    left = np.ones(4, dtype=bool)
    assert chain.reaches(parts, left, ends) == [0, 2, 3]
    left[2] = False
    assert chain.reaches(parts, left, ends) is None
    assert chain.reaches(parts, np.ones(4, dtype=bool), np.zeros(4, dtype=bool)) is None


def test_clipped_cuts_cells_to_the_range_and_keeps_those_left_even_a_single_point():
    cells = np.array([0.0, 1.0, 2.0]), np.array([1.0, 2.0, 3.0])
    lo, hi = chain.clipped(cells, 0.5, 2.5)
    assert lo.tolist() == [0.5, 1.0, 2.0] and hi.tolist() == [1.0, 2.0, 2.5]
    lo, hi = chain.clipped(cells, 1.0, 1.0)  # cells touching the range at one point keep that point
    assert lo.tolist() == [1.0, 1.0] and hi.tolist() == [1.0, 1.0]


def test_parts_between_positions_are_between_l_and_2l_up_to_the_tolerance():
    """Nodes 0, 1, 2, 3 at l = 1: parts of exactly l and 2l are in, 3l and 0 are not; l = 2 scales all."""
    for l in (1.0, 2.0):
        x = np.array([0.0, 1.0, 2.0, 3.0]) * l
        parts = chain.parts(x, x, l, 0.0)
        assert np.argwhere(parts).tolist() == [[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]]
    tol = 0.01
    x = np.array([0.0, 1.0 - tol / 2, 2.0 + tol, 1.0 - 2 * tol, 2.0 + 3 * tol])
    assert chain.parts(x, x, 1.0, tol)[0].tolist() == [False, True, True, False, False]


def test_parts_between_cells_ask_only_some_two_points_of_them():
    """From [0, 0.5]: to [1.2, 1.4] and [2.4, 2.6] some part is in [l, 2l] (2.4 - 0.5 one), to [2.6, 2.9] and
    [0.6, 0.9] none."""
    lo, hi = np.array([0.0, 1.2, 2.6, 0.6, 2.4]), np.array([0.5, 1.4, 2.9, 0.9, 2.6])
    parts = chain.parts(lo, hi, 1.0, 0.0)
    assert parts[0].tolist() == [False, True, False, False, True]


def test_cross_takes_the_largest_distance_over_the_corners_of_two_cells():
    """theta = 0 (the two sides on one ray, d = |u - v|), l = 2: each corner of the cells in turn decides."""
    l, far = 2.0, (np.inf, np.inf)
    cell = lambda lo, hi: (np.array([lo]) * l, np.array([hi]) * l)  # noqa: E731
    cases = [
        (cell(0.0, 0.2), cell(1.1, 1.1), True),
        (cell(2.0, 2.2), cell(1.1, 1.1), True),
        (cell(1.1, 1.1), cell(0.0, 0.2), True),
        (cell(1.1, 1.1), cell(2.0, 2.2), True),
        (cell(0.5, 0.7), cell(1.1, 1.3), False),
        (cell(1.0, 1.0), cell(0.0, 0.0), True),
        (cell(0.5, 0.5), cell(0.0, 0.0), False),
    ]
    for mine, theirs, apart in cases:
        assert chain.far_apart(0.0, mine, theirs, l, 0.0, far)[0, 0] == apart
    cell = lambda lo, hi: (np.array([lo]), np.array([hi]))  # noqa: E731
    # at 90 degrees d^2 = u^2 + v^2; the tolerance lowers the bound to ((1 - tol) l)^2
    assert chain.far_apart(np.pi / 2, cell(0.6, 0.6), cell(0.85, 0.85), 1.0, 0.0, far)[0, 0]
    assert not chain.far_apart(np.pi / 2, cell(0.5, 0.5), cell(0.75, 0.75), 1.0, 0.0, far)[0, 0]
    assert chain.far_apart(np.pi / 2, cell(0.5, 0.5), cell(0.75, 0.75), 1.0, 0.2, far)[0, 0]
    assert not chain.far_apart(np.pi / 2, cell(0.5, 0.5), cell(0.6, 0.6), 1.0, 0.2, far)[0, 0]
    # at 60 degrees d^2 = u^2 + v^2 - u v: (1, 1) is exactly l apart, (0.9, 1) is not
    assert chain.far_apart(np.pi / 3, (np.ones(1), np.ones(1)), (np.ones(1), np.ones(1)), 1.0, 1e-9, far)[0, 0]
    assert not chain.far_apart(np.pi / 3, cell(0.9, 0.9), cell(1.0, 1.0), 1.0, 0.0, far)[0, 0]


def test_cross_does_not_check_pairs_beyond_the_radii():
    """A close pair counts as apart once either cell reaches past its radius (strictly)."""
    mine, theirs = (np.array([0.5]), np.array([0.6])), (np.array([0.3]), np.array([0.4]))
    close = lambda radii: chain.far_apart(0.0, mine, theirs, 1.0, 0.0, radii)[0, 0]  # noqa: E731
    assert not close((np.inf, np.inf)) and not close((0.6, 0.4)) and not close((0.6, 0.5))
    assert close((0.59, np.inf)) and close((np.inf, 0.39)) and close((0.5, 0.6))


def test_side_nodes_are_the_multiples_of_the_step_from_either_end_and_a_long_side_stops_past_k_l():
    """l = 2, step l/4, K l = 6: a side of 5.3 has the multiples of 0.5 from both ends and stops at its far end; one
    of 12 = K l + 3l is still short; one of 12.5 is long: nodes up to K l + 2l = 10, any past K l an end."""
    l, step, reach = 2.0, 0.5, 6.0
    lo, hi, ends, _ = chain.side(5.3, reach, l, step, False, 0.0)
    expected = {0.0} | {k * step for k in range(1, 11)} | {5.3 - k * step for k in range(11)}
    assert lo.tolist() == sorted(expected) and hi is lo
    assert np.flatnonzero(ends).tolist() == [len(lo) - 1]
    for length in (12.0, 10.0):
        lo, _, ends, _ = chain.side(length, reach, l, step, False, 0.0)
        assert lo.tolist() == (np.arange(2 * length + 1) * step).tolist()
        assert np.flatnonzero(ends).tolist() == [2 * length]
    lo, _, ends, parts = chain.side(12.5, reach, l, step, False, 0.0)
    assert lo.tolist() == (np.arange(21) * step).tolist() and np.flatnonzero(ends).tolist() == list(range(12, 21))
    assert (parts == chain.parts(lo, lo, l, 0.0)).all()


def test_side_cells_clip_those_of_the_first_and_last_points_and_order_the_kinds():
    """l = 2, step 1, a side of 5: cells of 1, the first point's copies cut to [2, 4], the last point's to [1, 3],
    both; the corner leads to a first cell (or both), a last cell (or both) to the far end, inner to inner or last."""
    lo, hi, ends, parts = chain.side(5.0, 6.0, 2.0, 1.0, True, 0.0)
    assert lo.tolist() == [0, 0, 1, 2, 3, 4, 2, 2, 3, 4, 1, 1, 2, 3, 2, 2, 3, 5]
    assert hi.tolist() == [0, 1, 2, 3, 4, 5, 2, 3, 4, 4, 1, 2, 3, 3, 2, 3, 3, 5]
    assert np.flatnonzero(ends).tolist() == [17]
    assert np.flatnonzero(parts[0]).tolist() == [6, 7, 8, 9, 14, 15, 16]
    assert np.flatnonzero(parts[1]).tolist() == [2, 3, 4, 5, 11, 12, 13]
    assert np.flatnonzero(parts[6]).tolist() == [4, 5] and np.flatnonzero(parts[7]).tolist() == [4, 5]
    assert np.flatnonzero(parts[:, 17]).tolist() == [10, 11, 12, 13, 14, 15, 16]
    assert not parts[10:17, :17].any() and not parts[17].any()


def test_long_side_cells_go_a_cell_past_k_l_plus_2l_and_end_at_any_cell_reaching_k_l():
    """l = 2, step 1, K l = 6, a side of 13 > K l + 3l: cells up to 10, no far end and no last-point cells."""
    lo, hi, ends, parts = chain.side(13.0, 6.0, 2.0, 1.0, True, 0.0)
    assert lo.tolist() == [0, *range(10), 2, 2, 3, 4] and hi.tolist() == [0, *range(1, 11), 2, 3, 4, 4]
    assert np.flatnonzero(ends).tolist() == [6, 7, 8, 9, 10]
    assert np.flatnonzero(parts[0]).tolist() == [11, 12, 13, 14]


def test_a_decision_past_pair_steps_tests_is_left_undecided(monkeypatch):
    """The search of the placeable pair takes some number of distinct split tests: with exactly that many allowed
    it ends, with one fewer it is undecided; then place_chain finds nothing and chain_unplaceable proves nothing."""
    inf = (math.inf,) * 4
    search = chain.Chain(PAIR_THETAS, PLACEABLE, 1.0, 0, cells=False, radii=inf)
    assert search.search() is not None
    steps = search.steps
    assert steps == len(search.tested) > 1
    monkeypatch.setattr(chain, "PAIR_STEPS", steps)
    assert chain.Chain(PAIR_THETAS, PLACEABLE, 1.0, 0, cells=False, radii=inf).search() is not None
    monkeypatch.setattr(chain, "PAIR_STEPS", steps - 1)
    with pytest.raises(chain.Undecided):
        chain.Chain(PAIR_THETAS, PLACEABLE, 1.0, 0, cells=False, radii=inf).search()
    assert chain.place_chain(PAIR_THETAS, PLACEABLE, 1.0) is None
    monkeypatch.setattr(chain, "PAIR_STEPS", 0)
    assert not chain.chain_unplaceable(PAIR_THETAS, PAIR_LENGTHS, 1.0, inf)


def test_a_corner_neither_placed_nor_refuted_on_the_first_grid_is_placed_on_a_finer_one(monkeypatch):
    """12.41 degrees alone, sides of 2.837 l and 3.606 l (S): the nodes of l/16 hold no placement and the cells of
    l/16 refute nothing, the nodes of l/32 hold one; with no refinement allowed nothing is found."""
    thetas, lengths = (math.radians(12.41194009983165), None), (2.8369711193150855, 3.6063879049743512, 0.0)
    inf = (math.inf,) * 4
    assert chain.Chain(thetas, lengths, 1.0, 0, cells=False, radii=inf).search() is None
    assert chain.Chain(thetas, lengths, 1.0, 0, cells=True, radii=inf).search() is not None
    a, s, _ = chain.place_chain(thetas, lengths, 1.0)
    assert_placement(thetas[0], (lengths[1], lengths[0]), 1.0, (s, a))
    assert not chain.chain_unplaceable(thetas, lengths, 1.0, inf)
    monkeypatch.setattr(chain, "CORNER_REFINEMENTS", 0)
    assert chain.place_chain(thetas, lengths, 1.0) is None


def test_side_cells_clip_to_ranges_widened_by_the_tolerance():
    """As above with tol = 0.1: the first point's cells cut to [1.8, 4.4], the last point's to [0.6, 3.2]."""
    lo, hi, ends, _ = chain.side(5.0, 6.0, 2.0, 1.0, True, 0.1)
    assert lo.tolist() == pytest.approx([0, 0, 1, 2, 3, 4, 1.8, 2, 3, 4, 0.6, 1, 2, 3, 1.8, 2, 3, 5])
    assert hi.tolist() == pytest.approx([0, 1, 2, 3, 4, 5, 2, 3, 4, 4.4, 1, 2, 3, 3.2, 2, 3, 3.2, 5])
    assert np.flatnonzero(ends).tolist() == [17]


def test_the_shared_side_couples_the_corners_up_to_k1_l_plus_k2_l_plus_4l():
    """30 and 10 degrees (K = 2 and 6) at l = 2: coupled up to 2 l + 6 l + 4 l = 24 exactly, either order."""
    for thetas in [(math.radians(30.0), math.radians(10.0)), (math.radians(10.0), math.radians(30.0))]:
        assert chain.coupled(thetas, (1.0, 24.0, 1.0), 2.0)
        assert not chain.coupled(thetas, (1.0, 24.000001, 1.0), 2.0)
    assert chain.coupled((math.radians(30.0), None), (1.0, 100.0, 0.0), 2.0)


def test_the_tolerances_of_the_search_and_of_the_proof():
    """A right angle with A a single part a little below l (S of 2l): the search's nodes take parts down to
    (1 - REL_TOL / 4) l, the proof's cells down to (1 - 2 REL_TOL) l (pairs are far apart here)."""
    thetas, inf = (math.pi / 2, None), (math.inf,) * 4
    side = lambda below: (1.0 - below * REL_TOL, 2.0, 0.0)  # noqa: E731
    a, s, _ = chain.place_chain(thetas, side(0.22), 1.0)
    assert a.tolist() == [side(0.22)[0]] and s[-1] == 2.0
    assert chain.place_chain(thetas, side(0.3), 1.0) is None
    assert not chain.chain_unplaceable(thetas, side(1.9), 1.0, inf)
    assert chain.chain_unplaceable(thetas, side(2.5), 1.0, inf)


def test_the_first_points_are_kept_from_the_other_side_from_the_start():
    """10 degrees with A = l: its only point, l from the corner, is closer than l to every point of S but one
    at 2 cos(10 deg) l or more; with S = 2l the first point of S is its end, and at a right angle on the other
    side the same holds for B.  Nothing else is removed at the start: the corners are no points of the other side."""
    ten = math.radians(10.0)
    assert [p.tolist() for p in chain.place_chain((ten, None), (1.0, 2.0, 0.0), 1.0)] == [[1.0], [2.0], []]
    assert [p.tolist() for p in chain.place_chain((math.pi / 2, ten), (1.0, 2.0, 1.0), 1.0)] == [[1.0], [2.0], [1.0]]
    pair = chain.Chain((math.pi / 2, ten), (1.0, 2.0, 1.0), 1.0, 0, cells=False, radii=(math.inf,) * 4)
    assert [p.tolist() for p in pair.search()] == [[1.0], [2.0], [1.0]]  # on the first grid already
    s = pair.sides[1][0]
    for cross, (s, side) in [(pair.back, (s, pair.sides[0][0])), (pair.ahead[1], (2.0 - s, pair.sides[2][0]))]:
        theta = math.pi / 2 if cross is pair.back else ten
        d2 = s[:, None] ** 2 + side[None, :] ** 2 - 2.0 * math.cos(theta) * s[:, None] * side[None, :]
        expected = d2 >= (1.0 - REL_TOL / 4.0) ** 2
        expected[:, 0] = True
        expected[0 if cross is pair.back else -1] = True
        assert (cross == expected).all()


def test_a_lone_corner_stops_the_shared_side_past_k_l():
    """30 degrees alone (K = 2) with S of 20 l: S stops at its first point past 2 l, not at its far end."""
    a, s, b = chain.place_chain((math.radians(30.0), None), (3.0, 20.0, 0.0), 1.0)
    assert 2.0 <= s[-1] <= 4.0 and len(b) == 0


def test_the_proof_uses_cells_on_every_side_and_a_radius_drops_the_pairs_of_its_corner():
    """Cells have width (hi > lo) on A, S and B; a radius of 0 makes every pair of its corner count as apart."""
    pair = chain.Chain(PAIR_THETAS, PAIR_LENGTHS, 1.0, 0, cells=True, radii=(math.inf,) * 4)
    for lo, hi, *_ in pair.sides:
        assert (hi >= lo).all() and (hi > lo).any()
    assert not pair.back.all() and not pair.ahead[1].all()
    for i in range(4):
        radii = tuple(0.0 if j == i else math.inf for j in range(4))
        pair = chain.Chain(PAIR_THETAS, PAIR_LENGTHS, 1.0, 0, cells=True, radii=radii)
        assert pair.back.all() == (i < 2) and pair.ahead[1].all() == (i >= 2)


def test_a_pair_refuted_only_on_finer_cells_is_proven_there(monkeypatch):
    """Corners of 16.11 and 14.64 degrees, sides of 3.905, 4.621 and 3.742 l: the cells of l/16 refute nothing and
    its nodes hold no placement, the cells of l/32 refute every split; allowed no refinement, nothing is proven."""
    thetas = (0.2811920832642171, 0.2556000676733454)
    lengths = (3.9053127292452765, 4.621055221556947, 3.7424774384218624)
    inf = (math.inf,) * 4
    assert chain.Chain(thetas, lengths, 1.0, 0, cells=True, radii=inf).search() is not None
    assert chain.Chain(thetas, lengths, 1.0, 0, cells=False, radii=inf).search() is None
    assert chain.chain_unplaceable(thetas, lengths, 1.0, inf)
    assert chain.place_chain(thetas, lengths, 1.0) is None
    monkeypatch.setattr(chain, "PAIR_REFINEMENTS", 1)
    assert chain.chain_unplaceable(thetas, lengths, 1.0, inf)
    monkeypatch.setattr(chain, "PAIR_REFINEMENTS", 0)
    assert not chain.chain_unplaceable(thetas, lengths, 1.0, inf)


def test_useful_keeps_the_positions_on_some_split_only():
    """0 -> 1 -> 2 -> 3 (the end), with 4 reached from 1 but leading nowhere and 5 leading to the end but not
    reached: only 0 to 3 are on a split; with 2 gone nothing is, and positions not left are never kept."""
    parts = np.pad(_chain(4), ((0, 2), (0, 2)))
    parts[1, 4] = parts[5, 3] = True
    ends = np.array([False, False, False, True, False, False])
    assert np.flatnonzero(chain.useful(parts, np.ones(6, dtype=bool), ends)).tolist() == [0, 1, 2, 3]
    left = np.ones(6, dtype=bool)
    left[2] = False
    assert chain.useful(parts, left, ends) is None
    parts[1, 3] = True
    assert np.flatnonzero(chain.useful(parts, left, ends)).tolist() == [0, 1, 3]


def test_a_side_couples_its_corners_up_to_k1_l_plus_k2_l_plus_4l_in_a_chain_too():
    """The chain is coupled when every shared side is: 30, 10 and 30 degrees (K = 2, 6, 2) at l = 2 with shared
    sides of 24 (the limit) and 24.000001 (past it) in either place."""
    thetas = tuple(math.radians(x) for x in (30.0, 10.0, 30.0))
    assert chain.shared(thetas[:2], 24.0, 2.0) and not chain.shared(thetas[:2], 24.000001, 2.0)
    assert chain.coupled(thetas, (1.0, 24.0, 24.0, 1.0), 2.0)
    assert not chain.coupled(thetas, (1.0, 24.0, 24.000001, 1.0), 2.0)
    assert not chain.coupled(thetas, (1.0, 24.000001, 24.0, 1.0), 2.0)


def test_a_long_last_side_stops_past_its_own_corners_k_l():
    """Corners of 12 and 40 degrees (K = 5 and 2) with T_2 6 l long: longer than 2 l + 3 l, so it stops at a point past
    its own corner's K l = 2 l (with the first corner's 5 l it would not be long and would end at its far end)."""
    thetas = (math.radians(12.0), math.radians(40.0))
    found = chain.place_chain(thetas, (3.0, 6.0, 6.0), 1.0)
    assert chain.corner_reach(thetas[1], 1.0) == 2.0
    assert 2.0 <= found[-1][-1] <= 5.0


def test_entering_a_shared_side_removes_the_positions_of_the_next_side_near_its_first_corner():
    """Corners of 46, 48 and 16.75 degrees with T_2 only 1.1 l long: corner 1, where T_2 starts, is a point of corner
    2's
    side T_2 and is closer than l to T_3's point 2 l from corner 2 (0.998 l).  Entering T_2 at corner 1 removes such
    positions of T_3: no placement, refuted (from T_2's first grid point instead, the search would place T_3 at 2 l)."""
    thetas = tuple(math.radians(a) for a in (46.0, 48.0, 16.75))
    lengths = (1.5, 4.25, 1.1, 3.75)
    assert math.dist((1.1, 0.0), (2.0 * math.cos(thetas[2]), 2.0 * math.sin(thetas[2]))) < 1.0
    assert chain.place_chain(thetas, lengths, 1.0) is None
    assert chain.chain_unplaceable(thetas, lengths, 1.0, (math.inf,) * 6)


def test_a_proof_past_the_work_it_shares_is_left_undecided():
    """The proof of the unplaceable pair reduces some number of positions: with exactly that much work shared it is
    proven, with one position less it is not; a second proof charged to the same exhausted work proves nothing."""
    inf = (math.inf,) * 4
    measured = chain.Work(math.inf)
    assert chain.chain_unplaceable(PAIR_THETAS, PAIR_LENGTHS, 1.0, inf, measured)
    assert measured.spent > 0
    assert chain.chain_unplaceable(PAIR_THETAS, PAIR_LENGTHS, 1.0, inf, chain.Work(measured.spent))
    short = chain.Work(measured.spent - 1)
    assert not chain.chain_unplaceable(PAIR_THETAS, PAIR_LENGTHS, 1.0, inf, short)
    assert short.spent > short.limit
    assert not chain.chain_unplaceable(PAIR_THETAS, PAIR_LENGTHS, 1.0, inf, short)


def test_a_proof_charges_its_searches_on_nodes_too():
    """The pair proven only on cells of l/128: the searches on the nodes of the coarser grids, which find nothing, are
    charged to the work shared as the cells are, so it spends more than the cells' searches alone."""
    thetas = (math.radians(16.0), math.radians(24.0))
    lengths = (3.4802343778963283, 5.5, 2.358485811095189)
    inf = (math.inf,) * 4
    shared = chain.Work(math.inf)
    assert chain.chain_unplaceable(thetas, lengths, 1.0, inf, shared)
    cells = []
    for level in range(4):
        cells.append(chain.Work(math.inf))
        chain.Chain(thetas, lengths, 1.0, level, cells=True, radii=inf, work=cells[-1]).search()
    assert shared.spent > sum(work.spent for work in cells)


def test_work_is_charged_one_per_position_of_each_new_reduction():
    """Each distinct set of positions reduced spends its side's positions once (cached sets spend nothing)."""
    inf = (math.inf,) * 4
    work = chain.Work(math.inf)
    proof = chain.Chain(PAIR_THETAS, PAIR_LENGTHS, 1.0, 0, cells=True, radii=inf, work=work)
    assert proof.search() is None
    sizes = [len(proof.sides[side][0]) for side, _ in proof.tested]
    assert work.spent == sum(sizes) and len(sizes) == proof.steps


def test_a_point_leaving_the_next_side_no_split_reduces_nothing_of_t0(monkeypatch):
    """Corners of 49.6, 35.3 and 24 degrees (sides 1.19, 2.34, 2.43, 1.16 l): the first cells refute the chain with 7
    distinct reductions; a point of T_1 that leaves T_2 no split is dropped before T_0's positions are reduced for it
    (reducing them too would count an 8th and pass the bound)."""
    thetas, lengths = tuple(math.radians(a) for a in (49.6, 35.3, 24.0)), (1.19, 2.34, 2.43, 1.16)
    monkeypatch.setattr(chain, "PAIR_STEPS", 7)
    proof = chain.Chain(thetas, lengths, 1.0, 0, cells=True, radii=(math.inf,) * 6)
    assert proof.search() is None and proof.steps == 7


class _Forgetful(set):
    """A memo of dead prefixes that remembers none: the search then tries every prefix in full."""

    def __contains__(self, key):
        return False


@pytest.mark.parametrize(
    "degrees, lengths, side, point",
    [((4.5, None), (7.001, 7.9317, 0.0), 1, 3.9942), ((45.0, 45.0, 10.5), (2.91, 1.99, 5.68, 6.05), 2, 2.68)],
)
def test_the_dead_prefix_memo_drops_no_prefix_that_has_a_continuation(degrees, lengths, side, point):
    """Whether a prefix continues depends on the side enumerated, its last point and the positions left on the
    sides still read: T_0 and T_2 while T_1 is enumerated, T_k and T_(k+1) after it.  A prefix reaching a
    failed state again is dropped, so the search returns what it returns remembering nothing.

    4.5 degrees alone (A 7.001 l, S 7.9317 l): S's node 3.9942 l is reached first after 1.9942 l, which leaves A
    no point at 1.001 l, and fails; then after 2 l, with A's split 1.001, 3.001, 5.001, 7.001 l left, and
    continues.  Corners of 45, 45 and 10.5 degrees (sides 2.91, 1.99, 5.68, 6.05 l): T_2's node 2.68 l is
    reached after 1 l, which leaves T_3 no position between 1.0625 l and 2.05 l from corner 2, and fails;
    after 1.1175 l T_3 keeps 1.9875 l and it continues.  A key without T_0's positions (the first) or T_3's
    (the second) drops the second prefix and returns another placement."""
    thetas = tuple(None if d is None else math.radians(d) for d in degrees)
    chains = [chain.Chain(thetas, lengths, 1.0, 0, cells=False, radii=(math.inf,) * 6) for _ in range(2)]
    chains[1].dead = _Forgetful()
    found, expected = (search.search() for search in chains)
    assert len(found) == len(expected) and all(np.array_equal(a, b) for a, b in zip(found, expected))
    assert point in np.round(found[side], 4)  # the point on the second prefix
    assert chains[0].dead
