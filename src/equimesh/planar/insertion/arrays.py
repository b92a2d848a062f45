"""The fast engine's arrays: grown by doubling, and the triangle store.

The farthest point jumps across the region, so at a million points every
insertion reaches its triangles in memory that no cache holds.  Each
triangle is one 64-byte row of int32 (:func:`triangle_store`): its vertices,
neighbours and constraint segments (``V``, ``N``, ``S`` of :mod:`.cdt`, as
column views, :func:`store_views`), its cavity mark, version and whether it
is alive, read by one cache line where separate int64 arrays took four.
Rows not yet used are not initialised: memory never touched costs nothing.
"""

import numpy as np

from ..._jit import compiled

#: The columns of the triangle store after V, N and S (0-8): the cavity mark, the version, alive; a row of ROW.
MARK, VERSION, ALIVE, ROW = 9, 10, 11, 16


def grown(a, size):
    """``a`` in a zero-filled array of ``size`` rows."""
    out = np.zeros((size,) + a.shape[1:], dtype=a.dtype)
    out[: len(a)] = a
    return out


grown = compiled(grown)


def extended(a, size):
    """``a`` in an array of ``size`` rows, the rows beyond it not initialised (for arrays whose rows are written
    before they are read: memory never touched costs nothing)."""
    out = np.empty((size,) + a.shape[1:], dtype=a.dtype)
    out[: len(a)] = a
    return out


extended = compiled(extended)


def triangle_store(rows):
    """Uninitialised int32 rows of :data:`ROW` columns, the first at a 64-byte boundary: one cache line per triangle."""
    buf = np.empty((rows + 1) * ROW, dtype=np.int32)
    skip = (-(buf.ctypes.data // 4)) % ROW
    return buf[skip : skip + rows * ROW].reshape(rows, ROW)


triangle_store = compiled(triangle_store)


def store_views(T):
    """The columns of a triangle store as the arrays of :mod:`.cdt` and the engine: ``(V, N, S, mark, ver, alive)``."""
    return T[:, 0:3], T[:, 3:6], T[:, 6:9], T[:, MARK], T[:, VERSION], T[:, ALIVE]


store_views = compiled(store_views)


def grown_store(T, rows, used):
    """A triangle store of ``rows`` rows holding the first ``used`` rows of ``T``."""
    out = triangle_store(rows)
    out[:used] = T[:used]
    return out


grown_store = compiled(grown_store)
