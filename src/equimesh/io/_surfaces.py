"""Surface descriptions in: a table of surface types (the JSON ``"type"``) and a table of input formats.

A surface file is read by the format of its extension (:data:`INPUT_FORMATS`);
a JSON description names its surface type in ``"type"``
(:data:`SURFACE_TYPES`), whose schema turns the object into a surface (step 1
of Section 4: the map X^s(u, v)).  Every type may have openings,
``"holes": [[[u, v], ...], ...]`` (closed polylines in parameter space, see
:class:`~equimesh.surface.charts.openings.Perforated`), and a ``"description"``.  A new type or format is one new row in
a
table, nothing else.  Every problem, from an unreadable path to a coordinate
that is not a finite number, is one :class:`InvalidSurfaceError` line.
"""

import json
import os
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from ..errors import InvalidSurfaceError
from ..surface.charts.bezier import BezierSurface
from ..surface.charts.nurbs import NurbsSurface
from ..surface.charts.openings import Perforated
from . import _bezier, _nurbs
from ._rhino import read_rhino_surface
from ._schema import json_type, os_reason, shown, shown_path, uv_polylines
from ._trimesh import TRIANGLE_MESH_FORMATS, read_triangle_mesh


@dataclass(frozen=True)
class SurfaceType:
    """One surface type: its class, its fields and its JSON schema in both directions."""

    cls: type
    fields: tuple  # required, besides "type"; OPTIONAL_FIELDS are allowed everywhere
    from_dict: Callable  # the JSON object (fields present) -> a surface
    to_dict: Callable  # a surface -> its fields


@dataclass(frozen=True)
class InputFormat:
    """One input file format: its name, the function reading a path to a surface, the keywords it accepts."""

    name: str
    read: Callable  # read(path, **options) -> a surface
    options: tuple = ()  # keyword options of ``read``, e.g. ("object",)


#: Fields every surface type may have: a text, and openings in (u, v).
OPTIONAL_FIELDS = ("description", "holes")

#: Surface types by their JSON ``"type"``.
SURFACE_TYPES = {
    "bezier": SurfaceType(BezierSurface, _bezier.FIELDS, _bezier.bezier_from_dict, _bezier.bezier_to_dict),
    "nurbs": SurfaceType(NurbsSurface, _nurbs.FIELDS, _nurbs.nurbs_from_dict, _nurbs.nurbs_to_dict),
}


def surface_from_dict(d):
    """The surface described by the JSON object ``d`` (``{"type": ..., ...}``, see :data:`SURFACE_TYPES`).

    Raises
    ------
    InvalidSurfaceError
        naming the first field at fault: not an object, missing or unknown
        ``"type"``, a missing or unknown field, a malformed value.
    """
    if not isinstance(d, dict):
        raise InvalidSurfaceError(f"surface must be a JSON object, got {json_type(d)}")
    known = ", ".join(f'"{name}"' for name in SURFACE_TYPES)
    if "type" not in d:
        raise InvalidSurfaceError(f'surface is missing the field "type" (one of {known})')
    kind = SURFACE_TYPES.get(d["type"]) if isinstance(d["type"], str) else None
    if kind is None:
        got = repr(shown(d["type"])) if isinstance(d["type"], str) else json_type(d["type"])
        raise InvalidSurfaceError(f'surface "type" must be one of {known}, got {got}')
    extra = sorted(set(d) - {"type", *OPTIONAL_FIELDS, *kind.fields})
    if extra:
        raise InvalidSurfaceError(f"surface has unknown field {shown(extra[0])!r}")
    if not isinstance(d.get("description", ""), str):
        raise InvalidSurfaceError(f'surface "description" must be a string, got {json_type(d["description"])}')
    missing = [name for name in kind.fields if name not in d]
    if missing:
        raise InvalidSurfaceError(f'surface is missing the field "{missing[0]}"')
    if "holes" not in d:
        return kind.from_dict(d)
    holes = uv_polylines(d["holes"])
    return Perforated(kind.from_dict(d), holes)


def surface_to_dict(surface):
    """The JSON object describing ``surface`` (the inverse of :func:`surface_from_dict`)."""
    holes = {"holes": [hole.tolist() for hole in surface.holes]} if isinstance(surface, Perforated) else {}
    chart = surface.chart if holes else surface
    for name, kind in SURFACE_TYPES.items():
        if type(chart) is kind.cls:
            return {"type": name, **kind.to_dict(chart), **holes}
    raise TypeError(f"no JSON surface type for {type(surface).__name__}")


