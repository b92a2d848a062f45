"""Checks shared by the JSON schemas of every surface type, and plain text for messages.

Every message names the field by its JSON path (``control_points[1][0][2]``)
and shows values as plain text, never as a numpy or Python ``repr``.
"""

import errno
import math
from numbers import Integral, Real

from ..errors import InvalidSurfaceError

#: How many characters of an offending value a message shows.
SHOWN_CHARS = 40

#: Longest path a message shows; longer ones are cut in the middle.
SHOWN_PATH_CHARS = 160


def json_type(x):
    """The JSON name of ``x``'s type ("object", "list", "string", "number", ...)."""
    names = {dict: "object", list: "list", str: "string", bool: "boolean", type(None): "null"}
    if type(x) in names:
        return names[type(x)]
    return "number" if isinstance(x, Real) else type(x).__name__


def shown(x):
    """``x`` as short plain text for a message (numbers as plain decimals, booleans as JSON writes them, long text
    cut)."""
    if isinstance(x, bool):
        return "true" if x else "false"
    if isinstance(x, Integral):
        return str(int(x)) if abs(int(x)) < 10**SHOWN_CHARS else f"an integer beyond 1e{SHOWN_CHARS}"
    if isinstance(x, Real):
        return repr(float(x))
    text = str(x)
    return text if len(text) <= SHOWN_CHARS else text[: SHOWN_CHARS - 3] + "..."


def described(x):
    """``x`` by its JSON type and value for a message: ``number 1.5``, ``boolean true``, ``string x``, ``null``."""
    return "null" if x is None else f"{json_type(x)} {shown(x)}"


def a_list(x, where, what, min_length):
    """``x`` if it is a list of at least ``min_length`` entries, else an :class:`InvalidSurfaceError`."""
    if not isinstance(x, list):
        raise InvalidSurfaceError(f"{where} must be a list of {what}, got {json_type(x)}")
    if len(x) < min_length:
        raise InvalidSurfaceError(f"{where} needs at least {min_length} {what}, got {len(x)}")
    return x


def finite_number(x, where):
    """``float(x)`` if ``x`` is a finite real number (not a boolean), else an :class:`InvalidSurfaceError`."""
    if isinstance(x, bool) or not isinstance(x, Real):
        raise InvalidSurfaceError(f"{where} must be a real number, got {described(x)}")
    try:
        value = float(x)
    except OverflowError:  # an integer beyond the float range
        value = math.inf
    if not math.isfinite(value):
        raise InvalidSurfaceError(f"{where} is not a finite number: {shown(x)}")
    return value


def number_rows(x, where, what, min_rows, min_length):
    """``x`` if it is a list of at least ``min_rows`` equally long lists of at least ``min_length`` entries."""
    rows = a_list(x, f'"{where}"', "rows", min_rows)
    for i, row in enumerate(rows):
        a_list(row, f"{where}[{i}]", what, min_length)
        if len(row) != len(rows[0]):
            raise InvalidSurfaceError(f"{where}[{i}] has {len(row)} {what}, but {where}[0] has {len(rows[0])}")
    return rows


def control_net(x, check_shape, where="control_points"):
    """``x`` if it is a control net: rows (over u) of equally many points (over v), each ``[x, y, z]`` finite.

    ``check_shape(rows, columns)``, the chart's bound on the size of its net, runs before any point is read, so that a
    net too large to evaluate is refused without reading it."""
    rows = number_rows(x, where, "points", 2, 2)
    check_shape(len(rows), len(rows[0]))
    for i, row in enumerate(rows):
        for j, point in enumerate(row):
            coordinates(point, f"{where}[{i}][{j}]", "xyz")
    return rows


def uv_polylines(x, where="holes"):
    """``x`` as a list of closed (u, v) polylines: lists of at least 3 ``[u, v]`` pairs of finite numbers."""
    holes = a_list(x, f'"{where}"', "polylines", 0)
    for k, hole in enumerate(holes):
        a_list(hole, f"{where}[{k}]", "[u, v] points", 3)
        for i, point in enumerate(hole):
            coordinates(point, f"{where}[{k}][{i}]", "uv")
    return holes


def coordinates(point, where, names):
    """``point`` if it is a list of ``len(names)`` finite numbers (e.g. ``[x, y, z]`` for ``names = "xyz"``)."""
    if not isinstance(point, list) or len(point) != len(names):
        raise InvalidSurfaceError(
            f"{where} must be a list [{', '.join(names)}] of {len(names)} numbers, got {described(point)}"
        )
    for k, c in enumerate(point):
        finite_number(c, f"{where}[{k}]")
    return point


def shown_path(path):
    """``path`` as text for a one-line message, cut in the middle beyond :data:`SHOWN_PATH_CHARS`."""
    text = str(path)
    if len(text) <= SHOWN_PATH_CHARS:
        return text
    half = SHOWN_PATH_CHARS // 2
    return f"{text[:half]}...{text[-half:]} ({len(text)} characters)"


def os_reason(exc):
    """Why the ``OSError`` ``exc`` happened, as plain text: "path too long", else the system's words for its error."""
    return "path too long" if exc.errno == errno.ENAMETOOLONG else exc.strerror or type(exc).__name__
