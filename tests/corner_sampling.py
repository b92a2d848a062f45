"""Placements of the two sides of a corner (or of sharp corners in a row) enumerated on a grid, independently of
planar/boundary/corner.py and chain.py.

A placement splits each side (lengths by distance from the corner) into parts of ``[l, 2l]`` and keeps every
two points of different sides at least ``l`` apart (the corner excluded).  :func:`sampled_placement` tries
every split whose parts, all but the last, are multiples of ``step l`` from ``l`` to ``2l``, checking every
pair directly, with the other side's points pruned as soon as one is too close.  Finding none confirms,
without proving, that a corner refused as impossible to separate has no placement.  :func:`sampled_chain`
does the same for sharp corners in a row (two sharing a side, or more): every split of each shared side, given the
previous one's, then the first and last corner's other sides.
"""

import functools
import math

import numpy as np

from equimesh.planar.boundary import corner
from equimesh.tolerance import REL_TOL


def _splits(length, l, step, theta=0.0, fixed=()):
    """Every split of ``length`` into parts of [l, 2l], all but the last a multiple of ``step l``, whose every point
    is at least l from every point of ``fixed`` (distances from the corner on its other side): its points."""
    fixed = np.asarray(fixed, dtype=float)
    out, stack = [], [(0.0, ())]
    while stack:
        at, points = stack.pop()
        if l <= length - at <= 2.0 * l and _far_enough(theta, length, fixed, l):
            out.append(np.array(points + (length,)))
        for part in np.arange(l, 2.0 * l + 1e-9, step * l):
            if at + part <= length - l and _far_enough(theta, at + part, fixed, l):
                stack.append((at + part, points + (at + part,)))
    return out


def _far_enough(theta, a, points, l):
    """Whether every point of ``points`` is at least l from every point at distance ``a`` on the other side."""
    return np.all(a * a + points * points - 2.0 * math.cos(theta) * a * points >= l * l)


def sampled_placement(theta, lengths, l, step=0.125):
    """``(xs, ys)`` for the corner of ``theta`` radians and sides ``lengths``, or None if no split on the grid works."""
    for xs in _splits(lengths[0], l, step):
        stack = [(0.0, ())]
        while stack:
            at, points = stack.pop()
            if l <= lengths[1] - at <= 2.0 * l and _far_enough(theta, lengths[1], xs, l):
                return xs, np.array(points + (lengths[1],))
            for part in np.arange(l, 2.0 * l + 1e-9, step * l):
                y = at + part
                if y <= lengths[1] - l and _far_enough(theta, y, xs, l):
                    stack.append((y, points + (y,)))
    return None


def _fits(theta, fixed, length, l, step):
    """Whether some split of ``length`` (parts but the last multiples of ``step l``) keeps every point l from ``fixed``
    (distances from the corner on its other side)."""
    stack = [0.0]
    while stack:
        at = stack.pop()
        if l <= length - at <= 2.0 * l and _far_enough(theta, length, fixed, l):
            return True
        for part in np.arange(l, 2.0 * l + 1e-9, step * l):
            y = at + part
            if y <= length - l and _far_enough(theta, y, fixed, l):
                stack.append(y)
    return False


def sampled_chain(thetas, lengths, l, step=0.125):
    """Splits of the shared sides ``T_1 .. T_(m-1)`` of consecutive corners of ``thetas`` (sides ``T_0 .. T_m``:
    ``T_0`` arriving at the first corner, ``T_m`` leaving the last) keeping every corner's two sides l apart, with
    ``T_0`` and ``T_m`` split too, or None.  Each shared side's splits are enumerated given the previous one's points
    near their common corner (within ``K l``,
    ``K l sin theta >= l``: farther points are l from the whole other side)."""
    m = len(thetas)

    @functools.lru_cache(maxsize=None)
    def place(k, near):
        for xs in _splits(lengths[k], l, step, thetas[k - 1], near):
            if k == 1 and not _fits(thetas[0], xs, lengths[0], l, step):
                continue
            back = lengths[k] - np.append(0.0, xs[:-1])  # T_k's points by distance from corner k
            if k == m - 1:
                if _fits(thetas[k], back, lengths[m], l, step):
                    return (xs,)
                continue
            found = place(k + 1, tuple(back[back * math.sin(thetas[k]) < l]))
            if found is not None:
                return (xs, *found)
        return None

    return place(1, ())


def corners(rings):
    """``(theta, leaving, arriving)`` of every corner of ``rings`` (the region on their left): radians, lengths."""
    for ring in rings:
        for prev, v, nxt in zip(np.roll(ring, 1, axis=0), ring, np.roll(ring, -1, axis=0)):
            u, w = nxt - v, prev - v
            theta = math.atan2(u[0] * w[1] - u[1] * w[0], float(np.dot(u, w))) % (2.0 * math.pi)
            yield theta, float(np.linalg.norm(u)), float(np.linalg.norm(w))


# --------------------------------------------------------------------------- corners built by hand, and placements
# checked pair by pair


def at(angle, r):
    """The point ``r`` from the origin at ``angle`` degrees."""
    return np.array([r * math.cos(math.radians(angle)), r * math.sin(math.radians(angle))])


def cross(theta, a, b):
    """Distances between every point at distances ``a`` on one side and ``b`` on the other."""
    a, b = np.asarray(a)[:, None], np.asarray(b)[None, :]
    return np.sqrt(np.maximum(a * a + b * b - 2.0 * math.cos(theta) * a * b, 0.0))


def assert_placement(theta, lengths, l, found):
    """Parts in [l, 2l], each side ending at its far end (or, cut short, at least l before it and past K l),
    every cross pair l apart; all up to REL_TOL."""
    reach = corner.corner_reach(theta, l)
    for points, length in zip(found, lengths):
        steps = np.diff(np.concatenate([[0.0], points]))
        assert np.all(steps >= (1.0 - REL_TOL) * l) and np.all(steps <= 2.0 * (1.0 + REL_TOL) * l), points
        assert points[-1] == length or (reach <= points[-1] <= length - (1.0 - REL_TOL) * l), (points, length)
    assert cross(theta, *found).min() >= (1.0 - REL_TOL) * l
