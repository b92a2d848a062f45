"""The fast engine's buckets in front of its heap (``planar/insertion/buckets.py``).

What must hold:

* the bucket of a value never decreases as the value grows, equal values share one, and values far above the lowest
  share the top bucket;
* offers and pops in any interleaving (values above the current bucket included, entries dying on the way) give the
  live entries in the order of one heap of them all (:mod:`.heap`'s): largest value, then smallest x, smallest y, tag;
* a bucket too large for the heap is left as it is and its size returned; emptied chunks are reused.

Small inputs with many ties, run compiled and as Python (``NUMBA_DISABLE_JIT=1``, ``tools/mutation``).
"""

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from equimesh.planar.insertion import buckets, heap

LOW = 1.0 - 1e-9

#: Values at least LOW: equal, in one bucket, in neighbouring buckets, octaves apart, beyond the top bucket.
values = st.sampled_from([LOW, 1.0, 1.0 + 1e-12, 1.0004, 1.002, 1.5, 2.0, 3.0, 2.0**30, 2.0**40])

#: Offer a value at (x, y); pop; or kill the entry offered ``k``-th (bump its slot's version).
operations = st.lists(
    st.one_of(
        st.tuples(st.just("offer"), values, st.sampled_from([0.0, 1.0]), st.sampled_from([0.0, 1.0])),
        st.tuples(st.just("pop")),
        st.tuples(st.just("kill"), st.integers(0, 40)),
    ),
    max_size=80,
)


@given(st.floats(LOW, 2.0**60), st.floats(LOW, 2.0**60))
def test_buckets_follow_the_values(a, b):
    octave = math.frexp(LOW)[1]
    lo, hi = sorted((a, b))
    assert 0 <= buckets.bucket_of(lo, octave) <= buckets.bucket_of(hi, octave) < buckets.BUCKETS
    assert buckets.bucket_of(2.0**40, octave) == buckets.BUCKETS - 1


def test_bucket_by_hand():
    """The octave above the lowest, then the top mantissa bits: 1 and 1 + 2^-11 share a bucket, 1 + 2^-10 is next."""
    octave = math.frexp(1.0)[1]
    assert buckets.bucket_of(1.0, octave) == buckets.bucket_of(1.0 + 2.0**-11, octave) == 0
    assert buckets.bucket_of(1.0 + 2.0**-10, octave) == 1
    assert buckets.bucket_of(2.0, octave) == buckets.PER_OCTAVE


def _entry(H, i):
    return (-H[i]["key"], H[i]["x"], H[i]["y"], int(H[i]["tag"]), int(H[i]["version"]))


def _order(entry):
    return (-entry[0], entry[1], entry[2], entry[3])


def _next_live(queue, nh, ver, S, salive):
    """The engine's pop: refill an empty heap, skip dead entries; ``(entry or None, nh)``."""
    H, pool, link, table, q = queue
    while True:
        if nh == 0:
            nh, need = buckets.refill(H, pool, link, table, q, ver, S, salive)
            assert need == 0
            if nh == 0:
                return None, 0
        nh = heap.pop(H, nh)
        if heap.entry_live(H, nh, ver, S, salive):
            return _entry(H, nh), nh


