"""Step 2 at two sharp corners sharing a side, decided jointly on a grid: a search and a proof.

Corners ``c`` (angle ``theta_1``) and ``c + 1`` (angle ``theta_2``) share the
side ``S`` of length ``L``; ``A`` is the other side of ``c`` (arriving at it)
and ``B`` the other side of ``c + 1`` (leaving it).  Any Step 2 splits the
three sides into parts of ``[l, 2l]``; Lemma 3 (1) wants every two points of
``S`` and ``A`` (corner ``c`` excluded) and of ``S`` and ``B`` (corner
``c + 1`` excluded) at least ``l`` apart, where they see each other.  The two
corners are coupled through the points of ``S`` only.

Both readings enumerate the points of ``S`` from ``c`` to ``c + 1`` depth
first on a grid of positions (nodes for the search, cells for the proof);
every point of ``S`` removes the positions of ``A`` and of ``B`` closer than
``l`` to it (:func:`_cross`), and a prefix is dropped as soon as ``A`` or ``B``
has no split left (:func:`_reaches`: a path of parts in ``[l, 2l]`` through
the positions left, from its corner to its far end, or past ``K l`` for a long
side, where every point is ``l`` from the whole of ``S``).  What a prefix
leaves depends only on its last point and the positions left, so a failed
``(last, left on A, left on B)`` is not tried again: the work is polynomial in
the grid, and bounded by :data:`PAIR_STEPS`.

* :func:`place_pair` (a search) puts the points on grid nodes (multiples of
  the step from each end of each side) and checks every pair exactly: what
  it returns is a placement, checked pair by pair.
* :func:`pair_unplaceable` (a proof) lets positions be the grid *cells* and
  each far end; a part or a distance is allowed when *some* points of the
  two cells allow it, with the tolerances of the checks widened (parts from
  ``(1 - 2 REL_TOL) l`` to ``2 (1 + 2 REL_TOL) l``, distances from
  ``(1 - 2 REL_TOL) l``; ``d^2`` is convex, so its largest value over two
  cells is at their corners), and distances are checked only within the
  radii where the sides see each other.  Cells next to an exact end are
  clipped to the range a first or last point can have (:func:`_side`).
  Every placement the checks accept maps each point to a position holding
  it and is then an enumerated prefix that is never dropped; when every
  prefix is dropped, no Step 2 meets Lemma 3 (1) at the two corners
  together (docs/proofs.md, "Sharp corners").  With no second corner the
  same proof decides one corner on finer cells than
  :func:`._corner.corner_unplaceable`.
"""

import math

import numpy as np

from ..tolerance import REL_TOL
from ._corner import CORNER_GRID, CORNER_REFINEMENTS, corner_reach

#: Tests of :func:`_reaches` one decision may take (per grid): a bound on the
#: work, not a tolerance; past it the pair is left undecided.
PAIR_STEPS = 20000
#: Halvings of the grid step the proof tries (:func:`pair_unplaceable`, down to
#: ``l / (CORNER_GRID 2^PAIR_REFINEMENTS)`` = l/256): a bound on the work.  Finer
#: than the search's (:data:`._corner.CORNER_REFINEMENTS`): where the last
#: placements vanish at a part of exactly ``2l``, cells of l/64 still hold a path.
PAIR_REFINEMENTS = 4


class _Undecided(Exception):
    """The enumeration ran out of :data:`PAIR_STEPS`."""


def place_pair(thetas, lengths, l):
    """Points of ``A``, ``S`` and ``B`` keeping both corners ``l`` apart, or None if none is found.

    ``thetas`` are ``(theta_1, theta_2)`` in radians, ``lengths`` are
    ``(A, L, B)``.  Returns ``(a, s, b)``: ``a`` the points of ``A`` by
    distance from ``c``, ``s`` those of ``S`` by distance from ``c``, ``b``
    those of ``B`` by distance from ``c + 1``, each up to its far end, a long
    ``A`` or ``B`` stopping at a point past ``K l`` at least ``l`` before it.
    On each grid (``l / CORNER_GRID``, then halved up to
    :data:`._corner.CORNER_REFINEMENTS` times) the search runs, then, if it
    found nothing, the proof with every pair checked: None once it refutes.
    """
    if not _coupled(thetas, lengths, l):
        return None
    for level in range(CORNER_REFINEMENTS + 1):
        try:
            found = _Pair(thetas, lengths, l, level, cells=False, radii=(math.inf,) * 4).search()
            if found is not None or _Pair(thetas, lengths, l, level, cells=True, radii=(math.inf,) * 4).search() is None:
                return found
        except _Undecided:
            return None
    return None


