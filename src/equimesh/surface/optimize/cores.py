"""The threads the factorisations of the optimisation run on (docs/decisions.md, "One pattern for the normal matrix,
three factorisations", "PARDISO on two threads, the same bits as on one").

A factorisation whose rounding depends on its threads runs on one (:func:`one_blas_thread` keeps the BLAS bundled with
CHOLMOD's package to one); PARDISO's reproducible mode gives the same bits on any number up to
:data:`PARDISO_THREADS`, which it takes unless a solve runs beside the others (:data:`CORES`).
"""

import contextlib
import ctypes
import os
import threading
from pathlib import Path

#: PARDISO factorises on this many threads from :data:`~.solver.PARDISO_THREADS_FROM` variables on, in its mode of
#: conditional numerical reproducibility for that many (iparm 34): its results then have the same bits on one thread
#: as on two, and differ from those of its sequential mode (docs/decisions.md, "PARDISO on two threads, the same bits
#: as on one").
PARDISO_THREADS = 2


class Cores:
    """Who runs on the machine's cores: a solve beside the others (:meth:`beside`, on a thread of its own) and,
    while one runs, the others too factorise on one thread each; otherwise a factorisation in PARDISO's reproducible
    mode takes :data:`PARDISO_THREADS` of them.  Two solves at once on two threads each (four threads on two cores)
    took about one and a half times as long each as on one thread each (results/pardiso_threads.md); the bits do not
    depend on it (docs/decisions.md, "PARDISO on two threads, the same bits as on one")."""

    def __init__(self):
        self._lock, self._beside = threading.Lock(), 0

    @contextlib.contextmanager
    def beside(self):
        """Inside, this thread's solve is one beside the others."""
        with self._lock:
            self._beside += 1
        try:
            yield
        finally:
            with self._lock:
                self._beside -= 1

    def threads(self):
        """How many threads a factorisation may run on now."""
        return 1 if self._beside else min(PARDISO_THREADS, os.cpu_count() or 1)


CORES = Cores()


def one_blas_thread(module):
    """Keep the OpenBLAS bundled beside ``module``'s package (cvxopt's wheels carry one) to one thread.

    A supernodal factorisation calls the BLAS on dense blocks; with two
    threads the blocks' sums could be split, tying the last bits to the core
    count (docs/decisions.md, "One pattern for the normal matrix, three factorisations").
    Found by its file name beside the package (``cvxopt.libs``, ``cvxopt/.libs``, ``cvxopt/.dylibs``);
    a BLAS not bundled so is the platform's (Accelerate on macOS), left as it is.
    """
    package = Path(module.__file__).resolve().parent
    for folder in (package.parent / f"{package.name}.libs", package / ".libs", package / ".dylibs"):
        for path in sorted(folder.glob("*openblas*")) if folder.is_dir() else ():
            library = ctypes.CDLL(str(path))
            for name in ("openblas_set_num_threads", "scipy_openblas_set_num_threads64_"):
                if hasattr(library, name):
                    getattr(library, name)(1)
