"""Where the Step 2 points of each side of a ring lie (Sections 2 and 3), as fractions of the side.

The paper splits each edge into equal parts (:func:`split_counts`).  Next to a
corner sharper than :data:`SHARP_CORNER` equal parts would put points of the
two sides closer than l, so the points there are staggered (:func:`stagger`);
sides too short for their staggered points, and sharp corners still closer
than l, are placed by searches on a grid of positions
(:mod:`~equimesh.planar.boundary.corner` for one corner,
:mod:`~equimesh.planar.boundary.chain` for a run of them).  Every part is in
[l, 2l] whatever the search finds (docs/proofs.md, "Sharp corners").
"""

import math

import numpy as np

from ...tolerance import REL_TOL, at_least
from . import chain as _chain
from . import corner as _corner

#: Corners of P with an inner angle below this many degrees get staggered
#: Step 2 points (:func:`stagger`).  At 60 degrees or more, points at distances
#: ``s, t >= l`` from the corner on its two sides are at least ``min(s, t) >= l``
#: apart (law of cosines), so equal parts need nothing more
#: (docs/proofs.md, "Sharp corners").
SHARP_CORNER = 60.0


def stagger(angle, l, reach):
    """The staggered Step 2 points next to a corner of inner angle ``angle`` (degrees), up to ``reach`` from it.

    Returns ``(leaving, arriving)``: distances from the corner of the points
    on the side leaving it (counter-clockwise) and on the side arriving at it.
    For a corner of at least :data:`SHARP_CORNER` degrees both are empty.
    Otherwise the points ``k l`` for ``k = 1 .. K``, ``K = ceil(1 / sin angle)``,
    alternate between the sides (:func:`_multiples`): along each side the
    parts are ``2l`` (``l`` for the first leaving part), and two points of
    different sides are at least ``l`` apart at any angle because their
    distances from the corner differ by at least ``l``; past ``K l`` the sides
    themselves are ``l`` apart (docs/proofs.md, "Sharp corners").
    """
    return _multiples(angle, l, min(stagger_count(angle), math.floor(reach / l) + 1))


def _multiples(angle, l, count):
    """The points ``k l``, ``k = 1 .. count``, of a sharp corner: odd ``k`` leaving, even ``k`` arriving.

    Where ``2 k l sin(angle / 2) > l`` the two points at ``k l`` on both sides
    are ``l`` apart already, so ``k l`` is placed on both (parts of ``l``: a
    ``2l`` part there would leave its midpoint ``l`` from every point, and
    the insertion a sliver against it).
    """
    k = np.arange(1, count + 1)
    both = 2.0 * k * math.sin(math.radians(angle) / 2.0) >= 1.0 + REL_TOL
    return k[(k % 2 == 1) | both] * l, k[(k % 2 == 0) | both] * l


def stagger_count(angle):
    """``K = ceil(1 / sin angle)`` staggered points for a corner sharper than :data:`SHARP_CORNER`, else 0."""
    if not angle < SHARP_CORNER * (1.0 - REL_TOL):
        return 0
    return math.ceil((1.0 - REL_TOL) / math.sin(math.radians(angle)))


def stagger_reach(angle, l):
    """How far from a corner of ``angle`` degrees :func:`stagger` places points: ``K l`` (0 if not sharp)."""
    return stagger_count(angle) * l


