"""Wavefront OBJ meshes in: the positions and the faces, and nothing else a modeller writes beside them.

What is read:

* ``v x y z``, with anything after the three coordinates ignored: ``v x y z w`` (a weight, meaningless on a
  polygon), ``v x y z r g b`` (a colour);
* ``f`` with corners ``v``, ``v/vt``, ``v//vn`` or ``v/vt/vn``: only ``v`` counts, so texture coordinates and normals
  may come in any number (Blender writes one normal for a flat roof).  An index counts from 1 in the order the
  vertices are written; a negative one counts back from the last vertex written before the face (``-1`` is that
  vertex).  A face has 3 or 4 corners (a quadrilateral is split by the caller);
* any other statement is skipped: ``vt``, ``vn``, ``vp``, lines (``l``) and points (``p``), ``g``, ``o``, ``s``,
  ``usemtl``, ``mtllib``, comments, free-form geometry, statements of no standard.  Lines may end in CRLF, words be
  separated by tabs and runs of spaces, and a line ending in ``\\`` continues on the next.

What is refused, in one :class:`~equimesh.errors.InvalidSurfaceError` line naming the line of the file and the
vertex or face by the file's own numbers (both counted from 1): a vertex with fewer than three coordinates or a
coordinate that is no number (:data:`~equimesh._checks.NUMBER_TEXT`: ``1_0`` is refused) or not finite; a face of
fewer than 3 or more than 4 corners, a corner that is no index, an index 0, or an index to a vertex the file does not
have.
"""

import re

import numpy as np

from .._checks import NUMBER_TEXT, WHOLE_TEXT
from ..errors import InvalidSurfaceError, coordinates
from ._schema import shown

#: Face sizes read, by the name of their cells.
FACE_KINDS = {3: "triangle", 4: "quad"}


def read_obj(path, where):
    """The positions (N, 3) and the faces of the OBJ file ``path`` (``where``: the path as messages show it).

    Returns
    -------
    points : (N, 3) float array
    blocks : list of (kind, cells)
        Runs of faces of one kind (``"triangle"``, ``"quad"``) in the file's order; ``cells`` hold 0-based vertex
        indices, every one in range.
    """
    points, point_lines, faces, face_lines = [], [], [], []
    for line, words in _statements(path):
        if words[0] == "v":
            points.append(_vertex(words, line, len(points) + 1, where))
            point_lines.append(line)
        elif words[0] == "f":
            faces.append(_corners(words, line, len(faces) + 1, len(points), where))
            face_lines.append(line)
    points = np.array(points, dtype=float).reshape(-1, 3)
    bad = np.flatnonzero(~np.all(np.isfinite(points), axis=1))
    if bad.size:
        k = int(bad[0])
        raise InvalidSurfaceError(
            f"{where}, line {point_lines[k]}: vertex {k + 1} is not finite: {coordinates(points[k])}"
        )
    outside = [k for k, corners in enumerate(faces) if max(corners) > len(points)]
    if outside:
        k = outside[0]
        raise InvalidSurfaceError(
            f"{where}, line {face_lines[k]}: face {k + 1} refers to vertex {max(faces[k])}, but the file has "
            f"{len(points)} vertices"
        )
    blocks = []
    for corners in faces:
        kind = FACE_KINDS[len(corners)]
        if not blocks or blocks[-1][0] != kind:
            blocks.append((kind, []))
        blocks[-1][1].append(corners)
    return points, [(kind, np.array(cells, dtype=np.int64) - 1) for kind, cells in blocks]


def _statements(path):
    """``(line number, words)`` of every statement of the file: comments (``#`` to the end of the line) dropped,
    continued lines joined, blank lines skipped."""
    text = path.read_bytes().decode("utf-8", errors="replace")  # names and comments may be in any encoding
    pending = []
    for number, raw in enumerate(text.splitlines(), start=1):
        stripped = raw.partition("#")[0].strip()
        if not pending:
            start = number
        if stripped.endswith("\\"):
            pending.append(stripped[:-1])
            continue
        words = " ".join([*pending, stripped]).split()
        pending = []
        if words:
            yield start, words
    words = " ".join(pending).split()  # the last line ends in a backslash: its statement, or nothing
    if words:
        yield start, words


def _vertex(words, line, vertex, where):
    """``[x, y, z]`` of the statement ``v x y z ...`` (vertex number ``vertex``)."""
    if len(words) < 4:
        raise InvalidSurfaceError(
            f"{where}, line {line}: vertex {vertex} has {len(words) - 1} coordinates; a vertex is 'v x y z'"
        )
    bad = [w for w in words[1:4] if not NUMBER_TEXT.fullmatch(w)]
    if bad:
        raise InvalidSurfaceError(
            f"{where}, line {line}: vertex {vertex} has a coordinate that is no number: {shown(bad[0])!r}"
        )
    return [float(w) for w in words[1:4]]


#: A corner's vertex index as the reader takes it at once: a sign and at most 18 digits (any file's count fits).
INDEX = re.compile(r"[+-]?\d{1,18}", re.ASCII)


def _corners(words, line, face, written, where):
    """The 1-based vertex indices of the statement ``f ...`` (face number ``face``, ``written`` vertices before it)."""
    corners = []
    for word in words[1:]:
        text = word.partition("/")[0]
        index = int(text) if INDEX.fullmatch(text) else 0
        if not index:
            _refuse_corner(word, text, line, face, where)
        if index < 0:
            if -index > written:
                raise InvalidSurfaceError(
                    f"{where}, line {line}: face {face} refers to vertex {index}, but only {written} vertices come "
                    "before it"
                )
            index += written + 1
        corners.append(index)
    if len(corners) not in FACE_KINDS:
        raise InvalidSurfaceError(
            f"{where}, line {line}: face {face} has {len(corners)} corners; only triangles and quadrilaterals are "
            "read (triangulate the mesh when exporting it)"
        )
    return corners


def _refuse_corner(word, text, line, face, where):
    """The refusal of the corner ``word`` (vertex part ``text``): an index beyond any file, or no index."""
    if WHOLE_TEXT.fullmatch(text) and text.lstrip("+-").strip("0"):
        raise InvalidSurfaceError(f"{where}, line {line}: face {face} refers to vertex {shown(text)}, beyond the file")
    raise InvalidSurfaceError(
        f"{where}, line {line}: face {face} has the corner {shown(word)!r}, whose vertex is no index (indices count "
        "from 1, or back from -1)"
    )
