"""A snippet of Python run in a fresh process with one BLAS thread and with two: the determinism tests' runner."""

import os
import subprocess
import sys

from equimesh.surface.optimize.solver import FACTORISATION_VARIABLE


def outputs_with_one_and_two_threads(code, factorisation):
    """The standard output of ``python -c code`` with ``OPENBLAS_NUM_THREADS`` (and ``OMP_NUM_THREADS``) 1, then 2,
    the optimisation's factorisation chosen by its environment variable."""
    return [
        subprocess.run(
            [sys.executable, "-c", code],
            env={
                **os.environ,
                "OPENBLAS_NUM_THREADS": threads,
                "OMP_NUM_THREADS": threads,
                FACTORISATION_VARIABLE: factorisation,
            },
            capture_output=True,
            text=True,
            check=True,
        ).stdout
        for threads in ("1", "2")
    ]
