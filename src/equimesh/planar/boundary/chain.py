"""Step 2 at sharp corners in a row, decided jointly on a grid: a search and a proof.

Corners ``0 .. m - 1`` (angles ``theta_j``) follow each other along a ring:
corner ``j`` joins side ``T_j`` (arriving at it) and side ``T_(j+1)`` (leaving
it), so ``T_1 .. T_(m-1)`` are shared by two corners each, ``T_0`` and
``T_m`` by one (``m = 2``: two corners sharing one side, ``T_0, T_1, T_2``
being ``A``, ``S``, ``B``).  Any Step 2 splits every side into parts of
``[l, 2l]``; Lemma 3 (1) wants, at every corner, every two points of its two
sides (the corner excluded) at least ``l`` apart where they see each other.
Consecutive corners are coupled through the points of the side they share
only.

Both readings enumerate the points of the shared sides ``T_1``, then
``T_2``, ..., depth first on a grid of positions (nodes for the search, cells
for the proof).  A point of ``T_k`` removes the positions of ``T_(k+1)``
closer than ``l`` to it at corner ``k`` (and, for ``T_1``, those of ``T_0`` at
corner 0: :func:`far_apart`); the points of ``T_(k+1)`` are then enumerated
through the positions left.  A prefix is dropped as soon as a side still to
come has no split left (:func:`useful`: a path of parts in ``[l, 2l]``
through the positions left, from its corner to its far end, or past ``K l``
for a long side, where every point is ``l`` from the whole other side).
What a prefix leaves to its continuations depends only on the side being
enumerated, its last point and the positions left on the sides still to come,
and those only through the positions on some split (the *useful* ones): a
failed state is not tried again, and prefixes that remove only positions no
split uses lead to the same state.  The work is bounded by
:data:`PAIR_STEPS`.

* :func:`place_chain` (a search) puts the points on grid nodes (multiples of
  the step from each end of each side) and checks every pair exactly: what
  it returns is a placement, checked pair by pair.
* :func:`chain_unplaceable` (a proof) lets positions be the grid *cells* and
  each far end; a part or a distance is allowed when *some* points of the
  two cells allow it, with the tolerances of the checks widened (parts from
  ``(1 - 2 REL_TOL) l`` to ``2 (1 + 2 REL_TOL) l``, distances from
  ``(1 - 2 REL_TOL) l``; ``d^2`` is convex, so its largest value over two
  cells is at their corners), and distances are checked only within the
  radii where the sides see each other.  Cells next to an exact end are
  clipped to the range a first or last point can have (:func:`side`).
  Every placement the checks accept maps each point to a position holding
  it and is then an enumerated prefix that is never dropped; when every
  prefix is dropped, no Step 2 meets Lemma 3 (1) at the corners together
  (docs/proofs.md, "Sharp corners").  With no second corner (``theta_1``
  None) the same proof decides one corner on finer cells than
  :func:`.corner.corner_unplaceable`.
"""

import math

import numpy as np

from ...tolerance import REL_TOL
from .corner import CORNER_GRID, CORNER_REFINEMENTS, corner_reach

#: Distinct sets of positions left that one decision may reduce to their useful
#: part (:func:`useful`, per grid): a bound on the work, not a tolerance; past
#: it the corners are left undecided.
PAIR_STEPS = 20000
#: Halvings of the grid step the proof tries (:func:`chain_unplaceable`, down to
#: ``l / (CORNER_GRID 2^PAIR_REFINEMENTS)`` = l/256): a bound on the work.  Finer
#: than the search's (:data:`.corner.CORNER_REFINEMENTS`): where the last
#: placements vanish at a part of exactly ``2l``, cells of l/64 still hold a path.
PAIR_REFINEMENTS = 4


class Undecided(Exception):
    """The enumeration ran out of :data:`PAIR_STEPS`, or of the :class:`Work` it shares."""


class Work:
    """The positions that the decisions sharing it may reduce together (:func:`useful`): a bound on their work.

    Each reduction of a side's positions spends their number: its cost grows
    with them, and a finer grid has more positions per side, so the bound
    follows the time where a count of reductions (:data:`PAIR_STEPS`) does
    not.  Past ``limit``, each decision charged to it is :class:`Undecided`.
    """

    def __init__(self, limit):
        self.limit, self.spent = limit, 0

    def spend(self, positions):
        """Charge ``positions``; :class:`Undecided` once the total passes the limit."""
        self.spent += positions
        if self.spent > self.limit:
            raise Undecided


