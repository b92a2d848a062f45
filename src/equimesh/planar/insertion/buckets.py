"""The fast engine's queue of candidates, outer level: buckets by value in front of the heap of :mod:`.heap`.

Step 3 inserts the candidate first in the reference's order (largest value,
then smallest x, then smallest y, :mod:`.heap`).  A heap of every candidate
(a million entries at a million points) misses the cache at every level of
every pop, because the farthest point jumps across the region.  Here the
values are cut into buckets, :data:`PER_OCTAVE` per octave (the top mantissa
bits of the value, :func:`bucket_of`), and only one bucket at a time is a
heap:

* the heap holds every entry whose bucket is ``state[CURRENT]`` or above, the
  buckets below it every other entry, appended to chunks of :data:`CHUNK`
  entries (a singly linked list per bucket, the newest chunk first);
* a candidate goes into the heap if its bucket is at least the current one,
  else onto its bucket (:func:`offer`);
* when the heap is empty, the highest bucket that holds entries becomes the
  current one and its live entries the heap (:func:`refill`).

So the heap's top is the first of all entries in the reference's order:
every entry outside the heap lies in a lower bucket, so its value is
smaller than every value in the heap (:func:`bucket_of` does not decrease
with the value, and equal values share a bucket).  The order is exact
whatever the values pushed: a candidate above the current bucket (a value
larger than one popped before) goes into the heap and comes out next, as it
would from one heap.  In farthest-point insertion the values popped do not
increase (a new triangle's empty circumcircle lies inside the cavity's), so
a new candidate almost always lands in a bucket below, by an append to one
of the few bucket ends in use, and the heap holds one bucket: a few thousand
entries at a million points, in the cache.

The lowest bucket is that of the smallest value pushed, ``(1 - REL_TOL) l``;
values :data:`OCTAVES` octaves above it share the top bucket.  Every function
only indexes its arrays and is compiled without numba's reference counting
(:mod:`.fast`, "Compilation").
"""

import math

import numpy as np

from ..._jit import compiled
from .heap import ENTRY, compact, push

#: Buckets per octave of the value (its top 10 mantissa bits) ...
MANTISSA_BITS = 10
PER_OCTAVE = 2**MANTISSA_BITS
#: ... over this many octaves above the lowest value (values beyond share the top bucket; in the local frame
#: l is in [1, 2) and coordinates stay below 2^17, so values stay below 2^18 l).
OCTAVES = 24
BUCKETS = OCTAVES * PER_OCTAVE
#: Entries per chunk of a bucket (512 bytes).
CHUNK = 16

#: The queue's scalars, rows of the engine's state (:data:`.fast.STATE` holds them under these names): the current
#: bucket, the first free chunk (-1 none), the number of free chunks, the chunks ever used, the lowest value's octave.
QUEUE_STATE = ("current", "free_chunk", "free_chunks", "chunks", "octave")


def empty_queue(rows, chunks, low):
    """An empty queue for values of at least ``low``: ``(H, pool, link, table, q)``, a heap of ``rows`` rows and
    ``chunks`` chunks (the arrays of :func:`offer`), every value below the current bucket."""
    H, pool = np.empty(rows, dtype=ENTRY), np.empty(chunks * CHUNK, dtype=ENTRY)
    link, table = np.empty(chunks, dtype=np.int64), np.full((BUCKETS, 2), -1, dtype=np.int64)
    table[:, 1] = 0
    q = np.array([BUCKETS, -1, 0, 0, math.frexp(low)[1]], dtype=np.int64)
    return H, pool, link, table, q


empty_queue = compiled(empty_queue)


def bucket_of(value, octave):
    """The bucket of ``value`` (at least ``2^(octave - 1)``): its octave above ``octave``, then its top
    :data:`MANTISSA_BITS` mantissa bits; never smaller for a larger value."""
    m, e = math.frexp(value)
    b = (e - octave) * PER_OCTAVE + int((2.0 * m - 1.0) * PER_OCTAVE)
    return min(b, BUCKETS - 1)


bucket_of = compiled(bucket_of, nrt=False)


def offer(H, nh, pool, link, table, q, value, x, y, tag, version):
    """Queue the candidate ``(value, x, y)`` of ``tag`` at ``version``: into the heap ``H[:nh]`` if its bucket is
    the current one or above, else onto its bucket; the new heap size.

    ``q``: the queue's scalars (:data:`QUEUE_STATE`, in order).  ``table[b]``:
    bucket ``b``'s newest chunk (-1 none) and that chunk's fill, for the
    buckets below the current one only: the rows at or above it are stale
    (:func:`refill` frees a bucket's chunks as it makes it the current one
    without clearing its row), and neither function reads them again, since
    the current bucket never rises.  ``link[c]``: the chunk after ``c`` in its
    bucket or in the free list.  The caller makes sure a chunk is free or
    unused (:func:`spare_chunks`).
    """
    b = bucket_of(value, q[4])
    if b >= q[0]:
        return push(H, nh, value, x, y, tag, version)
    c, fill = table[b, 0], table[b, 1]
    if c < 0 or fill == CHUNK:
        if q[1] >= 0:
            fresh = q[1]
            q[1] = link[fresh]
            q[2] -= 1
        else:
            fresh = q[3]
            q[3] += 1
        link[fresh] = c
        c, fill = fresh, 0
        table[b, 0] = c
    i = c * CHUNK + fill
    pool[i]["key"], pool[i]["x"], pool[i]["y"], pool[i]["tag"], pool[i]["version"] = -value, x, y, tag, version
    table[b, 1] = fill + 1
    return nh


offer = compiled(offer, nrt=False)


def spare_chunks(link, q):
    """Chunks :func:`offer` can still take: the free ones and those never used."""
    return q[2] + len(link) - q[3]


spare_chunks = compiled(spare_chunks, nrt=False)


def bucket_size(link, table, b):
    """Entries in bucket ``b``."""
    c, size = table[b, 0], table[b, 1]
    if c < 0:
        return 0
    c = link[c]
    while c >= 0:
        size += CHUNK
        c = link[c]
    return size


bucket_size = compiled(bucket_size, nrt=False)


def refill(H, pool, link, table, q, ver, S, salive):
    """With the heap empty: the live entries of the highest bucket that has any become the heap; ``(size, need)``.

    Size 0: no entry is left.  ``need`` > 0: ``H`` needs that many rows for
    the next bucket, which is left as it is (the caller grows ``H`` and calls
    again).  Emptied chunks go to the free list.
    """
    b = q[0] - 1
    while b >= 0:
        if table[b, 0] < 0:
            b -= 1
            continue
        size = bucket_size(link, table, b)
        if size + 1 > len(H):
            return 0, size + 1
        c, fill, k = table[b, 0], table[b, 1], 0
        while c >= 0:
            for i in range(c * CHUNK, c * CHUNK + fill):
                H[k]["key"], H[k]["x"], H[k]["y"] = pool[i]["key"], pool[i]["x"], pool[i]["y"]
                H[k]["tag"], H[k]["version"] = pool[i]["tag"], pool[i]["version"]
                k += 1
            after = link[c]
            link[c], q[1] = q[1], c
            q[2] += 1
            c, fill = after, CHUNK
        q[0] = b
        k = compact(H, k, ver, S, salive)
        if k > 0:
            return k, 0
        b -= 1
    q[0] = 0
    return 0, 0


refill = compiled(refill, nrt=False)
