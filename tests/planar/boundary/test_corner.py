"""Step 2 at one sharp corner decided on a grid (``planar/boundary/corner.py``; docs/proofs.md, "Sharp corners").

What must hold: the merged-order lemma (consecutive cross pairs decide every cross pair); every placement
the search returns has parts in [l, 2l], ends at the far corners and keeps every cross pair l apart
(checked pair by pair here); the proof never contradicts a placement; and a corner it proves impossible has
no placement on a sampled grid either (``tests/corner_sampling.py``, independently of the module).
"""

import math

import numpy as np
import pytest
from corner_sampling import assert_placement, cross, sampled_placement
from hypothesis import given
from hypothesis import strategies as st

from equimesh.planar.boundary import corner
from equimesh.tolerance import REL_TOL


@pytest.fixture(autouse=True)
def _no_cached_relaxation():
    """Each test computes the relaxation afresh (corner.relaxed is cached per corner across calls)."""
    corner.relaxed.cache_clear()


parts = st.lists(st.floats(1.0, 2.0), min_size=1, max_size=8)


@given(st.floats(0.5, 60.0), parts, parts)
def test_consecutive_cross_pairs_in_merged_order_decide_every_cross_pair(angle, parts_a, parts_b):
    """The merged-order lemma: if every two points of different sides that are consecutive by distance from the
    corner are l apart, every two points of different sides are (parts of at least l on each side)."""
    theta = math.radians(angle)
    a, b = np.cumsum(parts_a), np.cumsum(parts_b)
    merged = sorted([(x, 0) for x in a] + [(x, 1) for x in b])
    consecutive = [cross(theta, [u], [w])[0, 0] for (u, s), (w, t) in zip(merged, merged[1:]) if s != t]
    if min(consecutive, default=math.inf) >= 1.0:
        assert cross(theta, a, b).min() >= 1.0 - 1e-12


@given(st.floats(5.0, 59.0), st.floats(1.0, 9.0), st.floats(1.0, 9.0), st.sampled_from([1.0, 1.5]))
def test_a_placement_found_meets_lemma_3_and_is_never_proven_impossible(angle, a, b, l):
    """Whatever place_corner returns is a placement (checked pair by pair), and corner_unplaceable (which claims
    a proof) never says impossible where a placement exists: the relaxation is checked against the search."""
    theta, lengths = math.radians(angle), (a * l, b * l)
    found = corner.place_corner(theta, lengths, l)
    if found is not None:
        assert_placement(theta, lengths, l, found)
        assert not corner.corner_unplaceable(theta, lengths, l, (math.inf, math.inf))


def test_a_placement_off_every_grid_is_found_by_tightening():
    """17.46 degrees with sides of 4.132 l: the placements form a sliver that the grids of 1/16 to 1/64 l miss;
    the order of the relaxation's path, pushed as near the corner as it allows (corner.tighten), is one."""
    theta, lengths = math.radians(17.460507302465036), (4.132016938510646, 4.132016938510646)
    reach = corner.corner_reach(theta, 1.0)
    for grid in (16, 32, 64):
        nodes = corner.nodes(lengths, reach, 1.0, 1.0 / grid, (None, None))
        assert (
            corner.Graph(theta, lengths, reach, 1.0, nodes, nodes, REL_TOL / 4.0, (math.inf, math.inf)).search() is None
        )
    found = corner.place_corner(theta, lengths, 1.0)
    assert_placement(theta, lengths, 1.0, found)
    assert [points.tolist() for points in found] == [
        [1.0, 2.6398839449125027, 4.132016938510646],
        [1.9078479878943455, 3.12864928468156, 4.132016938510646],
    ]


def test_a_long_side_is_cut_past_k_l_and_kept_sides_are_kept():
    """5 degrees with sides of 40 l (K = 12): both sides stop at their first point past 12 l; with the leaving
    side given (multiples of 2 l), it is returned as given."""
    theta, lengths = math.radians(5.0), (40.0, 40.0)
    found = corner.place_corner(theta, lengths, 1.0)
    assert_placement(theta, lengths, 1.0, found)
    assert all(12.0 <= points[-1] < 14.0 for points in found)
    kept = np.arange(1, 8) * 2.0 - 1.0
    found = corner.place_corner(theta, lengths, 1.0, (kept, None))
    assert found is not None and np.array_equal(found[0], kept)
    assert_placement(theta, lengths, 1.0, found)


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
    assert corner.corner_unplaceable(theta, (a, b), 1.0, (math.inf, math.inf))
    assert corner.place_corner(theta, (a, b), 1.0) is None
    assert sampled_placement(theta, (a, b), 1.0) is None