def place_chain(thetas, lengths, l):
    """Points of ``T_0 .. T_m`` keeping every corner's two sides ``l`` apart, or None if none is found.

    ``thetas`` are the ``m >= 2`` corners' angles in radians, ``lengths`` the
    ``m + 1`` sides' (``theta_1`` None: corner 0 alone, ``T_2`` ignored).
    Returns one array per side: ``T_0``'s points by distance from corner 0,
    each shared side's by distance from its first corner, ``T_m``'s by
    distance from corner ``m - 1``, each up to its far end, a long ``T_0`` or
    ``T_m`` stopping at a point past ``K l`` at least ``l`` before it.  On
    each grid (``l / CORNER_GRID``, then halved up to
    :data:`.corner.CORNER_REFINEMENTS` times) the search runs, then, if it
    found nothing, the proof with every pair checked: None once it refutes.
    """
    if not coupled(thetas, lengths, l):
        return None
    inf = (math.inf,) * (2 * len(thetas))
    for level in range(CORNER_REFINEMENTS + 1):
        try:
            found = Chain(thetas, lengths, l, level, cells=False, radii=inf).search()
            if found is not None or Chain(thetas, lengths, l, level, cells=True, radii=inf).search() is None:
                return found
        except Undecided:
            return None
    return None


def chain_unplaceable(thetas, lengths, l, radii, work=None):
    """True when no Step 2 keeps every corner's two sides ``l`` apart (Lemma 3 (1)): proven on a grid of cells.

    ``thetas`` and ``lengths`` as for :func:`place_chain`.  ``radii`` are two
    per corner, ``(T_j, T_(j+1))`` for corner ``j``: the distances from it
    within which the points of its two sides see each other (the caller
    proves it); pairs beyond are not checked.  Cells of ``l / CORNER_GRID``
    down to ``l / (CORNER_GRID 2^PAIR_REFINEMENTS)``; after each grid of cells
    that refuted nothing, the search on its nodes (the finest of the
    search's), and False when it finds a placement (then no proof exists).
    False means only that no grid refuted every prefix within
    :data:`PAIR_STEPS`, or within ``work`` (a :class:`Work` the caller shares
    among several decisions; None: no bound but the steps).
    """
    if not coupled(thetas, lengths, l):
        return False
    inf = (math.inf,) * (2 * len(thetas))
    for level in range(PAIR_REFINEMENTS + 1):
        try:
            if Chain(thetas, lengths, l, level, cells=True, radii=radii, work=work).search() is None:
                return True
            if (
                level <= CORNER_REFINEMENTS
                and Chain(thetas, lengths, l, level, cells=False, radii=inf, work=work).search()
            ):
                return False
        except Undecided:
            return False
    return False


def coupled(thetas, lengths, l):
    """Whether every shared side is short enough for its two corners to read the same points of it.

    Each corner's placement reads a side only up to its first point past
    ``K l`` (at most ``K l + 2l``; past ``K l`` a point is ``l`` from the
    whole other side), so with ``T_k`` longer than ``K_(k-1) l + K_k l + 4l``
    no point of it matters to both: not this module's case (and its grid
    would grow with it).  One corner alone is always decided here (``T_1``
    cut like ``T_0``).
    """
    return thetas[1] is None or all(shared(thetas[k - 1 : k + 1], lengths[k], l) for k in range(1, len(thetas)))


def shared(thetas, length, l):
    """Whether a side of ``length`` between corners of ``thetas`` couples them: at most ``K_1 l + K_2 l + 4l`` long
    (:func:`coupled`)."""
    return length <= corner_reach(thetas[0], l) + corner_reach(thetas[1], l) + 4.0 * l