def side_positions(lengths, angles, l, spacing=2.0):
    """Step 2 on a closed ring of sides: where each side's points lie, staggered next to sharp corners.

    Side ``i`` runs from corner ``i`` (inner angle ``angles[i]`` degrees) to
    corner ``i + 1`` and is ``lengths[i]`` long.  Returns one
    ``(numerators, denominator)`` pair per side: its points lie at the
    fractions ``numerators / denominator`` of the side, the first (0) being
    corner ``i``.  Shared by the polygon's Step 2 and the surface outline.

    * Next to a corner sharper than :data:`SHARP_CORNER` the points of
      :func:`stagger` are placed; between the last staggered point from each
      end, the middle of length ``M`` is split into ``k`` equal parts by
      :func:`split_counts` (``l <= M / k <= 2l``).  A side at least
      ``stagger_reach`` of both its corners plus ``l`` long keeps them all.
    * A side with no staggered point is split into equal parts exactly as the
      paper's Step 2 (numerators ``0 .. k - 1``, denominator ``k``), bit for
      bit.
    * Sides too short for all their staggered points are placed by
      :func:`_separate_short_sides`; then each sharp corner still closer
      than ``l`` (also one whose sides fit their staggers but end, shorter
      than the proven length, near a staggered point of the other side) is
      decided by :func:`place_corners_on_a_grid`.  Every part is in
      ``[l, 2l]`` in every case (docs/proofs.md, "Sharp corners").
    """
    lengths = np.asarray(lengths, dtype=float)
    n = len(lengths)
    reach = [max(lengths[i - 1], lengths[i]) for i in range(n)]
    corners = [stagger(a, l, r) for a, r in zip(angles, reach)]
    sides, short = [], []
    for i, length in enumerate(lengths):
        start, end = _chains(corners, i, length)
        if (len(start) or len(end)) and not at_least(length - start.max(initial=0.0) - end.max(initial=0.0), l):
            short.append(i)
        sides.append(place(length, start, end, l, spacing))
    if short:
        _separate_short_sides(sides, short, corners, lengths, angles, l, spacing)
    if short or not all(at_least(corner_gap(sides, lengths, angles, l, c), l) for c in range(n)):
        place_corners_on_a_grid(sides, lengths, angles, l, spacing)
    return sides


def _chains(corners, i, length):
    """The staggered points of side ``i`` below ``length``: from its first corner, and from its last (distances from
    it)."""
    start, end = corners[i][0], corners[(i + 1) % len(corners)][1]
    return start[start < length], end[end < length]


def place(length, start, end, l, spacing):
    """A side of ``length`` with the staggered points ``start`` (from its first corner) and ``end`` (from its last).

    Staggered points that leave a middle shorter than ``l`` are dropped, the
    farthest from its corner first; the middle is split by
    :func:`split_counts`.
    """
    while (len(start) or len(end)) and not at_least(length - start.max(initial=0.0) - end.max(initial=0.0), l):
        if start.max(initial=0.0) >= end.max(initial=0.0):
            start = start[:-1]
        else:
            end = end[:-1]
    if not len(start) and not len(end):
        k = int(split_counts([length], l, spacing)[0])
        return np.arange(k, dtype=float), float(k)
    first, last = start.max(initial=0.0), length - end.max(initial=0.0)
    k = int(split_counts([last - first], l, spacing)[0])
    middle = first + (last - first) * np.arange(1, k) / k
    return np.concatenate([[0.0], start, middle, length - end[::-1]]), length


#: Rounds in which :func:`_separate_short_sides` lets each short side take its
#: best candidate given its neighbours: a bound on the work, not a tolerance.
#: One round settles a side whose neighbours are fixed; the extra rounds let
#: two short sides of one sharp corner (thin triangles) adapt to each other.
SETTLE_PASSES = 4


