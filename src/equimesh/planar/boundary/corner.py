"""Step 2 at one sharp corner, decided on a grid: where the points of its two sides can lie.

A corner ``v`` of inner angle ``theta`` has a leaving side of length ``A``
and an arriving side of length ``B``; distances are measured from ``v``.
Any Step 2 (Algorithm INCREMENT) places ``0 = x_0 < x_1 < ... < x_m = A``
on the leaving side and ``0 = y_0 < ... < y_k = B`` on the arriving one,
every part in ``[l, 2l]``.  Lemma 3 (1) wants every two visible points of
different sides, the corner excluded, at least ``l`` apart; their distance
is ``d(a, b)^2 = a^2 + b^2 - 2 a b cos theta``.

*Merged-order lemma* (docs/proofs.md, "Sharp corners"): sort the points of
both sides by distance from ``v``; if every two points of different sides
that are consecutive in this order are ``l`` apart, every two points of
different sides are.  So a placement is a path in a graph whose state is
``(s, p, q)``: the farthest point so far is ``p``, on side ``s``, and the
last point of the other side is ``q``.  A step either adds the next point
of side ``s`` (a part in ``[l, 2l]`` after ``p``) or switches: the next
point ``w`` of the other side, a part in ``[l, 2l]`` after ``q``, at least
as far as ``p`` and at least ``l`` from it.  A side ends at its far corner;
past ``K l`` (``K l sin theta >= l``) a point is ``l`` from the whole other
side, so a side longer than ``(K + 3) l`` ends, for this graph, at its
first point past ``K l`` (its remaining length is then at least ``l``).

Two readings of the same graph, on a grid of ``l / CORNER_GRID``:

* :func:`place_corner` (a search) puts the points on grid nodes (multiples
  of the grid step from the corner or from a far end) and checks every
  step exactly: a path is a placement, by the lemma.
* :func:`corner_unplaceable` (a proof) lets a state stand for the grid
  *cells* its points lie in and allows a step when *some* points of the two
  cells satisfy it, with tolerances beyond those of the checks (parts from
  ``(1 - 2 REL_TOL) l`` to ``2 (1 + 2 REL_TOL) l``, distances from
  ``(1 - 2 REL_TOL) l``), and checks distances only between points that
  see each other.  Every placement the checks would accept is then a path
  of cells, so when there is none, no Step 2 meets Lemma 3 (1) at the
  corner.  No lemma is needed for this direction: consecutive points of
  the merged order are pairs the checks test.

Where the nodes miss a thin set of placements, :func:`tighten` places the
order of the points along a path of cells as near the corner as it allows.

Both sweep at most ``2 n^2`` states of ``n`` grid positions (``n`` about
``CORNER_GRID (K + 3)``), vectorised over ``q``.
"""

import functools
import math

import numpy as np

from ...tolerance import REL_TOL

#: Grid steps per l of :func:`place_corner` and :func:`corner_unplaceable`:
#: a bound on the work (``(16 (K + 3))^2`` states), not a tolerance; a
#: placement off the grid is found on a finer one (:data:`CORNER_REFINEMENTS`).
CORNER_GRID = 16
#: Halvings of the grid step tried before a corner is left undecided
#: (a bound on the work: the finest grid has ``CORNER_GRID * 2**CORNER_REFINEMENTS`` steps per l).
CORNER_REFINEMENTS = 2


def corner_reach(theta, l):
    """``K l`` with ``K = ceil((1 - REL_TOL) / sin theta)``: a point that far from the corner sees no other side closer
    than l."""
    return math.ceil((1.0 - REL_TOL) / math.sin(theta)) * l


def place_corner(theta, lengths, l, fixed=(None, None)):
    """Points of the two sides of a corner of ``theta`` radians, every cross pair ``l`` apart, or None if none found.

    ``lengths`` are ``(A, B)``, the leaving and arriving sides.  Returns
    ``(xs, ys)``, each side's points by distance from the corner, its far
    end included; a side longer than ``(K + 3) l`` stops at its first point
    past ``K l``.  ``fixed[s]``, if given, are side ``s``'s points (the same
    form), kept as they are.  On each grid (:data:`CORNER_GRID` steps per l,
    then finer) the nodes are searched; with no side fixed, the proof's
    relaxation then either shows that no placement exists (None) or gives
    an order of the points of the two sides, which :func:`tighten` places
    as near the corner as it allows.
    """
    reach = corner_reach(theta, l)
    for level in range(CORNER_REFINEMENTS + 1):
        step = l / (CORNER_GRID * 2**level)
        lo = nodes(lengths, reach, l, step, fixed)
        order = Graph(theta, lengths, reach, l, lo, lo, REL_TOL / 4.0, (math.inf, math.inf), fixed).search()
        if order is not None:
            return _by_side(order)
        if any(points is not None for points in fixed):
            continue
        order = relaxed(theta, tuple(lengths), l, (math.inf, math.inf), level)
        if order is None:
            return None
        found = tighten(theta, lengths, reach, l, [side for side, _ in order])
        if found is not None:
            return found
    return None


