"""The fast engine's heap of candidates (``planar/insertion/heap.py``).

What must hold:

* the heap pops its entries in the reference's order (largest value, then smallest x, then smallest y), the tag
  last, with every field of an entry kept, whatever the order of the pushes;
* after every push every entry comes no earlier than its parent, entry ``(i - 1) // 4`` (the order pop relies on);
* compaction keeps exactly the live entries (current version, live segment), in heap order.

Small inputs with many ties, run compiled and as Python (``NUMBA_DISABLE_JIT=1``, ``tools/mutation``).
"""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from equimesh.planar.insertion import heap

#: Keys with many ties in value, then in x, then in y.
heap_keys = st.lists(
    st.tuples(st.sampled_from([1.0, 1.5, 2.0]), st.sampled_from([0.0, 1.0]), st.sampled_from([0.0, 1.0])),
    min_size=1,
    max_size=40,
)


def _heap(keys):
    """Entry ``i``: the key ``keys[i]``, tag ``4 i + i % 4`` (slot ``i``, edge ``i % 4 - 1``), version ``10 + i``."""
    H = np.empty(len(keys) + 1, dtype=heap.ENTRY)
    n = 0
    for i, (value, x, y) in enumerate(keys):
        n = heap.push(H, n, value, x, y, 4 * i + i % 4, 10 + i)
        _assert_heap_order(H, n)
    return H, n


def _assert_heap_order(H, n):
    """No entry of ``H[:n]`` comes before its parent ``(i - 1) // ARITY``."""
    assert not any(heap.earlier(H, i, (i - 1) // heap.ARITY) for i in range(1, n))


def _pop_all(H, n):
    out = []
    while n:
        n = heap.pop(H, n)
        out.append((-H[n]["key"], H[n]["x"], H[n]["y"], int(H[n]["tag"]), int(H[n]["version"])))
    return out


def _order(entry):
    return (-entry[0], entry[1], entry[2], entry[3])


@given(heap_keys)
def test_heap_pops_the_largest_value_then_smallest_x_then_y_then_tag(keys):
    H, n = _heap(keys)
    assert n == len(keys)
    popped = _pop_all(H, n)
    assert popped == sorted(((*k, 4 * i + i % 4, 10 + i) for i, k in enumerate(keys)), key=_order)


def test_an_entry_is_lifted_along_its_parents():
    """Ten distinct values: 9, pushed eighth, starts in row 7, whose parent is row 1 ((7 - 1) // 4), and is lifted
    through it to the top; the heap order holds after each push, and the pops give the values in decreasing order."""
    values = [5.0, 7.0, 8.0, 3.0, 1.0, 2.0, 6.0, 9.0, 0.0, 4.0]
    H, n = _heap([(v, 0.0, 0.0) for v in values])
    assert -H[0]["key"] == 9.0
    assert [e[0] for e in _pop_all(H, n)] == sorted(values, reverse=True)


def test_earlier_is_lexicographic():
    H = np.zeros(6, dtype=heap.ENTRY)
    for i, entry in enumerate([(-2.0, 5.0, 5.0, 9), (-1.0, 0.0, 0.0, 0), (-1.0, 0.0, 5.0, 0), (-1.0, 1.0, 0.0, 0)]):
        H[i]["key"], H[i]["x"], H[i]["y"], H[i]["tag"] = entry
    H[4], H[5] = H[3], H[3]
    H[5]["tag"] = 1
    for i, j in [(0, 1), (1, 2), (2, 3), (4, 5)]:
        assert heap.earlier(H, i, j) and not heap.earlier(H, j, i)
    assert not heap.earlier(H, 3, 4) and not heap.earlier(H, 4, 3)


@given(heap_keys, st.data())
def test_compact_keeps_exactly_the_live_entries_in_heap_order(keys, data):
    """An entry lives when its slot's version is current and the segment on its edge (if any) is alive."""
    H, n = _heap(keys)
    ver = np.array([10 + i + data.draw(st.sampled_from([0, 0, 1])) for i in range(len(keys))], dtype=np.int64)
    S = np.arange(3 * len(keys), dtype=np.int64).reshape(-1, 3) % 2  # the edges' segments: 0 and 1 in turn
    salive = np.array([data.draw(st.booleans()), data.draw(st.booleans())])
    live = [i for i in range(len(keys)) if ver[i] == 10 + i and (i % 4 == 0 or salive[S[i, i % 4 - 1]])]
    k = heap.compact(H, n, ver, S, salive)
    assert k == len(live)
    popped = _pop_all(H, k)
    assert popped == sorted(((*keys[i], 4 * i + i % 4, 10 + i) for i in live), key=_order)