def test_the_enumeration_finds_placements_where_they_exist():
    """The enumeration above is not vacuous: 20 degrees with sides of 3.4 and 3 l (the thin triangle of
    results/sharp_corners.md meshed by the search) has a placement on steps of l/8."""
    assert sampled_placement(math.radians(20.0), (3.4, 3.0), 1.0) is not None


def test_visibility_radii_drop_the_pairs_beyond_them():
    """The 20-degree corner with sides 3.4553 is proven impossible with every pair checked; with no pair seen
    (radii 0) nothing is proven."""
    theta = math.radians(20.0)
    assert corner.corner_unplaceable(theta, (3.4553, 3.4553), 1.0, (math.inf, math.inf))
    assert not corner.corner_unplaceable(theta, (3.4553, 3.4553), 1.0, (0.0, 0.0))


def test_visibility_radii_belong_to_their_sides():
    """5.83 degrees with sides 3.5 (leaving) and 2.5473: proven when the leaving side is seen up to 2.5 l and the
    arriving one whole, not the other way round."""
    theta, lengths = math.radians(5.83171), (3.5, 2.5473)
    assert corner.corner_unplaceable(theta, lengths, 1.0, (2.5, math.inf))
    assert not corner.corner_unplaceable(theta, lengths, 1.0, (math.inf, 2.5))


def _corners(seed, count, angles, sides):
    """``count`` corners ``(degrees, A / l, B / l, l)`` drawn from ``seed``: angles and side lengths uniform in the
    given ranges, rounded."""
    rng = np.random.default_rng(seed)
    return [
        (
            round(float(rng.uniform(*angles)), 2),
            *np.round(rng.uniform(*sides, 2), 3).tolist(),
            float(rng.choice([1.0, 1.5])),
        )
        for _ in range(count)
    ]


def _corner_fingerprint(corners):
    """The proof's answers (every pair seen, and only within half of each side) and the search's placements, each
    with its leaving side kept, summed: (proven, index-weighted proven, points, index-weighted sum of the points).
    """
    proven, weighted_proven, points, weighted = 0, 0, 0, 0.0
    for k, (angle, a, b, l) in enumerate(corners, 1):
        theta, lengths = math.radians(angle), (a * l, b * l)
        for radii in ((math.inf, math.inf), (a * l / 2.0, b * l / 2.0)):
            decided = corner.corner_unplaceable(theta, lengths, l, radii)
            proven, weighted_proven = proven + decided, weighted_proven + k * decided
        found = corner.place_corner(theta, lengths, l)
        if found is None:
            continue
        assert_placement(theta, lengths, l, found)
        again = corner.place_corner(theta, lengths, l, (found[0], None))
        if again is not None:  # None where found came from corner.tighten, off the grid (the search alone misses it)
            assert np.array_equal(again[0], found[0])
            assert_placement(theta, lengths, l, again)
            found = (*found, *again)
        at = np.concatenate(found)
        points, weighted = points + len(at), weighted + k * float(np.dot(np.round(at, 9), np.arange(1, len(at) + 1)))
    return proven, weighted_proven, points, round(weighted, 6)


def test_corner_fingerprint_short_sides():
    """40 corners of 3 to 45 degrees with sides of 1 to 8 l: the proof and the search pinned by sums (a fingerprint,
    as in dmsh's tests; a change to either changes them), every placement checked pair by pair."""
    assert _corner_fingerprint(_corners(5, 40, (3.0, 45.0), (1.0, 8.0))) == (15, 345, 204, 82530.326293)


def test_corner_fingerprint_long_sides():
    """8 corners of 12 to 25 degrees (K = 3 to 5) with sides of 6 to 30 l, most longer than (K + 3) l and cut past
    K l."""
    assert _corner_fingerprint(_corners(6, 8, (12.0, 25.0), (6.0, 30.0))) == (0, 0, 74, 7138.78125)


TOL = REL_TOL / 4.0  # the tolerance of corner.placed's checks


FAR = 2.0**-31  # TOL * FAR_L exactly, a multiple of the ulp of 3.5: a far end exactly at the tolerance


FAR_L = 1.862645149230957


EXACT = 3.464101614560404  # at 30 degrees and l = 2, its squared distance from 2 is ((1 - TOL) l)^2 to the last bit


