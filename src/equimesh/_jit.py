"""How equimesh's compiled kernels are compiled (numba), in one place.

The kernels of the fast engine (:mod:`equimesh.planar.insertion.predicates`,
``._cdt`` and ``.fast``) and the solver's sum of the normal matrix
(:func:`equimesh.surface.optimize.solver._sum_products`) are plain functions, each compiled right after its definition
by
``name = compiled(name)``: the same as the decorator ``@njit(cache=True)``,
but mutation testing reaches them (mutmut leaves decorated functions alone),
and under ``NUMBA_DISABLE_JIT=1`` they run as the Python they are written in
(``tools/mutation``).  So a kernel must mean the same as
Python and compiled: a count of booleans is a sum of ``int(...)``, as NumPy's
booleans add as a logical or.
"""

from numba import njit


def compiled(function, nrt=None):
    """``function`` compiled in nopython mode and cached on disk.

    ``nrt`` True or False asks for numba's reference-counting runtime
    explicitly, with or without it; None (the default) lets numba decide
    (:mod:`.fast`, "Compilation").
    """
    return njit(cache=True)(function) if nrt is None else njit(cache=True, _nrt=nrt)(function)
