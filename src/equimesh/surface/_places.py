"""Places on a surface patch named in the caller's terms, for error messages.

A refused surface is described by what the user gave: the chart's parameter
rectangle (its sides ``u = 0`` ... and corners ``(u, v) = (1, 0)`` ..., with
the chart's own bounds) and the points in space, never by the internal outline
polygon of step 3.
"""


def number(x):
    """A float as plain text with enough digits: ``0.42``, ``1e-200``, ``13.37``."""
    return f"{float(x):.6g}"


def coordinates(x):
    """``(1, 2, 3)``: a point in space (or any tuple of numbers)."""
    return f"({', '.join(number(c) for c in x)})"


def at(uv, point=None):
    """``(u, v) = (0.42, 0.5), point (x, y, z) = (1, 2, 3)``."""
    text = f"(u, v) = ({number(uv[0])}, {number(uv[1])})"
    if point is not None:
        text += f", point {coordinates(point)}"
    return text


def side_name(side, domain):
    """``side v = 0`` for an index into :data:`~equimesh.surface.chart.SIDES` of ``domain``."""
    return f"side {'uv'[side // 2]} = {number(domain.side_values[side])}"


def corner_name(uv):
    """``corner (u, v) = (1, 0)`` for a corner of the parameter rectangle."""
    return f"corner (u, v) = ({number(uv[0])}, {number(uv[1])})"