@pytest.mark.parametrize(
    "angle, l, lengths, xs, ys, placed",
    [
        (90.0, 2.0, (6.0, 4.0), [2.0, 6.0], [2.0, 4.0], True),
        (90.0, 2.0, (6.0, 4.0), [2.0, 6.0], [2.0, 4.5], False),  # the arriving side does not end at its far end
        (
            90.0,
            2.0,
            (4.0 + (1.0 - TOL) * 2.0,) * 2,
            [(1.0 - TOL) * 2.0, 4.0 + (1.0 - TOL) * 2.0],
            [2.0, 4.0 + (1.0 - TOL) * 2.0],
            True,
        ),
        (90.0, 2.0, (6.0, 4.0), [(1.0 - 0.9 * TOL) * 2.0, 6.0], [2.0, 4.0], True),
        (90.0, 2.0, (6.0, 4.0), [(1.0 - 2.0 * TOL) * 2.0, 6.0], [2.0, 4.0], False),
        (90.0, 2.0, (2.0 * (1.0 + TOL) * 2.0, 4.0), [2.0 * (1.0 + TOL) * 2.0], [2.0, 4.0], True),
        (90.0, 2.0, (2.0 * (1.0 + 2.0 * TOL) * 2.0, 4.0), [2.0 * (1.0 + 2.0 * TOL) * 2.0], [2.0, 4.0], False),
        (
            90.0,
            2.0,
            (12.0, 4.0),
            [2.0, 4.0, 6.0, 8.0, 10.0],
            [2.0, 4.0],
            True,
        ),  # a long side: its last point l before the end
        (90.0, 2.0, (12.0, 4.0), [2.0, 4.0, 6.0, 8.0, 10.5], [2.0, 4.0], False),
        (90.0, FAR_L, (3.5, 3.5), [3.5 + FAR], [3.5], True),  # a far end missed by exactly TOL l is moved onto it
        (90.0, FAR_L, (3.5, 3.5), [3.5 + 2.0 * FAR], [3.5], False),
        (30.0, 2.0, (4.0, 4.0), [2.0, 4.0], [4.0], True),
        (30.0, 2.0, (4.0, 4.0), [2.0, 4.0], [2.0, 4.0], False),  # the first points 1.04 apart
        (30.0, 2.0, (4.0, EXACT), [2.0, 4.0], [EXACT], True),  # a cross pair at (1 - TOL) l exactly
    ],
)
def test_placed_checks_parts_ends_and_cross_pairs_at_their_tolerance(angle, l, lengths, xs, ys, placed):
    """corner.placed accepts parts from (1 - TOL) l to 2 (1 + TOL) l, far ends within TOL l (moved onto them), a long
    side's last point up to l before its end, cross pairs from (1 - TOL) l; each threshold exactly and just past."""
    theta = math.radians(angle)
    sides, z = np.array([0] * len(xs) + [1] * len(ys)), np.array(xs + ys)
    found = corner.placed(theta, lengths, corner.corner_reach(theta, l), l, sides, z)
    assert (found is not None) == placed
    if placed:
        assert [points.tolist() for points in found] == [xs[:-1] + [min(xs[-1], lengths[0])], ys]


def test_cut_keeps_a_long_sides_points_up_to_the_first_past_k_l():
    """K l = 12 (5 degrees): a side longer than 15 l keeps its points up to the first at or past 12; one of 15 l is
    not cut."""
    odd, even = np.arange(1.0, 40.0, 2.0), np.arange(2.0, 40.0, 2.0)
    assert corner.cut(odd, 40.0, 12.0, 1.0).tolist() == [1.0, 3.0, 5.0, 7.0, 9.0, 11.0, 13.0]
    assert corner.cut(even, 15.5, 12.0, 1.0).tolist() == [2.0, 4.0, 6.0, 8.0, 10.0, 12.0]
    assert corner.cut(even, 15.0, 12.0, 1.0) is even


def test_cells_and_nodes_by_hand():
    """K l = 6 and sides 3.125 and 20 (long: past K l + 3 l) at a step of 1/4: the search's nodes are the multiples of
    the step up to K l + 2 l = 8, the short side's far end less multiples of the step, and the points kept; the
    proof's cells cover [0, 8.25] in steps (one more than 8 needs),
    with the corner and the short side's far end as points."""
    lengths, step = (3.125, 20.0), 0.25
    nodes = corner.nodes(lengths, 6.0, 1.0, step, (np.array([1.1, 3.125]), None))
    assert nodes.tolist() == sorted(
        {0.0, 1.1} | {step * k for k in range(1, 33)} | {3.125 - step * k for k in range(12)}
    )
    lo, hi = corner.cells(lengths, 6.0, 1.0, step)
    assert lo.tolist() == [0.0, *(step * k for k in range(33)), 3.125]
    assert hi.tolist() == [0.0, *(step * k for k in range(1, 34)), 3.125]
    assert corner.horizon((20.0, 9.0), 6.0, 1.0) == 9.0 and corner.horizon((9.5, 7.0), 6.0, 1.0) == 8.0


