"""Rhino files (``.3dm``) in: a NURBS surface, or the surface of a single-face Brep, read with rhino3dm.

rhino3dm is an optional dependency (``pip install 'equimesh[rhino]'``).  Every
object of the file's object table whose geometry is a surface (a NURBS
surface, or a plane, revolution, sum or extrusion surface, converted to NURBS
by rhino3dm) or a Brep of one face is a candidate.  With one candidate it is
taken; with several, ``object=`` picks one by its name or by its index in the
object table.  A trimmed face is meshed on its untrimmed surface, with a
:class:`~equimesh.errors.SurfaceWarning` that says so.

Rhino stores ``n + p - 1`` knots per direction (no superfluous end knots); the
first and the last knot are repeated once to give the ``n + p + 1`` of
:class:`~equimesh.NurbsSurface`, which has the same domain.  Control points
come as homogeneous ``(w x, w y, w z, w)``.
"""

import warnings

import numpy as np

from ..errors import InvalidSurfaceError, MissingDependencyError, SurfaceWarning
from ..surface.charts.nurbs import NurbsSurface
from ._schema import shown, shown_path


def read_rhino_surface(path, object=None):
    """The surface of the Rhino file ``path``; ``object`` (a name, or an index in the object table) picks one of
    several.

    Raises
    ------
    MissingDependencyError
        rhino3dm is not installed.
    InvalidSurfaceError
        one line: not a Rhino file, no surface in it, an unknown or ambiguous
        ``object`` (the message lists the surfaces by index and name), a Brep
        of several faces.
    """
    try:
        import rhino3dm
    except ImportError:
        raise MissingDependencyError(
            "reading Rhino files needs rhino3dm, which is not installed: pip install 'equimesh[rhino]' "
            f"({shown_path(path)})"
        ) from None
    model = rhino3dm.File3dm.Read(str(path))
    if model is None:
        raise InvalidSurfaceError(f"{shown_path(path)} is not a Rhino .3dm file rhino3dm can read")
    objects = list(model.Objects)
    candidates = {k: o for k, o in enumerate(objects) if _is_surface(o.Geometry, rhino3dm)}
    if not candidates:
        kinds = sorted({type(o.Geometry).__name__ for o in objects}) or ["nothing"]
        raise InvalidSurfaceError(
            f"{shown_path(path)} holds no surface and no single-face Brep ({len(objects)} objects: {', '.join(kinds)})"
        )
    index = _pick(candidates, object, path)
    name = _label(index, candidates[index])
    return _to_nurbs(candidates[index].Geometry, name, path, rhino3dm)


def _is_surface(geometry, rhino3dm):
    return isinstance(geometry, (rhino3dm.Surface, rhino3dm.Brep))


def _label(index, obj):
    name = obj.Attributes.Name
    return f"{index} {shown(name)!r}" if name else f"{index} (unnamed)"


def _pick(candidates, wanted, path):
    listing = ", ".join(_label(k, o) for k, o in candidates.items())
    if wanted is None:
        if len(candidates) == 1:
            return next(iter(candidates))
        raise InvalidSurfaceError(
            f"{shown_path(path)} holds {len(candidates)} surfaces ({listing}); choose one by name or index"
        )
    named = [k for k, o in candidates.items() if isinstance(wanted, str) and o.Attributes.Name == wanted]
    if len(named) == 1:
        return named[0]
    if len(named) > 1:
        raise InvalidSurfaceError(
            f"{shown_path(path)} holds {len(named)} surfaces named {shown(wanted)!r} ({listing}); choose one by index"
        )
    index = _as_index(wanted)
    if index is None or index not in candidates:
        choice = repr(shown(wanted)) if isinstance(wanted, str) else shown(wanted)
        raise InvalidSurfaceError(f"{shown_path(path)} has no surface {choice}; its surfaces are {listing}")
    return index


def _as_index(wanted):
    if isinstance(wanted, bool):
        return None
    if isinstance(wanted, (int, np.integer)):
        return int(wanted)
    if isinstance(wanted, str) and wanted.strip().isdigit():
        return int(wanted.strip())
    return None


def _to_nurbs(geometry, name, path, rhino3dm):
    if isinstance(geometry, rhino3dm.Brep):
        faces = len(geometry.Faces)
        if faces != 1:
            raise InvalidSurfaceError(
                f"object {name} of {shown_path(path)} is a Brep of {faces} faces; only single-face Breps (or surfaces) "
                "can be meshed: explode it in Rhino and pick one face"
            )
        if not geometry.IsSurface:
            warnings.warn(
                f"object {name} of {shown_path(path)} is a trimmed face: it is meshed on its untrimmed surface, "
                "not on the trimmed outline",
                SurfaceWarning,
                stacklevel=4,
            )
        geometry = geometry.Faces[0].UnderlyingSurface()
    nurbs = geometry.ToNurbsSurface()
    if nurbs is None:
        raise InvalidSurfaceError(f"object {name} of {shown_path(path)}: rhino3dm cannot convert its surface to NURBS")
    n_u, n_v = nurbs.Points.CountU, nurbs.Points.CountV
    net = np.array([[_xyzw(nurbs.Points[i, j]) for j in range(n_v)] for i in range(n_u)])
    weights = net[..., 3]
    if not np.all(weights > 0):
        i, j = (int(k) for k in np.argwhere(~(weights > 0))[0])
        raise InvalidSurfaceError(
            f"object {name} of {shown_path(path)}: control point [{i}][{j}] has weight {float(weights[i, j])!r}, not "
            "positive"
        )
    knots = [_full_knots(nurbs.KnotsU.ToList()), _full_knots(nurbs.KnotsV.ToList())]
    return NurbsSurface((nurbs.Degree(0), nurbs.Degree(1)), *knots, net[..., :3] / weights[..., None], weights)


def _xyzw(p):
    return (p.X, p.Y, p.Z, p.W)


def _full_knots(rhino_knots):
    """Rhino's ``n + p - 1`` knots with the first and last repeated once more (``n + p + 1``)."""
    k = list(rhino_knots)
    return [k[0], *k, k[-1]]


def to_rhino_surface(surface):
    """The ``rhino3dm.NurbsSurface`` of a :class:`~equimesh.NurbsSurface` (the inverse of reading one).

    For writing example and test files; needs rhino3dm.
    """
    import rhino3dm

    (p, q), (n_u, n_v) = surface.degree, surface.weights.shape
    out = rhino3dm.NurbsSurface.Create(3, True, p + 1, q + 1, n_u, n_v)
    for knots, target in ((surface.knots_u, out.KnotsU), (surface.knots_v, out.KnotsV)):
        for k, t in enumerate(knots[1:-1]):
            target[k] = float(t)
    for i in range(n_u):
        for j in range(n_v):
            w = float(surface.weights[i, j])
            out.Points[i, j] = rhino3dm.Point4d(*(w * float(c) for c in surface.control_points[i, j]), w)
    return out