@given(operations)
def test_offers_and_pops_give_the_live_entries_in_heap_order(ops):
    """Entry ``k`` (the ``k``-th offer): slot ``k``, a circumcentre (tag ``4 k``), version 0 until killed."""
    queue = buckets.empty_queue(100, 100, LOW)
    H, pool, link, table, q = queue
    ver, S, salive = np.zeros(100, dtype=np.int64), np.full((100, 3), -1, dtype=np.int64), np.ones(1, dtype=bool)
    nh, waiting, offered = 0, {}, 0
    for op in ops + [("pop",)] * 80:
        if op[0] == "offer":
            k, offered = offered, offered + 1
            nh = buckets.offer(H, nh, pool, link, table, q, op[1], op[2], op[3], 4 * k, 0)
            waiting[k] = (op[1], op[2], op[3], 4 * k, 0)
        elif op[0] == "kill":
            ver[op[1]] += 1
        else:
            got, nh = _next_live(queue, nh, ver, S, salive)
            live = [e for k, e in waiting.items() if ver[k] == 0]
            assert got == (min(live, key=_order) if live else None)
            if got is not None:
                del waiting[got[3] // 4]


def test_values_in_and_above_the_current_bucket_go_to_the_heap():
    """After 1.5 is popped (its bucket the current one), 1.5 again and 3.0 are in the heap, 1.0 in a bucket below:
    they come out 3.0, 1.5, 1.0."""
    queue = buckets.empty_queue(10, 4, LOW)
    H, pool, link, table, q = queue
    ver, S, salive = np.zeros(4, dtype=np.int64), np.full((4, 3), -1, dtype=np.int64), np.ones(1, dtype=bool)
    assert buckets.offer(H, 0, pool, link, table, q, 1.5, 0.0, 0.0, 0, 0) == 0
    assert _next_live(queue, 0, ver, S, salive) == ((1.5, 0.0, 0.0, 0, 0), 0)
    nh = buckets.offer(H, 0, pool, link, table, q, 1.5, 1.0, 0.0, 4, 0)
    nh = buckets.offer(H, nh, pool, link, table, q, 3.0, 0.0, 0.0, 8, 0)
    assert buckets.offer(H, nh, pool, link, table, q, 1.0, 0.0, 0.0, 12, 0) == nh == 2
    out = []
    for _ in range(4):
        got, nh = _next_live(queue, nh, ver, S, salive)
        out.append(got and got[0])
    assert out == [3.0, 1.5, 1.0, None]


def test_a_bucket_too_large_for_the_heap_waits_and_its_chunks_are_reused():
    """40 entries in one bucket, a heap of 10 rows: the bucket stays and needs 41 rows; with them, every entry comes
    out and the three chunks it took are free again."""
    H, pool, link, table, q = buckets.empty_queue(10, 8, LOW)
    ver, S, salive = np.zeros(40, dtype=np.int64), np.full((40, 3), -1, dtype=np.int64), np.ones(1, dtype=bool)
    for k in range(40):
        assert buckets.offer(H, 0, pool, link, table, q, 1.5, float(k), 0.0, 4 * k, 0) == 0
    assert buckets.spare_chunks(link, q) == 5 and buckets.bucket_size(link, table, buckets.bucket_of(1.5, q[4])) == 40
    before = q.copy()
    assert buckets.refill(H, pool, link, table, q, ver, S, salive) == (0, 41)
    assert (q == before).all()
    H = np.empty(41, dtype=heap.ENTRY)
    nh, need = buckets.refill(H, pool, link, table, q, ver, S, salive)
    assert (nh, need) == (40, 0) and buckets.spare_chunks(link, q) == 8 and q[2] == 3
    xs = []
    while nh:
        nh = heap.pop(H, nh)
        xs.append(H[nh]["x"])
    assert xs == [float(k) for k in range(40)]
    assert buckets.refill(H, pool, link, table, q, ver, S, salive) == (0, 0)


def _queue(rows, chunks, low, slots):
    """An empty queue and the slots' versions, segments and segment flags of :func:`buckets.refill`."""
    ver, S, salive = np.zeros(slots, dtype=np.int64), np.full((slots, 3), -1, dtype=np.int64), np.ones(1, dtype=bool)
    return buckets.empty_queue(rows, chunks, low), ver, S, salive


def test_bucket_size_counts_every_chunk():
    """Offered one at a time, 33 entries fill chunk 0 (the first taken), then chunk 1, then one in chunk 2: the size
    counts each of them; a bucket never offered to holds none."""
    (H, pool, link, table, q), _, _, _ = _queue(4, 3, LOW, 40)
    b = buckets.bucket_of(1.5, q[4])
    sizes = [buckets.bucket_size(link, table, b)]
    for k in range(2 * buckets.CHUNK + 1):
        buckets.offer(H, 0, pool, link, table, q, 1.5, float(k), 0.0, 4 * k, 0)
        sizes.append(buckets.bucket_size(link, table, b))
    assert table[b, 0] == 2 and sizes == list(range(34)) and buckets.bucket_size(link, table, b - 1) == 0


def test_a_chunk_freed_by_a_refill_is_taken_again():
    """A queue of one chunk: 1.5 fills it, the refill frees it (one spare), and 1.0, below the current bucket then,
    takes that chunk again (none spare), and comes out after 1.5."""
    (H, pool, link, table, q), ver, S, salive = _queue(4, 1, LOW, 2)
    assert buckets.offer(H, 0, pool, link, table, q, 1.5, 0.0, 0.0, 0, 0) == 0 and buckets.spare_chunks(link, q) == 0
    assert buckets.refill(H, pool, link, table, q, ver, S, salive) == (1, 0) and buckets.spare_chunks(link, q) == 1
    assert buckets.offer(H, 1, pool, link, table, q, 1.0, 0.0, 0.0, 4, 0) == 1
    assert buckets.spare_chunks(link, q) == 0 and table[buckets.bucket_of(1.0, q[4]), 0] == 0
    got, nh = _next_live((H, pool, link, table, q), 1, ver, S, salive)
    assert got[0] == 1.5 and _next_live((H, pool, link, table, q), nh, ver, S, salive)[0][0] == 1.0
    assert buckets.spare_chunks(link, q) == 1


def test_a_bucket_needs_a_row_beyond_its_entries():
    """A heap of 4 rows takes a bucket of 3 entries (the pop's scratch row beyond them) but not one of 4: that one
    needs 5 rows."""
    for size, answer in [(3, (3, 0)), (4, (0, 5))]:
        (H, pool, link, table, q), ver, S, salive = _queue(4, 1, LOW, size)
        for k in range(size):
            buckets.offer(H, 0, pool, link, table, q, 1.5, float(k), 0.0, 4 * k, 0)
        assert buckets.refill(H, pool, link, table, q, ver, S, salive) == answer


def test_a_bucket_of_dead_entries_is_passed_over():
    """Three buckets, the top one's entries all dead and one of the middle one's: the refill drops them (the chunks
    free again), the middle bucket's live entry is the heap, then the lowest's entry; nothing after."""
    (H, pool, link, table, q), ver, S, salive = _queue(8, 3, LOW, 6)
    for k, value in enumerate([3.0, 3.0, 2.0, 2.0, 1.0]):
        buckets.offer(H, 0, pool, link, table, q, value, 0.0, float(k), 4 * k, 0)
    ver[[0, 1, 2]] = 1
    assert buckets.refill(H, pool, link, table, q, ver, S, salive) == (1, 0)
    assert q[0] == buckets.bucket_of(2.0, q[4]) and buckets.spare_chunks(link, q) == 2
    got, nh = _next_live((H, pool, link, table, q), 1, ver, S, salive)
    assert got == (2.0, 0.0, 3.0, 12, 0)
    assert _next_live((H, pool, link, table, q), nh, ver, S, salive)[0] == (1.0, 0.0, 4.0, 16, 0)
    assert _next_live((H, pool, link, table, q), 0, ver, S, salive) == (None, 0)
    assert buckets.spare_chunks(link, q) == 3


def test_the_lowest_bucket_and_a_queue_run_dry():
    """The lowest value 1 is bucket 0: its entry comes out of the refill; once the queue is empty, every bucket is
    at least the current one, so an entry offered then goes into the heap."""
    (H, pool, link, table, q), ver, S, salive = _queue(4, 1, 1.0, 2)
    assert buckets.bucket_of(1.0, q[4]) == 0
    assert buckets.offer(H, 0, pool, link, table, q, 1.0, 0.0, 0.0, 0, 0) == 0
    got, nh = _next_live((H, pool, link, table, q), 0, ver, S, salive)
    assert got == (1.0, 0.0, 0.0, 0, 0) and _next_live((H, pool, link, table, q), nh, ver, S, salive) == (None, 0)
    assert buckets.offer(H, 0, pool, link, table, q, 1.0, 1.0, 0.0, 4, 0) == 1