def side(length, reach, l, step, cells, tol):
    """``(lo, hi, ends, parts)`` of one side: its positions, where a split may stop, and the parts allowed between them.

    Positions: the corner (0), grid nodes or cells, and the far end (last).
    A side longer than ``K l + 3l`` has no far end: it may stop at any
    position past ``K l`` (at most ``length - l`` before it: the rest is
    split into parts of ``[l, 2l]``; for cells, any reaching past ``K l``);
    positions go to ``K l + 2l`` and a cell more.  ``parts[i, j]``: a part
    from a point of ``i`` to one of ``j`` can be in ``[(1 - tol) l, 2 (1 + tol) l]``.

    Cells next to an exact end are clipped (:func:`clipped`): the first
    point lies within ``[(1 - tol) l, 2 (1 + tol) l]`` of the corner and the
    last before the far end as near it, so the cells holding them are cut
    to those ranges, as copies that only the corner leads to (only lead to
    the far end, or both).  Every split is still a path, with each point in
    a position holding it.
    """
    long_ = length > reach + 3.0 * l
    top = reach + 2.0 * l if long_ else length
    count = math.ceil(top / step) + 1
    if not cells:
        nodes = np.arange(1, count) * step
        if not long_:
            nodes = np.concatenate([nodes, length - np.arange(0, count) * step])
        lo = hi = np.unique(np.concatenate([[0.0], nodes[(nodes > 0.0) & (nodes <= top)]]))
        ends = (lo >= reach) & (lo <= length - l) if long_ else lo == length
        return lo, hi, ends, parts(lo, hi, l, tol)
    edges = np.arange(0, count + 1) * step
    keep = edges[:-1] < min(top, length)
    grid = edges[:-1][keep], np.minimum(edges[1:][keep], length)
    near, far = ((1.0 - tol) * l, 2.0 * (1.0 + tol) * l), (length - 2.0 * (1.0 + tol) * l, length - (1.0 - tol) * l)
    groups = [(np.zeros(1), np.zeros(1)), grid, clipped(grid, *near)]  # kinds 0 corner, 1 inner, 2 first
    if not long_:
        groups += [
            clipped(grid, *far),
            clipped(clipped(grid, *near), *far),
            (np.full(1, length), np.full(1, length)),
        ]
    kind = np.concatenate([np.full(len(group[0]), k) for k, group in enumerate(groups)])
    lo, hi = (np.concatenate([group[i] for group in groups]) for i in (0, 1))
    # corner -> first or both (or the far end); first or inner -> inner or last; last or both (or corner) -> far end
    follows = {0: (2, 4, 5), 1: (1, 3), 2: (1, 3), 3: (5,), 4: (5,), 5: ()}
    allowed = np.array([[j in follows[i] for j in range(6)] for i in range(6)])
    ends = hi >= reach if long_ else kind == 5
    return lo, hi, ends, parts(lo, hi, l, tol) & allowed[kind[:, None], kind[None, :]]


def clipped(cells, low, high):
    """The cells ``(lo, hi)`` cut to ``[low, high]``, those left."""
    lo, hi = np.maximum(cells[0], low), np.minimum(cells[1], high)
    return lo[lo <= hi], hi[lo <= hi]


def parts(lo, hi, l, tol):
    """``[i, j]``: a part from a point of position ``i`` to one of ``j`` can be in ``[(1 - tol) l, 2 (1 + tol) l]``."""
    return (hi[None, :] - lo[:, None] >= (1.0 - tol) * l) & (lo[None, :] - hi[:, None] <= 2.0 * (1.0 + tol) * l)


def far_apart(theta, mine, theirs, l, tol, radii):
    """``[i, j]``: a point of position ``i`` of one side can be ``(1 - tol) l`` or more from one of ``j`` of the other.

    ``mine`` and ``theirs`` are ``(lo, hi)`` by distance from the corner;
    ``d^2`` is convex, so its largest value over two cells is at one of
    their four corners.  A pair beyond the ``radii`` is not checked.
    """
    c, best = math.cos(theta), 0.0
    for u in (mine[0][:, None], mine[1][:, None]):
        for v in (theirs[0][None, :], theirs[1][None, :]):
            best = np.maximum(best, u * u + v * v - 2.0 * c * u * v)
    return (best >= ((1.0 - tol) * l) ** 2) | (mine[1][:, None] > radii[0]) | (theirs[1][None, :] > radii[1])


def reaches(parts, left, ends):
    """The positions of a path of ``parts`` through ``left`` from position 0 to one of ``ends``, or None.

    Breadth first: each position after one reached a round earlier.
    """
    when = np.full(len(left), -1)
    when[0] = rounds = 0
    fresh = when == 0
    while fresh.any():
        rounds += 1
        fresh = parts[fresh].any(axis=0) & left & (when < 0)
        when[fresh] = rounds
    done = np.flatnonzero(ends & (when >= 0))
    if not len(done):
        return None
    found = [int(done[0])]
    while found[-1]:
        found.append(int(np.flatnonzero((when == when[found[-1]] - 1) & parts[:, found[-1]])[0]))
    return found[::-1]


def useful(parts, left, ends):
    """The positions of ``left`` on some path of ``parts`` from position 0 to one of ``ends``, or None if there is none.

    Every split through ``left`` runs through these only, so they stand for
    ``left`` in every later test: a canonical form of the positions left.
    """
    start = np.zeros(len(left), dtype=bool)
    start[0] = True
    ahead = _spread(parts, left, start)
    if not (ahead & ends).any():
        return None
    return ahead & _spread(parts.T, ahead, ends & ahead)


def _spread(parts, left, seen):
    """``seen`` and every position of ``left`` reached from it along ``parts``."""
    fresh = seen
    while fresh.any():
        fresh = parts[fresh].any(axis=0) & left & ~seen
        seen = seen | fresh
    return seen