def corner_unplaceable(theta, lengths, l, radii):
    """True when no Step 2 keeps the two sides of the corner ``l`` apart (Lemma 3 (1)): proven on a grid of cells.

    ``radii`` bound the distances from the corner within which points of
    the two sides see each other (the caller proves it: the triangle of the
    corner and those two distances lies in P); pairs beyond are not
    checked.  False means only that the relaxation found a path on the
    finest grid, not that a placement exists.
    """
    return any(
        relaxed(theta, tuple(lengths), l, tuple(radii), level) is None for level in range(CORNER_REFINEMENTS + 1)
    )


@functools.lru_cache(maxsize=1024)
def relaxed(theta, lengths, l, radii, level):
    """A path of the relaxation on cells of ``l / (CORNER_GRID 2^level)`` (points in merged order), or None.

    Cached: the grid search of a ring asks for the same corner again
    (:func:`corner_unplaceable` first, then :func:`place_corner`).
    """
    reach = corner_reach(theta, l)
    lo, hi = cells(lengths, reach, l, l / (CORNER_GRID * 2**level))
    return Graph(theta, lengths, reach, l, lo, hi, 2.0 * REL_TOL, radii).search()


def _by_side(order):
    """``(xs, ys)`` from the points ``(side, distance)`` in their merged order."""
    return tuple(np.array([x for side, x in order if side == s]) for s in (0, 1))


#: Rounds of :func:`tighten` before it gives up: a bound on the work.
TIGHTEN_ROUNDS = 200


def tighten(theta, lengths, reach, l, sides):
    """The placement nearest the corner with the points in the merged order ``sides`` (side of each), or None.

    Each point is pushed to the largest of its lower bounds: ``l`` past the
    previous point of its side, as far as the point before it, past
    ``G(u) = u cos theta + sqrt(l^2 - u^2 sin^2 theta)`` (where the other
    side's point ``u`` before it stops being closer than l), its side's far
    end (``K l`` for a long side), and ``2l`` before the next point of its
    side; repeated until nothing moves.  Where ``G`` increases these bounds
    are monotone, so this is the least placement of that order if there is
    one; whatever it gives is checked pair by pair (:func:`placed`).
    """
    sides = np.asarray(sides)
    z = np.zeros(len(sides))
    last = [int(np.flatnonzero(sides == s)[-1]) for s in (0, 1)]
    ends = [reach if _long(length, reach, l) else length for length in lengths]
    before = [_previous(sides, i) for i in range(len(sides))]
    sin, cos = math.sin(theta), math.cos(theta)
    for _ in range(TIGHTEN_ROUNDS):
        old = z.copy()
        for i, s in enumerate(sides):
            low = [l if before[i] is None else z[before[i]] + l]
            if i:
                u = z[i - 1]
                low.append(u)
                if sides[i - 1] != s and u * sin < l:
                    low.append(u * cos + math.sqrt(l * l - (u * sin) ** 2))
            if i == last[s]:
                low.append(ends[s])
            z[i] = max(z[i], *low)
        for i in range(len(sides) - 1, -1, -1):
            if before[i] is not None:
                z[before[i]] = max(z[before[i]], z[i] - 2.0 * l)
        if np.array_equal(z, old):
            return placed(theta, lengths, reach, l, sides, z)
    return None


def _previous(sides, i):
    """The index of the point before ``i`` on the same side, or None."""
    same = np.flatnonzero(sides[:i] == sides[i])
    return int(same[-1]) if len(same) else None