def load_surface(path, *, object=None):
    """Read the surface in file ``path``; its format is chosen by extension (:data:`INPUT_FORMATS`).

    Parameters
    ----------
    path : path-like
    object : str or int, optional
        For files holding several surfaces (Rhino ``.3dm``): the name, or
        the index in the file's object table, of the one to read.

    Raises
    ------
    InvalidSurfaceError
        one line naming the problem: ``path`` not a path (a str or
        path-like), unknown extension (listing the known ones), a path that
        is missing, too long, not a regular file or not readable, a
        malformed description, ``object`` given for a format
        holding one surface, or not naming a surface of the file.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise InvalidSurfaceError(f"the surface file must be given as a path, got {type(path).__name__}")
    path = Path(path)
    fmt = INPUT_FORMATS.get(path.suffix.lower())
    if fmt is None:
        raise InvalidSurfaceError(
            f"unknown surface file extension {path.suffix!r} for {shown_path(path)}; use one of {sorted(INPUT_FORMATS)}"
        )
    options = {} if object is None else {"object": object}
    if options and "object" not in fmt.options:
        with_objects = sorted(ext for ext, f in INPUT_FORMATS.items() if "object" in f.options)
        raise InvalidSurfaceError(
            f"choosing an object applies to files with several surfaces ({', '.join(with_objects)}), "
            f"not to {fmt.name} {shown_path(path)}"
        )
    try:
        if not path.is_file():
            raise InvalidSurfaceError(
                f"surface file {'is not a regular file' if path.exists() else 'not found'}: {shown_path(path)}"
            )
        return fmt.read(path, **options)
    except OSError as exc:
        raise InvalidSurfaceError(f"cannot read surface file {shown_path(path)}: {os_reason(exc)}") from None


#: The largest JSON file read: three times a net of ``MAX_NET_POINTS`` written with every digit, one number a line
#: (10.3 MB for 316 x 316 points, ``python experiments/chart_timing.py``).  A larger file is refused on its size,
#: before a parse of seconds that would end in the refusal of its net (docs/decisions.md, "Charts bounded by what
#: evaluation costs").
MAX_JSON_BYTES = 32_000_000


def read_json_surface(path):
    """Read a JSON surface description (UTF-8, a byte-order mark allowed) and build it with
    :func:`surface_from_dict`."""
    where = shown_path(path)
    size = Path(path).stat().st_size
    if size > MAX_JSON_BYTES:
        raise InvalidSurfaceError(
            f"{where} has {size} bytes, more than the {MAX_JSON_BYTES} of the largest surface description read "
            "(a control net of the most points allowed takes a third of that)"
        )
    data = Path(path).read_bytes()
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InvalidSurfaceError(f"{where} is not UTF-8 text (byte {exc.start} cannot be decoded)") from None
    try:
        d = json.loads(text, object_pairs_hook=_unique_keys)
    except json.JSONDecodeError as exc:
        raise InvalidSurfaceError(
            f"{where}: malformed JSON at line {exc.lineno} column {exc.colno}: {exc.msg}"
        ) from None
    except InvalidSurfaceError:  # from _unique_keys
        raise
    except RecursionError:
        raise InvalidSurfaceError(f"{where}: JSON nested too deeply to read (a surface needs a few levels)") from None
    except ValueError:  # only an integer too long for int(), Python >= 3.11
        raise InvalidSurfaceError(
            f"{where}: an integer has more than {sys.get_int_max_str_digits()} digits; "
            "write coordinates as ordinary numbers"
        ) from None
    return surface_from_dict(d)


#: Input formats by file extension (lower case).
INPUT_FORMATS = {
    ".json": InputFormat("equimesh surface JSON", read_json_surface),
    ".3dm": InputFormat("Rhino file", read_rhino_surface, ("object",)),
    **{
        ext: InputFormat(f"{name} triangle mesh", read_triangle_mesh)
        for ext, (name, _) in TRIANGLE_MESH_FORMATS.items()
    },
}


def _unique_keys(pairs):
    seen = set()
    for key, _ in pairs:
        if key in seen:
            raise InvalidSurfaceError(f"surface JSON has the field {shown(key)!r} twice")
        seen.add(key)
    return dict(pairs)
