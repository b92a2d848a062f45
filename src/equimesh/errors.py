"""Every error class of equimesh, in one place.

Two families, never mixed:

* :class:`EquimeshError` (a :class:`ValueError`): something is wrong with the
  caller's input.  The message is one line and names the vertex, edge, field,
  side or corner at fault in the caller's own terms.  The command line prints
  it and exits with code 2, writing nothing.
* :class:`InternalError` (a :class:`RuntimeError`): a guarantee the paper
  proves (edges in [l, 2l], valid triangles) failed on an output we were about
  to return.  It means a bug in equimesh, never a wrong input; the result is
  withheld rather than returned.  The command line prints one line asking for a
  report and exits with code 3.

Numbers in messages are written by :func:`number`, the one formatter.
"""


def number(x, digits=6):
    """A number for a message, with ``digits`` significant digits (``0.42``, ``1e-200``, ``13.37``); ``digits=None``
    gives the shortest text that reads back as the same float, so that two different values never print alike (a
    length compared with l, a suggested bound)."""
    return repr(float(x)) if digits is None else f"{float(x):.{digits}g}"


def coordinates(x):
    """``(1, 2, 3)``: a point in space (or any tuple of numbers)."""
    return f"({', '.join(number(c) for c in x)})"


def at(uv, point=None):
    """``(u, v) = (0.42, 0.5), point (x, y, z) = (1, 2, 3)``."""
    text = f"(u, v) = ({number(uv[0])}, {number(uv[1])})"
    if point is not None:
        text += f", point {coordinates(point)}"
    return text


class EquimeshError(ValueError):
    """Base class of every input error raised by equimesh."""


class InvalidLengthError(EquimeshError):
    """The target length l is not a positive finite number in the supported range."""


class InvalidPolygonError(EquimeshError):
    """The polygon violates an assumption of Problem 1 or Problem 2.

    ``points`` (optional, ``(k, 2)`` float array in the caller's coordinates)
    are the points at fault (the two boundary points that are too close, the
    vertex whose angle is wrong), so that a caller that built the polygon (the
    surface pipeline) can restate the problem in its own terms.
    """

    def __init__(self, message, *, points=None):
        super().__init__(message)
        self.points = None if points is None else [tuple(map(float, p)) for p in points]


class InvalidSurfaceError(EquimeshError):
    """A surface description (control net, JSON file) is malformed, or the surface is singular or folds."""


class SurfaceTooSmallError(InvalidSurfaceError):
    """A side of the surface is shorter than l on the plane."""


class MeshTooLargeError(EquimeshError):
    """The requested mesh would exceed the configured node limit."""


class InvalidToleranceError(EquimeshError):
    """A length-class tolerance is not a number, or outside (0, 50 %) of l."""


class OutputPathError(EquimeshError):
    """An output path cannot be written (missing or unwritable folder, unknown extension, name too long)."""


class InvalidMethodError(EquimeshError):
    """A mesher given to the benchmark cannot be imported or called, or does not return a triangle mesh."""


class InternalError(RuntimeError):
    """An output violated a proven guarantee (Theorem 1 or 3, a valid triangulation): a bug, not bad input."""


class MissingDependencyError(EquimeshError):
    """An optional dependency needed for the request (e.g. rhino3dm for .3dm files) is not installed."""


class SurfaceWarning(UserWarning):
    """The surface read is not exactly what the file describes (a trimmed face read untrimmed); the mesh is still
    made."""