def placed(theta, lengths, reach, l, sides, z):
    """``(xs, ys)`` if the points ``z`` of ``sides`` are a placement (checked within ``REL_TOL / 4``), else None.

    Parts in ``[l, 2l]`` from the corner, each side ending at its far end
    (a long side: past ``K l``, at least ``l`` before it), every cross pair
    at least ``l`` apart.
    """
    tol = REL_TOL / 4.0
    placed = []
    for s, length in enumerate(lengths):
        points = z[sides == s].copy()
        parts = np.diff(np.concatenate([[0.0], points]))
        if np.any(parts < (1.0 - tol) * l) or np.any(parts > 2.0 * (1.0 + tol) * l):
            return None
        if _long(length, reach, l):
            if points[-1] > length - l:
                return None
        elif abs(points[-1] - length) > tol * l:
            return None
        else:
            points[-1] = length
        placed.append(points)
    a, b = placed
    distance = a[:, None] ** 2 + b[None, :] ** 2 - 2.0 * math.cos(theta) * a[:, None] * b[None, :]
    return tuple(placed) if np.all(distance >= ((1.0 - tol) * l) ** 2) else None


def cut(points, length, reach, l):
    """A side's ``points`` by distance from the corner, up to the first past ``K l`` if the graph cuts the side
    there."""
    if not _long(length, reach, l):
        return points
    return points[: int(np.searchsorted(points, reach)) + 1]


def _long(length, reach, l):
    """A side the graph cuts at its first point past ``K l`` (the rest of it is at least ``l`` long)."""
    return length > reach + 3.0 * l


def horizon(lengths, reach, l):
    """How far from the corner the graph places points: each side's length, or ``K l + 2l`` for a long side."""
    return max(min(length, reach + 2.0 * l) if _long(length, reach, l) else length for length in lengths)


def nodes(lengths, reach, l, step, fixed):
    """Grid nodes of the search: multiples of ``step`` from the corner and from each short side's far end, and the fixed
    points."""
    top = horizon(lengths, reach, l)
    nodes = [np.arange(1, math.floor(top / step) + 1) * step]
    for length in lengths:
        if not _long(length, reach, l):
            nodes.append(length - np.arange(0, math.floor(length / step)) * step)
    nodes = np.concatenate(nodes)
    kept = [np.asarray(points, dtype=float) for points in fixed if points is not None]
    return np.unique(np.concatenate([[0.0], nodes[(nodes > 0.0) & (nodes <= top)], *kept]))


def cells(lengths, reach, l, step):
    """Cells of the proof: ``[i step, (i + 1) step]`` past the horizon, and each short side's far end as a point.

    One cell more than the horizon needs: a long side's first point past
    ``K l`` may lie up to ``2 REL_TOL l`` beyond ``K l + 2l``.
    """
    edges = np.arange(0, math.ceil(horizon(lengths, reach, l) / step) + 2) * step
    ends = [length for length in lengths if not _long(length, reach, l)]
    return np.concatenate([[0.0], edges[:-1], ends]), np.concatenate([[0.0], edges[1:], ends])


