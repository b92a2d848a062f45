"""Argument checks shared by every verb: real numbers, counts, the target length l, arrays of reals, of points and of
indices, numbers as text.

Each check returns the value in the form the code uses (a float, an int, a
float array) or raises an :class:`~equimesh.errors.EquimeshError` subclass
whose one-line message names the argument and shows the value as the caller
gave it (a numpy scalar as the number it holds).  A Python integer beyond the
float range (``10**400``) is refused like any other value that is no float,
never with Python's ``OverflowError``.
"""

import math
import numbers
import re

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
    try:
        return float(value)
    except OverflowError:  # an integer (or fraction) beyond the float range
        raise error(f"{name} must be a real number within the float range, got {_beyond_floats(value)}") from None


def _beyond_floats(value):
    """``value``, a number float() cannot hold, as text for a message: its digit count, not its 400 digits."""
    return plain_integer(value) if isinstance(value, numbers.Integral) else "a number beyond it"


def plain_integer(value):
    """The integer ``value`` as its digits, or beyond 20 digits as ``an integer of 401 digits``: a message never
    shows a 400-digit number."""
    n = abs(int(value))
    if n < 10**20:
        return str(int(value))
    digits = math.floor(n.bit_length() * math.log10(2)) + 1  # exact, or one too many
    return f"an integer of {digits - (n < 10 ** (digits - 1))} digits"


def check_count(value, name, least=1):
    """``value`` as an int, refusing anything but an integer of at least ``least`` (bool, 2.5, nan included).

    Beyond the paper: the one check of every count a caller gives (grid
    sizes, search counts, ``max_nodes``); numpy integers are accepted.
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise EquimeshError(f"{name} must be an integer of at least {least}, got {_plain(value)!r}")
    if value < least:
        raise EquimeshError(f"{name} must be an integer of at least {least}, got {plain_integer(value)}")
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
    except OverflowError:  # a Python integer beyond the float range among the entries
        flat = raw.ravel()
        k = next(k for k, x in enumerate(flat) if _overflows(x))
        index = "".join(f"[{int(i)}]" for i in np.unravel_index(k, raw.shape))
        raise error(
            f"{what} must be real numbers within the float range, but {f'entry {index}' if index else 'it'} is "
            f"{_beyond_floats(flat[k])}"
        ) from None


def finite_rows(value, width, what, row, error, per=None):
    """``value`` as an (N, ``width``) float array of finite numbers, raising ``error`` otherwise: ``what`` names the
    array (its shape is wrong), ``row`` is a format string naming row k (it is not finite); ``per``, ``(count,
    items)``, asks one row per item (``count`` of them)."""
    points = real_array(value, what, error)
    if points.ndim != 2 or points.shape[1] != width:
        raise error(f"{what} must be an (N, {width}) array, got shape {points.shape}")
    if per is not None and len(points) != per[0]:
        raise error(f"{what} must have one row per {per[1]} ({per[0]}), got {len(points)}")
    bad = np.flatnonzero(~np.all(np.isfinite(points), axis=1))
    if bad.size:
        raise error(f"{row.format(int(bad[0]))} is not finite: {points[bad[0]].tolist()}")
    return points


def index_rows(value, width, count, what, row, target, error):
    """``value`` as a (K, ``width``) int64 array of indices of ``count`` ``target`` items (empty: (0, width)),
    raising ``error`` otherwise: ``what`` names the array (not integers of that shape), ``row`` is a format string
    naming row k (an index outside 0 .. count - 1, compared in the caller's dtype: no uint64 wraps to -1)."""
    raw = np.asarray(value)
    if raw.size == 0:
        return np.zeros((0, width), dtype=np.int64)
    if raw.ndim != 2 or raw.shape[1] != width or not np.issubdtype(raw.dtype, np.integer):
        raise error(f"{what} must be an (M, {width}) array of {target} indices, got shape {raw.shape} of {raw.dtype}")
    bad = np.flatnonzero(np.any((raw < 0) | (raw >= count), axis=1))
    if bad.size:
        raise error(f"{row.format(int(bad[0]))} refers to a {target} outside 0 .. {count - 1}: {raw[bad[0]].tolist()}")
    return raw.astype(np.int64)


def _overflows(x):
    """True if ``float(x)`` overflows (other failures are not this entry's overflow)."""
    try:
        float(x)
    except OverflowError:
        return True
    except (TypeError, ValueError):
        pass
    return False


#: Numbers as a person types them: ASCII decimal digits with an optional point and exponent (``0.5``, ``.5``,
#: ``1e-3``), or ``inf`` and ``nan``; Python's other spellings (``1_0``, other scripts' digits) are refused, as they
#: are typos more often than intended.
NUMBER_TEXT = re.compile(r"[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf|infinity|nan)", re.IGNORECASE | re.ASCII)

#: Whole numbers as a person types them: decimal digits with an optional sign.
WHOLE_TEXT = re.compile(r"[+-]?\d+", re.ASCII)


def number_text(text, what, error, *, whole=False):
    """The number written in ``text`` (an int if ``whole``, else a float), or ``error`` ("``what`` must be ...")
    unless it is written as :data:`NUMBER_TEXT` (:data:`WHOLE_TEXT`) allows: ``1_0`` is refused, not read as 10."""
    plain = isinstance(text, str) and (WHOLE_TEXT if whole else NUMBER_TEXT).fullmatch(text.strip())
    try:
        if plain:
            return int(text) if whole else float(text)
    except ValueError:  # more digits than int() reads (sys.get_int_max_str_digits)
        pass
    got = repr(text) if len(str(text)) <= 40 else f"a text of {len(str(text))} characters"
    raise error(f"{what} must be {'a whole number' if whole else 'a number'}, got {got}")
