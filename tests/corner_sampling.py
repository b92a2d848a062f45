"""Placements of the two sides of a corner (or of two corners sharing a side) enumerated on a grid, independently of planar/_corner.py and planar/_coupled.py.

A placement splits each side (lengths by distance from the corner) into parts of ``[l, 2l]`` and keeps every
two points of different sides at least ``l`` apart (the corner excluded).  :func:`sampled_placement` tries
every split whose parts, all but the last, are multiples of ``step l`` from ``l`` to ``2l``, checking every
pair directly, with the other side's points pruned as soon as one is too close.  Finding none confirms,
without proving, that a corner refused as impossible to separate has no placement.  :func:`sampled_pair`
does the same for two corners sharing a side: every split of the shared side, then each corner's other side.
"""

import math

import numpy as np


def _splits(length, l, step):
    """Every split of ``length`` into parts of [l, 2l], all but the last a multiple of ``step l``: its points."""
    out, stack = [], [(0.0, ())]
    while stack:
        at, points = stack.pop()
        if l <= length - at <= 2.0 * l:
            out.append(np.array(points + (length,)))
        for part in np.arange(l, 2.0 * l + 1e-9, step * l):
            if at + part <= length - l:
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


def sampled_pair(thetas, lengths, l, step=0.125):
    """The split of the shared side for corners of ``thetas`` sharing it, with sides ``(A, L, B)`` (``A`` arriving at
    the first corner, ``B`` leaving the second), for which both other sides can be split, or None."""
    a, s, b = lengths
    for xs in _splits(s, l, step):
        if _fits(thetas[0], xs, a, l, step) and _fits(thetas[1], s - np.append(0.0, xs[:-1]), b, l, step):
            return xs
    return None


def corners(rings):
    """``(theta, leaving, arriving)`` of every corner of ``rings`` (the region on their left): radians, lengths."""
    for ring in rings:
        for prev, v, nxt in zip(np.roll(ring, 1, axis=0), ring, np.roll(ring, -1, axis=0)):
            u, w = nxt - v, prev - v
            theta = math.atan2(u[0] * w[1] - u[1] * w[0], float(np.dot(u, w))) % (2.0 * math.pi)
            yield theta, float(np.linalg.norm(u)), float(np.linalg.norm(w))
