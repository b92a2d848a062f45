"""The JSON schema of a NURBS surface (:class:`equimesh.NurbsSurface`)::

    {"type": "nurbs", "degree": [p, q], "knots_u": [...], "knots_v": [...],
     "control_points": [[[x, y, z], ...], ...], "weights": [[w, ...], ...]}

Rows of ``control_points`` and ``weights`` run over ``u``, the entries of a row
over ``v``; ``knots_u`` holds ``n_u + p + 1`` knots for ``n_u`` rows, ``knots_v``
``n_v + q + 1`` for ``n_v`` columns.  The parameter domain is
``[knots_u[p], knots_u[n_u]] x [knots_v[q], knots_v[n_v]]``.
"""

from numbers import Integral

from ..errors import InvalidSurfaceError
from ..surface.charts.nurbs import NurbsSurface, check_net_shape
from ._schema import a_list, control_net, described, finite_number, number_rows

#: The fields of the "nurbs" type besides "type" and "description".
FIELDS = ("degree", "knots_u", "knots_v", "control_points", "weights")


def nurbs_from_dict(d):
    """The :class:`NurbsSurface` of a checked JSON object; the first problem found is raised naming its field."""
    degree = a_list(d["degree"], '"degree"', "integers [p, q]", 2)
    if len(degree) != 2:
        raise InvalidSurfaceError(f'"degree" must be a list of 2 integers [p, q], got {len(degree)} entries')
    for k, value in enumerate(degree):
        if isinstance(value, bool) or not isinstance(value, Integral):
            raise InvalidSurfaceError(f"degree[{k}] must be an integer, got {described(value)}")
    net = control_net(d["control_points"], check_net_shape)  # first: its size bounds what the rest may cost
    knots = [_numbers(d[name], name) for name in ("knots_u", "knots_v")]
    weights = number_rows(d["weights"], "weights", "weights", 1, 1)
    for i, row in enumerate(weights):
        for j, w in enumerate(row):
            finite_number(w, f"weights[{i}][{j}]")
    return NurbsSurface(degree, *knots, net, weights)


def nurbs_to_dict(surface):
    """The fields of ``surface`` (the inverse of :func:`nurbs_from_dict`)."""
    return {
        "degree": list(surface.degree),
        "knots_u": surface.knots_u.tolist(),
        "knots_v": surface.knots_v.tolist(),
        "control_points": surface.control_points.tolist(),
        "weights": surface.weights.tolist(),
    }


def _numbers(x, name):
    values = a_list(x, f'"{name}"', "numbers", 1)
    return [finite_number(v, f"{name}[{k}]") for k, v in enumerate(values)]
