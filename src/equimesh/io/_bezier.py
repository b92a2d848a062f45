"""The JSON schema of a Bezier surface (:class:`equimesh.BezierSurface`, the paper's example in Section 4)::

    {"type": "bezier", "control_points": [[[x, y, z], ...], ...]}

Rows of ``control_points`` run over ``u``, the entries of a row over ``v``; an
(m+1) x (n+1) net gives a surface of degree (m, n).
"""

from ..errors import InvalidSurfaceError
from ..surface.bezier import BezierSurface
from ._schema import a_list, finite_number, json_type, shown

#: The fields of the "bezier" type besides "type" and "description".
FIELDS = ("control_points",)


def bezier_from_dict(d):
    """The :class:`BezierSurface` of a checked JSON object; the first problem found is raised naming its field."""
    rows = a_list(d["control_points"], '"control_points"', "rows", 2)
    width = None
    for i, row in enumerate(rows):
        row = a_list(row, f"control_points[{i}]", "points", 2)
        if width is None:
            width = len(row)
        elif len(row) != width:
            raise InvalidSurfaceError(f"control_points[{i}] has {len(row)} points, but control_points[0] has {width}")
        for j, point in enumerate(row):
            where = f"control_points[{i}][{j}]"
            if not isinstance(point, list) or len(point) != 3:
                raise InvalidSurfaceError(
                    f"{where} must be a list [x, y, z] of 3 numbers, got {json_type(point)} {shown(point)}"
                )
            for k, x in enumerate(point):
                finite_number(x, f"{where}[{k}]")
    return BezierSurface(rows)


def bezier_to_dict(surface):
    """The fields of ``surface`` (the inverse of :func:`bezier_from_dict`)."""
    return {"control_points": surface.control_points.tolist()}