def _separate_short_sides(sides, short, corners, lengths, angles, l, spacing):
    """Place the ``short`` sides (in place) so that the two sides of every sharp corner are ``l`` apart.

    First each short side takes the best of its candidates
    (:func:`_short_side`), again when a neighbour changed, for at most
    :data:`SETTLE_PASSES` rounds.  Then each sharp corner still below ``l``
    (:func:`corner_gap`), in order, is tried with its stagger mirrored (odd
    ``k`` on the arriving side): its two sides are placed again (and the
    sides next to them) and the trial is kept if it raises the smallest gap
    at their corners.  Both rounds run first with the staggers alone, then,
    if a corner is still below ``l``, with multiples of ``l`` from the other
    corners too.  Deterministic; the sides keep parts in ``[l, 2l]``.
    """
    n = len(lengths)
    flipped, free = [False] * n, list(short)

    def settle(sides, free, flipped, multiples):
        dirty = set(free)
        for _ in range(SETTLE_PASSES):
            for i in [i for i in free if i in dirty]:
                dirty.discard(i)
                best = _short_side(i, sides, lengths, angles, l, spacing, flipped, multiples)
                if best is not sides[i]:
                    sides[i] = best
                    dirty |= {(i - 1) % n, (i + 1) % n}
            if not dirty & set(free):
                return

    def lowest(sides, changed):
        return min(corner_gap(sides, lengths, angles, l, c % n) for i in changed for c in (i, i + 1))

    for multiples in (False, True):
        settle(sides, free, flipped, multiples)
        for c in sorted({j % n for i in short for j in (i, i + 1)}):
            if at_least(corner_gap(sides, lengths, angles, l, c), l):
                continue
            trial, mirrored = list(sides), list(corners)
            mirrored[c] = corners[c][::-1]
            for i in ((c - 1) % n, c):
                trial[i] = place(lengths[i], *_chains(mirrored, i, lengths[i]), l, spacing)
            trial_flipped = flipped[:c] + [not flipped[c]] + flipped[c + 1 :]
            trial_free = sorted(set(free) | {(c - 1) % n, c})
            near = sorted({i % n for i in range(c - 2, c + 2)} & set(trial_free))
            settle(trial, near, trial_flipped, multiples)
            if lowest(trial, near) > lowest(sides, near):
                sides[:], corners[:], flipped[:], free = trial, mirrored, trial_flipped, trial_free
        if at_least(lowest(sides, range(n)), l):
            return


def _short_side(i, sides, lengths, angles, l, spacing, flipped, multiples):
    """The placement of side ``i``: its current one if its sharp corners are separated, else the best candidate.

    Candidates keep a prefix of a chain from each end and a middle of ``l``
    to ``3l``: at a sharp corner its stagger continued along the side
    (:func:`_multiples` up to the side's length, mirrored where
    ``flipped``), at another corner nothing or, with ``multiples``, the
    multiples of ``l``, so that the last part before it can be ``l``.  They
    are tried in order (by start, then by end; the longest stagger first,
    the fewest multiples first) and the first whose :func:`corner_gap` at
    both ends is at least ``l`` (up to REL_TOL) is taken, else the one with
    the largest gap.
    """
    n = len(lengths)
    length = lengths[i]

    def gap(side):
        trial = {(i - 1) % n: sides[(i - 1) % n], (i + 1) % n: sides[(i + 1) % n], i: side}
        return min(corner_gap(trial, lengths, angles, l, c % n) for c in (i, i + 1))

    best, best_gap = sides[i], gap(sides[i])
    if at_least(best_gap, l):
        return best
    count = math.floor(length / l * (1.0 + REL_TOL))

    def chain(c, arriving):
        if not stagger_count(angles[c]):
            return np.arange(1, count * multiples + 1) * l
        return _multiples(angles[c], l, count)[int(arriving) ^ int(flipped[c])]

    def prefixes(c, points):
        sizes = range(len(points) + 1)
        return sizes[::-1] if stagger_count(angles[c]) else sizes

    start, end = chain(i, False), chain((i + 1) % n, True)
    start, end = start[start < length], end[end < length]
    reach_start, reach_end = np.append(0.0, start), np.append(0.0, end)
    for a in prefixes(i, start):
        for b in prefixes((i + 1) % n, end):
            middle = length - reach_start[a] - reach_end[b]
            if not at_least(middle, l) or at_least(middle, 3.0 * l):
                continue
            side = place(length, start[:a], end[:b], l, spacing)
            g = gap(side)
            if at_least(g, l):
                return side
            if g > best_gap:
                best, best_gap = side, g
    return best


#: The trials of :func:`place_corners_on_a_grid` placing a corner and the next one jointly, and its whole run.
PAIR, CHAIN = "pair", "chain"


