"""The one error family of equimesh.

Every problem with the caller's input is raised as a subclass of
:class:`EquimeshError`, itself a :class:`ValueError`, with a one-line message
that names the vertex, edge or field at fault.  The command line turns these
into a one-line message and exit code 2.
"""


class EquimeshError(ValueError):
    """Base class of every input error raised by equimesh."""


class InvalidLengthError(EquimeshError):
    """The target length l is not a positive finite number."""


class InvalidPolygonError(EquimeshError):
    """The polygon violates an assumption of Problem 1 or Problem 2."""


class InvalidSurfaceError(EquimeshError):
    """A surface description (control net, JSON file) is malformed."""


class MeshTooLargeError(EquimeshError):
    """The requested mesh would exceed the configured node limit."""