def pair_unplaceable(thetas, lengths, l, radii):
    """True when no Step 2 keeps both corners ``l`` apart (Lemma 3 (1)): proven on a grid of cells.

    ``thetas`` and ``lengths`` as for :func:`place_pair`; ``theta_2`` None
    decides corner ``c`` alone (``B`` ignored).  ``radii`` are ``(A, S from
    c, B, S from c + 1)``: the distances from each corner within which the
    points of its two sides see each other (the caller proves it); pairs
    beyond are not checked.  Cells of ``l / CORNER_GRID`` down to
    ``l / (CORNER_GRID 2^PAIR_REFINEMENTS)``; after each grid of cells that
    refuted nothing, the search on its nodes (the finest of the search's), and False when it finds a
    placement (then no proof exists).  False means only that no grid refuted
    every prefix within :data:`PAIR_STEPS`.
    """
    if not _coupled(thetas, lengths, l):
        return False
    for level in range(PAIR_REFINEMENTS + 1):
        try:
            if _Pair(thetas, lengths, l, level, cells=True, radii=radii).search() is None:
                return True
            if level <= CORNER_REFINEMENTS and _Pair(thetas, lengths, l, level, cells=False, radii=(math.inf,) * 4).search():
                return False
        except _Undecided:
            return False
    return False


def _coupled(thetas, lengths, l):
    """Whether the shared side is short enough for the two corners to read the same points of it.

    Each corner's placement reads ``S`` only up to its first point past
    ``K l`` (at most ``K l + 2l``; past ``K l`` a point is ``l`` from the
    whole other side), so with ``L > K_1 l + K_2 l + 4l`` no point of ``S``
    matters to both: not this module's case (and its grid would grow with
    ``L``).  One corner alone is always decided here (``S`` cut like ``A``).
    """
    return thetas[1] is None or lengths[1] <= corner_reach(thetas[0], l) + corner_reach(thetas[1], l) + 4.0 * l