def place_corners_on_a_grid(sides, lengths, angles, l, spacing):
    """Each sharp corner still closer than ``l`` after :func:`_separate_short_sides`, placed by
    :func:`.corner.place_corner`.

    The two sides of the corner are placed again (:func:`grid_sides`):
    both free; the leaving side kept; the arriving one kept; or, for a side
    shared with the next (previous) sharp corner, that corner placed first
    with both its sides free and this one then with the shared side kept,
    or the other way round; then with each neighbouring sharp corner
    jointly; last, with the whole run of three or more sharp corners it
    belongs to (:func:`sharp_run`), jointly (:func:`grid_chain`).  The first
    trial after which every corner it touched, and their neighbours, have a
    :func:`corner_gap` of at least ``l`` is taken, in place.  A corner that
    :func:`.corner.corner_unplaceable` proves impossible even with every
    pair checked ends the search: the ring cannot be separated, and
    :func:`check_boundary_separation` refuses it, naming the first such
    corner.  Every part stays in ``[l, 2l]``.  Deterministic.
    """
    n = len(lengths)
    free, leaving, arriving = (False, False), (True, False), (False, True)
    for c in range(n):
        if at_least(corner_gap(sides, lengths, angles, l, c), l):
            continue
        if _corner.corner_unplaceable(math.radians(angles[c]), (lengths[c], lengths[c - 1]), l, (math.inf, math.inf)):
            return
        after, before = (c + 1) % n, (c - 1) % n
        trials = (
            [(c, free)],
            [(c, leaving)],
            [(c, arriving)],
            [(after, free), (c, leaving)],
            [(before, free), (c, arriving)],
            [(c, free), (after, arriving)],
            [(c, free), (before, leaving)],
            [(c, PAIR)],
            [(before, PAIR)],
            [(c, CHAIN)],
        )
        for steps in trials:
            if not all(stagger_count(angles[corner]) for corner, _ in steps):
                continue
            trial, touched = list(sides), set()
            for corner, keep in steps:
                if keep in (PAIR, CHAIN):
                    run = [corner, (corner + 1) % n] if keep is PAIR else sharp_run(lengths, angles, l, corner)
                    # a run of two is the pair's trial
                    trial = (
                        trial and (keep is PAIR or len(run) > 2) and grid_chain(trial, lengths, angles, l, spacing, run)
                    )
                else:
                    run = [corner]
                    trial = trial and grid_sides(trial, lengths, angles, l, spacing, corner, keep)
                touched |= {(k + d) % n for k in run for d in (-1, 0, 1)}
            if trial and all(at_least(corner_gap(trial, lengths, angles, l, k), l) for k in touched):
                sides[:] = trial
                break


def sharp_run(lengths, angles, l, c):
    """The run of sharp corners through the sharp corner ``c``: consecutive, each two sharing a side that couples them.

    Coupled as :func:`.chain.shared` says (no longer than ``K_1 l +
    K_2 l + 4l``); in ring order, at most all corners but one.
    """
    n = len(lengths)

    def joined(k):  # corners k and k + 1 (sharp), sharing side k
        return _chain.shared((math.radians(angles[k]), math.radians(angles[(k + 1) % n])), lengths[k], l)

    run = [c]
    while len(run) < n - 1 and stagger_count(angles[(run[-1] + 1) % n]) and joined(run[-1]):
        run.append((run[-1] + 1) % n)
    while len(run) < n - 1 and stagger_count(angles[run[0] - 1]) and joined((run[0] - 1) % n):
        run.insert(0, (run[0] - 1) % n)
    return run


def grid_chain(sides, lengths, angles, l, spacing, run):
    """``sides`` with the sides of the corners ``run`` (consecutive) placed by :func:`.chain.place_chain`, or None.

    None too when a corner is not sharp.  The shared sides take the points
    found; the first and last side are completed by :func:`grid_side`.
    """
    if not all(stagger_count(angles[c]) for c in run):
        return None
    n, m = len(lengths), len(run)
    edges = [(run[0] - 1 + k) % n for k in range(m + 1)]  # T_0 .. T_m
    found = _chain.place_chain(tuple(math.radians(angles[c]) for c in run), tuple(lengths[i] for i in edges), l)
    if found is None:
        return None
    trial = list(sides)
    for i, points in zip(edges[1:-1], found[1:-1]):
        trial[i] = np.concatenate([[0.0], points[:-1]]), lengths[i]
    for i, points, c, leaving in ((edges[0], found[0], run[0], False), (edges[-1], found[-1], run[-1], True)):
        trial[i] = grid_side(lengths[i], points, from_corner(sides, lengths, c, i), leaving, l, spacing)
    return trial