class Graph:
    """The states ``(s, p, q)`` of the module docstring over positions ``[lo, hi]`` (points: ``lo == hi``).

    ``tol`` is the relative tolerance of its steps: parts in ``[(1 - tol) l,
    2 (1 + tol) l]``, cross distances from ``(1 - tol) l``.  The search takes
    ``REL_TOL / 4``, inside the tolerance of the later checks, so that
    rounding cannot undo a step; the proof ``2 REL_TOL``, beyond it, so that
    it allows every step the checks might accept.  A side can end where
    ``ends`` and can go on where not ``stops``: both at its far end, or for a
    long side past ``K l`` (for the proof: a cell reaching past ``K l`` may
    end, one wholly past it must).
    """

    def __init__(self, theta, lengths, reach, l, lo, hi, tol, radii, fixed=(None, None)):
        self.lo, self.hi, self.n = lo, hi, len(lo)
        short, long_ = (1.0 - tol) * l, 2.0 * (1.0 + tol) * l
        part = (hi[None, :] - lo[:, None] >= short) & (lo[None, :] - hi[:, None] <= long_)
        far = self.far_enough(theta, short)
        self.cross = [far | beyond(hi, radii[s], radii[1 - s]) for s in (0, 1)]
        index = np.arange(self.n)
        self.ends, self.stops, self.next = [], [], []
        for length, points in zip(lengths, fixed):
            if _long(length, reach, l):
                ends, stops = hi >= reach, lo >= reach
                allowed = lo <= reach + long_
            else:
                ends = stops = (lo == length) & (hi == length)
                allowed = (lo < length) | ends
            step = part & (allowed & (index > 0))[None, :]
            if points is not None:
                where = np.searchsorted(lo, np.concatenate([[0.0], points]))
                step = np.zeros_like(part)
                step[where[:-1], where[1:]] = True
            self.ends.append(ends)
            self.stops.append(stops)
            self.next.append(step)

    def far_enough(self, theta, short):
        """``[p, w]``: some points of ``p`` and of ``w`` (of the other side), the latter at least as far, ``short``
        apart or more."""
        lo, hi, c = self.lo, self.hi, math.cos(theta)
        if hi is lo:  # points: the one pair
            u, v = lo[:, None], lo[None, :]
            return (v >= u) & (u * u + v * v - 2.0 * c * u * v >= short * short)
        best = np.full((self.n, self.n), -1.0)
        for u in (lo[:, None], hi[:, None]):
            for v in (lo[None, :], hi[None, :]):
                u2, v2 = np.broadcast_arrays(u, v)
                best = np.where(v2 >= u2, np.maximum(best, u2 * u2 + v2 * v2 - 2.0 * c * u2 * v2), best)
        first, last = np.maximum(lo[:, None], lo[None, :]), np.minimum(hi[:, None], hi[None, :])
        for t in (first, last):  # where the cells overlap, the diagonal v = u bounds the region too
            best = np.where(first <= last, np.maximum(best, 2.0 * (1.0 - c) * t * t), best)
        return best >= short * short

    def search(self):
        """A path from the corner to both far ends: the points of each side (:meth:`_path`), or None.

        Sweeps the positions by distance, each position with new states
        passing its steps on, until nothing new is reached (steps go no
        nearer the corner, so one sweep does nearly all).
        """
        n = self.n
        reached = np.zeros((2, n, n), dtype=bool)
        parent = np.full((2, n, n), -1, dtype=np.int64)
        reached[:, 0, 0] = True
        dirty = np.zeros((2, n), dtype=bool)
        dirty[:, 0] = True
        order = np.lexsort((self.hi, self.lo))
        while dirty.any():
            for p in order:
                for s in (0, 1):
                    if dirty[s, p]:
                        dirty[s, p] = False
                        self._step(reached, parent, dirty, s, int(p))
        for s in (0, 1):
            done = reached[s] & self.ends[s][:, None] & self.ends[1 - s][None, :]
            if done.any():
                p, q = np.argwhere(done)[0]
                return self._path(parent, (s, int(p), int(q)))
        return None

    def _step(self, reached, parent, dirty, s, p):
        """Pass on the steps out of the states ``(s, p, q)``: the next point of side ``s``, or a switch; mark what is
        new."""
        n, o, row = self.n, 1 - s, reached[s, p]
        if not self.stops[s][p]:
            targets = np.flatnonzero(self.next[s][p])
            fresh = row[None, :] & ~reached[s, targets]
            grown = fresh.any(axis=1)
            if grown.any():
                targets, fresh = targets[grown], fresh[grown]
                reached[s, targets] |= fresh
                codes = (s * n + p) * n + np.arange(n)
                parent[s, targets] = np.where(fresh, codes[None, :], parent[s, targets])
                dirty[s, targets] = True
        open_ = np.flatnonzero(row & ~self.stops[o])
        if len(open_):
            steps = self.next[o][open_]
            ws = steps.any(axis=0) & self.cross[s][p] & (self.hi >= self.lo[p]) & ~reached[o, :, p]
            if ws.any():
                ws = np.flatnonzero(ws)
                reached[o, ws, p] = True
                parent[o, ws, p] = (s * n + p) * n + open_[np.argmax(steps[:, ws], axis=0)]
                dirty[o, ws] = True

    def _path(self, parent, state):
        """The points ``(side, distance)`` along the path ending at ``state``, in their merged order."""
        n, order = self.n, []
        s, p, q = state
        while p:
            order.append((s, self.lo[p]))
            code = int(parent[s, p, q])
            s, p, q = code // (n * n), code // n % n, code % n
        return order[::-1]


def beyond(hi, mine, theirs):
    """``[p, w]``: a point of ``p`` may lie past ``mine`` or one of ``w`` past ``theirs``, where visibility is not
    proven."""
    return (hi[:, None] > mine) | (hi[None, :] > theirs)