def test_far_enough_cells_against_sampled_points():
    """Graph.far_enough on cells: some u of cell p and v >= u of cell w with u^2 + v^2 - 2 c u v >= short^2, the
    same answer as sampling each cell (ends included) and the diagonal v = u where the cells overlap (the largest value
    of the convex quadratic lies at a corner of that region); on random cells, points and overlaps, at 3 angles."""
    rng = np.random.default_rng(3)
    lo = np.round(rng.uniform(0.0, 4.0, 40), 3)
    hi = lo + np.where(rng.random(40) < 0.3, 0.0, np.round(rng.uniform(0.0, 1.5, 40), 3))
    cells = type("Cells", (), {"lo": lo, "hi": hi, "n": len(lo)})()
    samples = np.linspace(0.0, 1.0, 9)
    for angle in (10.0, 35.0, 80.0):
        c, short = math.cos(math.radians(angle)), 1.0
        far = corner.Graph.far_enough(cells, math.radians(angle), short)
        for p in range(len(lo)):
            for w in range(len(lo)):
                u = lo[p] + (hi[p] - lo[p]) * samples
                v = lo[w] + (hi[w] - lo[w]) * samples
                first, last = max(lo[p], lo[w]), min(hi[p], hi[w])
                uu, vv = np.meshgrid(u, v)
                uu, vv = uu.ravel(), vv.ravel()
                if first <= last:
                    uu, vv = np.append(uu, [first, last]), np.append(vv, [first, last])
                ok = vv >= uu
                best = np.max(uu[ok] ** 2 + vv[ok] ** 2 - 2.0 * c * uu[ok] * vv[ok], initial=-1.0)
                assert far[p, w] == (best >= short * short), (angle, p, w)


@pytest.mark.parametrize(
    "angle, sides, placed",
    [
        (
            8.0,
            [1, 0, 1, 0, 0, 0],
            [[2.0, 4.0, 6.0, 8.0], [1.0, 3.0]],
        ),  # the last point pushed to K l = 8, the rest 2 l back
        (15.0, [1, 0, 1, 0, 0], [[1.9318516525781366, 3.5279475487927563, 4.527947548792756], [1.0, 3.0]]),
    ],
)
def test_tighten_by_hand(angle, sides, placed):
    """A long leaving side (12 l) and an arriving one of 3 l in a given merged order: each point at the largest of its
    lower bounds (l past the point before it on its side, G of the other side's point before it, K l for the long
    side's last point, 2 l before the next point of its side)."""
    theta = math.radians(angle)
    found = corner.tighten(theta, (12.0, 3.0), corner.corner_reach(theta, 1.0), 1.0, sides)
    assert [points.tolist() for points in found] == placed


def test_tighten_and_the_reach_scale_with_l():
    """The 8 degree order above at l = 1.5 is the same placement scaled; K at 30 degrees is 2 although 1 / sin 30
    degrees rounds to 2 + 4e-16 (the 1 - REL_TOL of K)."""
    theta = math.radians(8.0)
    found = corner.tighten(theta, (18.0, 4.5), corner.corner_reach(theta, 1.5), 1.5, [1, 0, 1, 0, 0, 0])
    assert [points.tolist() for points in found] == [[3.0, 6.0, 9.0, 12.0], [1.5, 4.5]]
    assert corner.corner_reach(math.radians(30.0), 1.5) == 3.0


def test_horizon_of_a_long_side_is_k_l_plus_2l_at_any_l():
    """At l = 2 and K l = 12 a long side (past K l + 3 l = 18) is read up to K l + 2 l = 16, a short one whole."""
    assert corner.horizon((40.0, 9.0), 12.0, 2.0) == 16.0
    assert corner.horizon((17.0, 9.0), 12.0, 2.0) == 17.0


def test_beyond_the_radii_only_past_them():
    """A point (or a cell's far end) exactly at its side's visibility radius is seen; only one past it is not."""
    beyond = corner.beyond(np.array([0.0, 1.0, 2.0]), 1.0, 2.0)
    assert beyond.tolist() == [[False, False, False], [False, False, False], [True, True, True]]


def _graph(lo, lengths, hi=None):
    """The graph at theta = 0 (the distance of u and v is |u - v|) with tolerance 0, so that parts are exactly in
    [l, 2l] (l = 1), K l = 2; on the points ``lo`` or, with ``hi``, on cells."""
    lo = np.array(lo)
    return corner.Graph(0.0, lengths, 2.0, 1.0, lo, lo if hi is None else np.array(hi), 0.0, (math.inf, math.inf))