def _side(length, reach, l, step, cells, tol):
    """``(lo, hi, ends, parts)`` of one side: its positions, where a split may stop, and the parts allowed between them.

    Positions: the corner (0), grid nodes or cells, and the far end (last).
    A side longer than ``K l + 3l`` has no far end: it may stop at any
    position past ``K l`` (at most ``length - l`` before it: the rest is
    split into parts of ``[l, 2l]``; for cells, any reaching past ``K l``);
    positions go to ``K l + 2l`` and a cell more.  ``parts[i, j]``: a part
    from a point of ``i`` to one of ``j`` can be in ``[(1 - tol) l, 2 (1 + tol) l]``.

    Cells next to an exact end are clipped (:func:`_clipped`): the first
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
        return lo, hi, ends, _parts(lo, hi, l, tol)
    edges = np.arange(0, count + 1) * step
    keep = edges[:-1] < min(top, length)
    grid = edges[:-1][keep], np.minimum(edges[1:][keep], length)
    near, far = ((1.0 - tol) * l, 2.0 * (1.0 + tol) * l), (length - 2.0 * (1.0 + tol) * l, length - (1.0 - tol) * l)
    groups = [(np.zeros(1), np.zeros(1)), grid, _clipped(grid, *near)]  # kinds 0 corner, 1 inner, 2 first
    if not long_:
        groups += [_clipped(grid, *far), _clipped(_clipped(grid, *near), *far), (np.full(1, length), np.full(1, length))]
    kind = np.concatenate([np.full(len(group[0]), k) for k, group in enumerate(groups)])
    lo, hi = (np.concatenate([group[i] for group in groups]) for i in (0, 1))
    # corner -> first or both (or the far end); first or inner -> inner or last; last or both (or corner) -> far end
    follows = {0: (2, 4, 5), 1: (1, 3), 2: (1, 3), 3: (5,), 4: (5,), 5: ()}
    allowed = np.array([[j in follows[i] for j in range(6)] for i in range(6)])
    ends = hi >= reach if long_ else kind == 5
    return lo, hi, ends, _parts(lo, hi, l, tol) & allowed[kind[:, None], kind[None, :]]


def _clipped(cells, low, high):
    """The cells ``(lo, hi)`` cut to ``[low, high]``, those left."""
    lo, hi = np.maximum(cells[0], low), np.minimum(cells[1], high)
    return lo[lo <= hi], hi[lo <= hi]


def _parts(lo, hi, l, tol):
    """``[i, j]``: a part from a point of position ``i`` to one of ``j`` can be in ``[(1 - tol) l, 2 (1 + tol) l]``."""
    return (hi[None, :] - lo[:, None] >= (1.0 - tol) * l) & (lo[None, :] - hi[:, None] <= 2.0 * (1.0 + tol) * l)


def _cross(theta, mine, theirs, l, tol, radii):
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


def _reaches(parts, left, ends, path=False):
    """Whether a path of ``parts`` through the positions ``left`` goes from position 0 to one of ``ends``.

    With ``path``, its positions (or None): breadth first, each position
    after one reached a round earlier.
    """
    when = np.full(len(left), -1)
    when[0] = rounds = 0
    fresh = when == 0
    while fresh.any() and (path or not (ends & (when >= 0)).any()):
        rounds += 1
        fresh = parts[fresh].any(axis=0) & left & (when < 0)
        when[fresh] = rounds
    done = np.flatnonzero(ends & (when >= 0))
    if not path:
        return bool(len(done))
    if not len(done):
        return None
    found = [int(done[0])]
    while found[-1]:
        found.append(int(np.flatnonzero((when == when[found[-1]] - 1) & parts[:, found[-1]])[0]))
    return found[::-1]


class _Pair:
    """The enumeration of the module docstring on one grid (``l / (CORNER_GRID 2^level)``), nodes or cells."""

    def __init__(self, thetas, lengths, l, level, cells, radii):
        step = l / (CORNER_GRID * 2**level)
        tol = 2.0 * REL_TOL if cells else REL_TOL / 4.0
        (a, s, b), alone = lengths, thetas[1] is None
        self.a = _side(a, corner_reach(thetas[0], l), l, step, cells, tol)
        self.b = (np.zeros(1), np.zeros(1), np.ones(1, dtype=bool), np.zeros((1, 1), dtype=bool))
        if not alone:
            self.b = _side(b, corner_reach(thetas[1], l), l, step, cells, tol)
        # alone, S is cut past K l like A; a pair reads all of S (short enough: _coupled)
        lo, hi, self.s_ends, s_parts = _side(s, corner_reach(thetas[0], l) if alone else math.inf, l, step, cells, tol)
        self.s = lo, hi
        self.parts = [self.a[3], s_parts, self.b[3]]
        self.cross_a = _cross(thetas[0], self.s, self.a[:2], l, tol, (radii[1], radii[0]))
        self.cross_b = np.ones((len(lo), 1), dtype=bool) if alone else _cross(thetas[1], (s - hi, s - lo), self.b[:2], l, tol, (radii[3], radii[2]))
        self.cross_a[0] = self.cross_b[-1] = True  # a corner is no point of the other side
        self.cross_a[:, 0] = self.cross_b[:, 0] = True
        self.dead, self.steps, self.tested = set(), 0, {}

    def search(self):
        """``(a, s, b)`` as :func:`place_pair` returns them (for cells: their lower ends), or None."""
        left_a, left_b = self.cross_a[0].copy(), self.cross_b[0].copy()
        found = self._extend([0], left_a, left_b)
        if found is None:
            return None
        path, left_a, left_b = found
        a = _reaches(self.parts[0], left_a, self.a[2], path=True)
        b = _reaches(self.parts[2], left_b, self.b[2], path=True)
        return self.a[0][a[1:]], self.s[0][path[1:]], self.b[0][b[1:]]

    def _extend(self, path, left_a, left_b):
        """A continuation of the points ``path`` of ``S`` to its far end with ``A`` and ``B`` still split, or None."""
        i = path[-1]
        if self.s_ends[i]:
            return path, left_a, left_b
        key = (i, left_a.tobytes(), left_b.tobytes())
        if key in self.dead:
            return None
        for j in np.flatnonzero(self.parts[1][i]):
            next_a, next_b = left_a & self.cross_a[j], left_b & self.cross_b[j]
            if self._splits(next_a, next_b):
                found = self._extend(path + [int(j)], next_a, next_b)
                if found is not None:
                    return found
        self.dead.add(key)
        return None

    def _splits(self, left_a, left_b):
        """Whether ``A`` and ``B`` can still be split through the positions left (cached)."""
        key = (left_a.tobytes(), left_b.tobytes())
        if key not in self.tested:
            self.steps += 1
            if self.steps > PAIR_STEPS:
                raise _Undecided
            self.tested[key] = _reaches(self.parts[0], left_a, self.a[2]) and _reaches(self.parts[2], left_b, self.b[2])
        return self.tested[key]
