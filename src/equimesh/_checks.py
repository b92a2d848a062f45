"""Argument checks shared by every verb: real numbers, counts, the target length l, arrays of reals.

Each check returns the value in the form the code uses (a float, an int, a
float array) or raises an :class:`~equimesh.errors.EquimeshError` subclass
whose one-line message names the argument and shows the value as the caller
gave it (a numpy scalar as the number it holds).
"""

import numbers

import numpy as np

from .errors import EquimeshError, InvalidLengthError
from .tolerance import MAX_LENGTH, MIN_LENGTH


def real_number(value, name, error):
    """``value`` as a float, raising ``error`` unless it is one real number (not complex, bool or text)."""
    if isinstance(value, (bool, np.bool_, str, bytes)) or not (
        isinstance(value, numbers.Real) or (np.ndim(value) == 0 and np.asarray(value).dtype.kind in "iuf")
    ):
        boolean = isinstance(value, (bool, np.bool_))
        kind = (
            "boolean "
            if boolean
            else "complex value "
            if isinstance(value, numbers.Complex) or np.iscomplexobj(value)
            else ""
        )
        raise error(f"{name} must be a real number, got {kind}{_plain(value)!r}")
    return float(value)


def check_count(value, name, least=1):
    """``value`` as an int, refusing anything but an integer of at least ``least`` (bool, 2.5, nan included).

    Beyond the paper: the one check of every count a caller gives (grid
    sizes, search counts, ``max_nodes``); numpy integers are accepted.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < least:
        raise EquimeshError(f"{name} must be an integer of at least {least}, got {_plain(value)!r}")
    return int(value)


def _plain(value):
    """``value`` with a numpy scalar as the Python number it holds, so that a message shows ``2.5``, not its numpy
    repr."""
    return value.item() if isinstance(value, np.generic) else value


def check_length(l):
    """Return ``l`` as a float, raising :class:`InvalidLengthError` unless it is in the supported range.

    The range ``[MIN_LENGTH, MAX_LENGTH]`` (:mod:`equimesh.tolerance`) keeps
    ``l^2`` a normal float; every computation then runs in a frame where l is
    in ``[1, 2)``.
    """
    value = real_number(l, "target length l", InvalidLengthError)
    if not np.isfinite(value) or value <= 0.0:
        raise InvalidLengthError(f"target length l must be positive and finite, got {value!r}")
    if not MIN_LENGTH <= value <= MAX_LENGTH:
        raise InvalidLengthError(
            f"target length l = {value!r} is outside the supported range [{MIN_LENGTH:g}, {MAX_LENGTH:g}]; "
            "rescale the coordinates"
        )
    return value


def real_array(value, what, error):
    """``value`` as a float array, raising ``error`` ("``what`` must be ...") unless every entry is a real number."""
    try:
        raw = np.asarray(value)
    except (TypeError, ValueError):
        raise error(f"{what} must be an array of numbers") from None
    if raw.dtype.kind == "c" or (raw.dtype.kind == "O" and any(isinstance(x, complex) for x in raw.ravel())):
        raise error(f"{what} must be real numbers, got complex values")
    try:
        if raw.dtype.kind not in "iufO":
            raise ValueError
        return np.array(raw, dtype=float)
    except (TypeError, ValueError):
        raise error(f"{what} must be an array of numbers") from None
