"""The JSON schema of a Bezier surface (:class:`equimesh.BezierSurface`, the paper's example in Section 4)::

    {"type": "bezier", "control_points": [[[x, y, z], ...], ...]}

Rows of ``control_points`` run over ``u``, the entries of a row over ``v``; an
(m+1) x (n+1) net gives a surface of degree (m, n).
"""

from ..surface.charts.bezier import BezierSurface, check_net_shape
from ._schema import control_net

#: The fields of the "bezier" type besides "type" and "description".
FIELDS = ("control_points",)


def bezier_from_dict(d):
    """The :class:`BezierSurface` of a checked JSON object; the first problem found is raised naming its field."""
    return BezierSurface(control_net(d["control_points"], check_net_shape))


def bezier_to_dict(surface):
    """The fields of ``surface`` (the inverse of :func:`bezier_from_dict`)."""
    return {"control_points": surface.control_points.tolist()}