class Chain:
    """The enumeration of the module docstring on one grid (``l / (CORNER_GRID 2^level)``), nodes or cells."""

    def __init__(self, thetas, lengths, l, level, cells, radii, work=None):
        step = l / (CORNER_GRID * 2**level)
        tol = 2.0 * REL_TOL if cells else REL_TOL / 4.0
        m, alone = len(thetas), thetas[1] is None
        self.m = m
        # sides: (lo, hi, ends, parts); T_0 and T_m by distance from their sharp corner, the others from their first
        sides = [side(lengths[0], corner_reach(thetas[0], l), l, step, cells, tol)]
        for k in range(1, m):  # alone, T_1 is cut past K l like T_0; shared sides are read whole (coupled)
            sides.append(side(lengths[k], corner_reach(thetas[0], l) if alone else math.inf, l, step, cells, tol))
        dummy = (np.zeros(1), np.zeros(1), np.ones(1, dtype=bool), np.zeros((1, 1), dtype=bool))
        sides.append(dummy if alone else side(lengths[m], corner_reach(thetas[m - 1], l), l, step, cells, tol))
        self.sides = sides
        # back: T_1's points against T_0's at corner 0; ahead[k]: T_k's against T_(k+1)'s at corner k
        self.back = far_apart(thetas[0], sides[1][:2], sides[0][:2], l, tol, (radii[1], radii[0]))
        self.ahead = [None]
        for k in range(1, m):
            lo, hi = sides[k][:2]
            if alone:
                cross = np.ones((len(lo), 1), dtype=bool)
            else:
                cross = far_apart(
                    thetas[k],
                    (lengths[k] - hi, lengths[k] - lo),
                    sides[k + 1][:2],
                    l,
                    tol,
                    (radii[2 * k], radii[2 * k + 1]),
                )
            cross[-1] = cross[:, 0] = True  # a corner is no point of the other side
            self.ahead.append(cross)
        self.back[0] = self.back[:, 0] = True
        self.dead, self.steps, self.tested, self.work = set(), 0, {}, work

    def search(self):
        """One array of points per side, as :func:`place_chain` returns them (for cells: their lower ends), or None."""
        left = [np.ones(len(side[0]), dtype=bool) for side in self.sides]
        left = next(self._after(1, [0], left))
        found = None if left is None else self._extend(1, [[0]], left)
        if found is None:
            return None
        paths, left = found
        first, last = (reaches(self.sides[k][3], left[k], self.sides[k][2]) for k in (0, self.m))
        return tuple(side[0][path[1:]] for side, path in zip(self.sides, [first, *paths, last]))

    def _extend(self, k, paths, left):
        """A continuation of the points ``paths`` of ``T_1 .. T_k`` to ``T_(m-1)``'s far end, every side to come still
        split, or None."""
        i = paths[-1][-1]
        lo, _, ends, parts = self.sides[k]
        if ends[i]:
            if k == self.m - 1:
                return paths, left
            following = next(self._after(k + 1, [0], left))
            return None if following is None else self._extend(k + 1, paths + [[0]], following)
        key = (k, i, *(left[j].tobytes() for j in ((0, 2) if k == 1 else (k, k + 1))))
        if key in self.dead:
            return None
        steps = np.flatnonzero(parts[i] & left[k])
        for j, following in zip(steps.tolist(), self._after(k, steps, left)):
            if following is not None:
                found = self._extend(k, paths[:-1] + [paths[-1] + [j]], following)
                if found is not None:
                    return found
        self.dead.add(key)
        return None

    def _after(self, k, steps, left):
        """For each position ``j`` of ``steps`` on ``T_k``: ``left`` with the positions closer than ``l`` to it removed
        and reduced to the useful ones, or None (a generator, one ``j`` at a time)."""
        ahead = left[k + 1][None, :] & self.ahead[k][steps]
        back = left[0][None, :] & self.back[steps] if k == 1 else None
        for row in range(len(steps)):
            following = list(left)
            following[k + 1] = self._useful(k + 1, ahead[row])
            if following[k + 1] is not None and back is not None:
                following[0] = self._useful(0, back[row])
            yield None if following[k + 1] is None or following[0] is None else following

    def _useful(self, side, left):
        """:func:`useful` of one side's positions left (cached; each new set counts towards :data:`PAIR_STEPS`, and its
        positions towards the :class:`Work` shared, if any)."""
        key = (side, left.tobytes())
        if key not in self.tested:
            self.steps += 1
            if self.steps > PAIR_STEPS:
                raise Undecided
            if self.work is not None:
                self.work.spend(len(left))
            self.tested[key] = useful(self.sides[side][3], left, self.sides[side][2])
        return self.tested[key]