def test_graph_thresholds_are_closed():
    """Every threshold of Graph holds with equality (tolerance 0, l = 1): parts of exactly l and 2l are steps; cross
    pairs exactly l apart are far enough, for points and for cells; a short side (3) ends only at a position that is
    its far end whole, and no cell starting there goes on; a long side (20, K l = 2) stops at a point exactly at K l
    and may step to one exactly at K l + 2l."""
    points = _graph([0.0, 1.0, 3.0], (3.0, 3.0))
    assert points.next[0].tolist() == [[False, True, False], [False, False, True], [False, False, False]]
    assert _graph([0.0, 1.0, 2.0], (3.0, 3.0)).cross[0][1, 2]
    assert _graph([0.0, 1.0, 2.0], (3.0, 3.0), hi=[0.0, 1.0, 2.0]).cross[0][1, 2]
    cells = _graph([0.0, 1.5, 3.0, 3.0], (3.0, 3.0), hi=[0.0, 2.0, 3.5, 3.0])
    assert cells.ends[0].tolist() == [False, False, False, True]
    assert cells.next[0][1].tolist() == [False, False, False, True]  # not to the cell from 3 to 3.5
    long_ = _graph([0.0, 1.0, 2.0, 3.0, 4.0], (20.0, 20.0))
    assert long_.stops[0].tolist() == [False, False, True, True, True]
    assert long_.next[0][2, 4]


def test_no_node_past_the_horizon_where_the_quotient_rounds_up():
    """At l = 1.2187810373376886 and a step of l / 32 the side 5.674949205103612 is an ulp short of 149 steps, and
    its quotient by the step rounds up to 149: the multiple past the side's end is not a node, the end itself is."""
    l = 1.2187810373376886
    step, length = l / 32.0, 5.674949205103612
    assert math.floor(length / step) * step > length
    nodes = corner.nodes((length, 2.0), 3.0 * l, l, step, (None, None))
    assert nodes.max() == length


@pytest.mark.parametrize("first, placed", [(1.9604759331026373, True), (1.96047593041909, False)])
def test_the_search_accepts_a_cross_pair_within_rel_tol_over_4(first, placed):
    """A 30-degree corner whose arriving side (1.5 l) is a single part and whose leaving side is kept at ``first`` and
    ``first + 1.5``: the arriving side's end is (1 - 2.25e-10) l from the first point at 1.9604759331026373, accepted
    by the search's tolerance REL_TOL / 4 (but not REL_TOL / 5); (1 - 2e-9) l at 1.96047593041909, refused (it would be
    within 4 REL_TOL), on every grid."""
    theta, kept = math.radians(30.0), np.array([first, first + 1.5])
    squared = 1.5**2 + first**2 - 2.0 * math.cos(theta) * 1.5 * first
    assert (squared >= (1.0 - REL_TOL / 4.0) ** 2) == placed and squared >= (1.0 - 4.0 * REL_TOL) ** 2
    assert squared < (1.0 - REL_TOL / 5.0) ** 2
    found = corner.place_corner(theta, (first + 1.5, 1.5), 1.0, (kept, None))
    assert (found is not None) == placed
    if placed:
        assert [points.tolist() for points in found] == [kept.tolist(), [1.5]]


@pytest.mark.parametrize(
    "first, second, arriving",
    [
        (1.1263, 2.3221, [61 / 32, 3.3]),  # the window holds a node of the grid of l / 32, none of l / 16
        (1.1207, 2.3181, None),  # the window holds a node of l / 128 only, past CORNER_REFINEMENTS
    ],
)
def test_a_kept_side_is_searched_on_each_finer_grid(first, second, arriving, monkeypatch):
    """A 25-degree corner whose leaving side is kept at ``first``, ``second`` and ``second + 1.5`` and whose arriving
    side is 3.3 l: its first point must lie at least l beyond ``first`` and l before ``second`` (on the other side),
    a window 0.012 l wide around 61/32 (0.004 l around 243/128) that no multiple of l/16 from either end reaches.  The
    search tries the grids of l/16, l/32 and l/64 in turn, and takes the first placement found; with one more
    refinement the second corner is placed at 243/128."""
    theta, kept = math.radians(25.0), np.array([first, second, second + 1.5])
    found = corner.place_corner(theta, (second + 1.5, 3.3), 1.0, (kept, None))
    assert (found if found is None else found[1].tolist()) == arriving
    monkeypatch.setattr(corner, "CORNER_REFINEMENTS", 3)
    assert corner.place_corner(theta, (second + 1.5, 3.3), 1.0, (kept, None))[1].tolist() == (
        arriving or [243 / 128, 3.3]
    )
