"""The fast engine's arrays: grown by doubling, and the triangle store.

The farthest point jumps across the region, so at a million points every
insertion reaches its triangles in memory that no cache holds.  Each
triangle is one 64-byte row of int32 (:func:`triangle_store`): its vertices,
neighbours and constraint segments (``V``, ``N``, ``S`` of :mod:`.cdt`, as
column views, :func:`store_views`), its cavity mark, version and whether it
is alive, read by one cache line where separate int64 arrays took four.
Rows not yet used are not initialised: memory never touched costs nothing.
The engine asks for the rows of its next candidate ahead of time
(:func:`prefetch`), so that they arrive while the current point is inserted.
"""

import numpy as np
from llvmlite import ir
from numba import config, types
from numba.core import cgutils
from numba.extending import intrinsic

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


def prefetch(array, row):
    """Ask the processor to bring row ``row`` of ``array`` into its caches (LLVM's ``llvm.prefetch``, for a read, into
    every level): it changes no value, only when the memory arrives.  Run as Python, it does nothing."""


def _prefetch(typingctx, array, row):
    """:func:`prefetch` compiled: the address of ``array[row, 0, ..]`` handed to ``llvm.prefetch``."""

    def codegen(context, builder, signature, args):
        kind = signature.args[0]
        view = context.make_array(kind)(context, builder, args[0])
        index = [args[1]] + [context.get_constant(types.intp, 0)] * (kind.ndim - 1)
        shape, strides = cgutils.unpack_tuple(builder, view.shape), cgutils.unpack_tuple(builder, view.strides)
        address = cgutils.get_item_pointer2(context, builder, view.data, shape, strides, kind.layout, index)
        byte = builder.bitcast(address, ir.IntType(8).as_pointer())
        word = ir.IntType(32)
        hint = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(ir.VoidType(), [byte.type, word, word, word]), "llvm.prefetch.p0"
        )
        builder.call(hint, [byte, ir.Constant(word, 0), ir.Constant(word, 3), ir.Constant(word, 1)])
        return context.get_dummy_value()

    return types.void(array, types.intp), codegen


if not config.DISABLE_JIT:
    prefetch = intrinsic(_prefetch)
