"""The fast engine's queue of candidates: a 4-ary min-heap of 32-byte records, compiled.

Step 3 of Algorithm INCREMENT inserts the farthest candidate, largest value
first, then smallest x, then smallest y (the reference engine's lexsort,
:mod:`.reference`).  An entry is a record of :data:`ENTRY`: ``key`` = minus
the value, ``x``, ``y``, ``tag`` = ``4 t + e + 1`` for the candidate of
triangle slot ``t`` (``e`` = -1 its circumcentre, else the constraint edge
``e`` whose midpoint it is) and ``version``, that slot's version when it was
pushed; the heap is ordered by ``(key, x, y, tag)``, lexicographically.  Two
candidates of one point set never share ``(t, e)``, so the order is strict
among them, and the top is the reference's choice (when two candidates have
the same value and point, the lower ``tag`` first: either inserts the same
point).

The heap holds the entries of one bucket of values at a time (:mod:`.buckets`
keeps the others), a few thousand at a million points.  Layout, for the
cache: each record holds everything the pop reads (one array, not one for
keys and one for the rest), the four children of an
entry are adjacent (128 bytes), and a 4-ary heap is half as tall as a binary
one.  A pop moves the hole left by the top down along the smaller children to
a leaf and then lifts the last entry from there (Floyd's "bottom-up" pop:
the last entry belongs near the bottom, so this saves most comparisons with it).

Every function only indexes its arrays and is compiled without numba's
reference counting (:mod:`.fast`, "Compilation").
"""

import numpy as np

from ..._jit import compiled

#: One heap entry (32 bytes).
ENTRY = np.dtype([("key", np.float64), ("x", np.float64), ("y", np.float64), ("tag", np.int32), ("version", np.int32)])

#: Children per entry.
ARITY = 4
#: Slots a tag can name (``4 t + 3`` in an int32); versions, at most the insertions, stay below it too.
MAX_SLOTS = 2**29


def earlier(H, i, j):
    """Whether entry ``i`` of ``H`` comes before entry ``j``: ``(key, x, y, tag)`` lexicographically."""
    a, b = H[i], H[j]
    if a["key"] != b["key"]:
        return a["key"] < b["key"]
    if a["x"] != b["x"]:
        return a["x"] < b["x"]
    if a["y"] != b["y"]:
        return a["y"] < b["y"]
    return a["tag"] < b["tag"]


earlier = compiled(earlier, nrt=False)


def move(H, dst, src):
    """Copy entry ``src`` of ``H`` to ``dst``."""
    H[dst]["key"], H[dst]["x"], H[dst]["y"] = H[src]["key"], H[src]["x"], H[src]["y"]
    H[dst]["tag"], H[dst]["version"] = H[src]["tag"], H[src]["version"]


move = compiled(move, nrt=False)


def sift_up(H, i):
    """Move entry ``i`` up to its place (every entry above it is in heap order); uses row ``len(H) - 1`` as scratch.

    The entries it passes move down one level each and it is written once at the end.
    """
    scratch = len(H) - 1
    move(H, scratch, i)
    while i > 0:
        parent = (i - 1) // ARITY
        if not earlier(H, scratch, parent):
            break
        move(H, i, parent)
        i = parent
    move(H, i, scratch)


sift_up = compiled(sift_up, nrt=False)


def earliest_child(H, c, n):
    """The earliest of the children ``c, c + 1, ..`` of one entry (at most :data:`ARITY`, all below ``n``)."""
    best = c
    for d in range(c + 1, min(c + ARITY, n)):
        if earlier(H, d, best):
            best = d
    return best


earliest_child = compiled(earliest_child, nrt=False)


def push(H, n, value, x, y, tag, version):
    """Add the candidate ``(value, x, y)`` of ``tag`` at ``version`` to the heap ``[:n]``; the new size.

    ``H`` needs a row beyond ``n``, its last row, for scratch.
    """
    H[n]["key"], H[n]["x"], H[n]["y"], H[n]["tag"], H[n]["version"] = -value, x, y, tag, version
    sift_up(H, n)
    return n + 1


push = compiled(push, nrt=False)


def pop(H, n):
    """Remove the top of the heap ``[:n]`` and copy it to row ``n - 1``; the new size.

    The hole left by the top moves down along the earlier child to a leaf,
    where the last entry goes and is lifted to its place.
    """
    scratch = len(H) - 1
    move(H, scratch, 0)
    last = n - 1
    hole = 0
    while True:
        c = ARITY * hole + 1
        if c >= last:
            break
        best = earliest_child(H, c, last)
        move(H, hole, best)
        hole = best
    if hole != last:
        move(H, hole, last)
        move(H, last, scratch)
        sift_up(H, hole)
    else:
        move(H, last, scratch)
    return last


pop = compiled(pop, nrt=False)


def entry_live(H, i, ver, S, salive):
    """Whether entry ``i`` is still a candidate: its slot's version is current and its constraint edge, if any,
    still a live segment."""
    t, e = H[i]["tag"] >> 2, (H[i]["tag"] & 3) - 1
    return ver[t] == H[i]["version"] and (e < 0 or salive[S[t, e]])


entry_live = compiled(entry_live, nrt=False)


def compact(H, n, ver, S, salive):
    """Drop the dead entries of the heap ``[:n]`` (lazy deletion's garbage), the heap order kept; the new size.

    The live entries are pushed again in turn (each lifted from the end of the
    heap so far), which keeps the heap order at any step.
    """
    k = 0
    for i in range(n):
        if entry_live(H, i, ver, S, salive):
            move(H, k, i)
            sift_up(H, k)
            k += 1
    return k


compact = compiled(compact, nrt=False)