def grid_sides(sides, lengths, angles, l, spacing, c, keep):
    """``sides`` with the two sides of corner ``c`` (leaving, arriving) placed by :func:`.corner.place_corner`, or None.

    The sides flagged in ``keep`` are passed as they are (:func:`from_corner`).
    """
    n = len(lengths)
    theta = math.radians(angles[c])
    reach = _corner.corner_reach(theta, l)
    ends = (c, (c - 1) % n)
    near = [from_corner(sides, lengths, c, i) for i in ends]
    fixed = [_corner.cut(points, lengths[i], reach, l) if kept else None for i, points, kept in zip(ends, near, keep)]
    found = _corner.place_corner(theta, tuple(lengths[i] for i in ends), l, fixed)
    if found is None:
        return None
    trial = list(sides)
    for i, points, now in zip(ends, found, near):
        trial[i] = grid_side(lengths[i], points, now, i == c, l, spacing)
    return trial


def from_corner(sides, lengths, c, i):
    """The points of side ``i`` (``c`` leaving corner ``c``, ``c - 1`` arriving) by distance from corner ``c``, far end
    included."""
    num, den = sides[i]
    positions = num[1:] / den * lengths[i]
    return np.append(positions if i == c else (lengths[i] - positions)[::-1], lengths[i])


def grid_side(length, points, now, leaving, l, spacing):
    """A side from :func:`.corner.place_corner`'s ``points`` (by distance from the corner), as ``(positions, length)``.

    Where the grid cut the side short (past ``K l``), its points ``now`` at
    least ``l`` beyond the cut are kept and :func:`place` splits the middle
    between, at least ``l`` long, into parts of ``[l, 2l]``; the kept points
    are consecutive points of a side, so their parts are in ``[l, 2l]`` too.
    """
    if points[-1] == length:
        inner = points[:-1]
        return np.concatenate([[0.0], inner if leaving else (length - inner)[::-1]]), length
    kept = now[(now >= points[-1] + l) & (now < length)]
    far = (length - kept)[::-1]
    return place(length, points, far, l, spacing) if leaving else place(length, far, points, l, spacing)


def corner_gap(sides, lengths, angles, l, c):
    """The smallest distance between Step 2 points of the two sides of corner ``c`` (``inf`` if it is not sharp).

    Far corners count, the corner itself not.  Points farther than ``K l >= l
    / sin theta`` from the corner are at least ``l`` from the whole other side
    and are left out, so a gap of at least ``l`` is reported as such but not
    always exactly.  At a corner of at least :data:`SHARP_CORNER` degrees
    every two such points are ``l`` apart (docs/proofs.md, "Sharp corners").
    """
    reach = stagger_count(angles[c]) * l
    if not reach:
        return math.inf
    (num_a, den_a), (num_b, den_b) = sides[c], sides[(c - 1) % len(lengths)]
    a = np.append(num_a[1:] / den_a * lengths[c], lengths[c])
    b = lengths[c - 1] * (1.0 - num_b / den_b)
    a, b = a[a < reach], b[b < reach]
    if not len(a) or not len(b):
        return math.inf
    squared = a[:, None] ** 2 + b[None, :] ** 2 - 2.0 * math.cos(math.radians(angles[c])) * a[:, None] * b[None, :]
    return math.sqrt(max(float(squared.min()), 0.0))


def split_counts(lengths, l, spacing=2.0):
    """Number of equal parts for each length: ``ceil(L / (spacing l))`` kept in ``[ceil(L / 2l), floor(L / l)]``.

    A part has length ``L / k``: at most ``2l`` as ``k >= L / 2l``, at least
    ``l`` as ``k <= L / l`` (bounds taken up to REL_TOL); the range is never
    empty for ``L >= l`` (for ``L <= 2l`` it contains 1, for ``L > 2l`` it has
    length ``L / 2l > 1``).
    """
    lengths = np.asarray(lengths, dtype=float)
    fewest = np.maximum(1, np.ceil(lengths / (2.0 * l) * (1.0 - REL_TOL)))
    most = np.floor(lengths / l * (1.0 + REL_TOL))
    return np.clip(np.ceil(lengths / (spacing * l) * (1.0 - REL_TOL)), fewest, most).astype(int)
