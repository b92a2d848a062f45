"""Surface files as modellers and accidents write them: OBJ files of every feature the reader skips, the NURBS file of
degree (399, 2), and strategies that build such files, valid by construction or mutated into hostile ones.
"""

import json

import numpy as np
from hypothesis import strategies as st

SQUARE = "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\n"

#: OBJ files modellers write, which meshio's OBJ reader refuses: each the 10 x 10 square in two triangles or a quad.
MODELLER_OBJ = {
    "Blender, one normal for a flat face": (
        "# Blender 4.0 style export\nmtllib roof.mtl\no Plane\n"
        + SQUARE
        + "vn -0.0000 -0.0000 1.0000\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\ns 0\nusemtl Material\n"
        "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n"
    ),
    "fewer texture coordinates than vertices": SQUARE + "vt 0 0\nvt 1 1\nf 1/1 2/1 3/2\nf 1/1 3/2 4/2\n",
    "relative indices": SQUARE + "f -4 -3 -2\nf -4 -2 -1\n",
    "vertex colours": SQUARE.replace(" 0\n", " 0 1 0 0\n") + "f 1 2 3\nf 1 3 4\n",
    "weights": SQUARE.replace(" 0\n", " 0 1.0\n") + "f 1 2 3\nf 1 3 4\n",
    "normals only": SQUARE + "vn 0 0 1\nf 1//1 2//1 3//1 4//1\n",
}


def degree_399():
    """A NURBS surface of degree (399, 2) over 20 x 15, one knot span in u: 12 ms a point to evaluate, minutes for a
    run."""
    p, n_u = 399, 400
    x, y = np.meshgrid(np.linspace(0, 20, n_u), np.linspace(0, 15, 4), indexing="ij")
    return {
        "type": "nurbs",
        "degree": [p, 2],
        "knots_u": [0.0] * n_u + [1.0] * n_u,
        "knots_v": [0, 0, 0, 0.5, 1, 1, 1],
        "control_points": np.stack([x, y, np.sin(x / 7) * np.sin(y / 5)], axis=-1).tolist(),
        "weights": np.ones((n_u, 4)).tolist(),
    }


def small_nurbs():
    """A valid NURBS roof of degree (2, 1) over about 3 x 8."""
    return {
        "type": "nurbs",
        "degree": [2, 1],
        "knots_u": [0, 0, 0, 0.5, 1, 1, 1],
        "knots_v": [0, 0, 1, 1],
        "control_points": [[[i, j, (i - 1.5) ** 2], [i, j + 5, 0]] for i, j in zip(range(4), range(4))],
        "weights": [[1, 1], [0.5, 2], [1, 1], [3, 1]],
    }


def small_bezier():
    """A valid Bezier dome of degree (2, 2) over 6 x 6."""
    return {
        "type": "bezier",
        "control_points": [[[3 * i, 3 * j, 2.0 * (i == j == 1)] for j in range(3)] for i in range(3)],
    }


@st.composite
def grid_meshes(draw):
    """A grid of (nx + 1) x (ny + 1) points of drawn coordinates, each cell a quad or two triangles: ``(points,
    faces)`` with faces as lists of 0-based indices."""
    nx, ny = draw(st.integers(1, 4)), draw(st.integers(1, 3))
    coordinate = st.floats(-1e6, 1e6, allow_nan=False, allow_subnormal=False)
    n = (nx + 1) * (ny + 1)
    points = np.array(draw(st.lists(st.tuples(coordinate, coordinate, coordinate), min_size=n, max_size=n)))
    node = np.arange(n).reshape(nx + 1, ny + 1)
    faces = []
    for i in range(nx):
        for j in range(ny):
            a, b, c, d = (int(k) for k in (node[i, j], node[i + 1, j], node[i + 1, j + 1], node[i, j + 1]))
            faces += [[a, b, c, d]] if draw(st.booleans()) else [[a, b, c], [a, c, d]]
    return points, faces


def roof_grid(nx=4, ny=3):
    """A vault of nx x ny unit cells rising 1, as ``(points, faces)`` of quads: a mesh the pipeline meshes at l = 1."""
    x, y = np.meshgrid(np.arange(nx + 1.0), np.arange(ny + 1.0), indexing="ij")
    points = np.column_stack([x.ravel(), y.ravel(), (np.sin(np.pi * x / nx) * np.sin(np.pi * y / ny)).ravel()])
    node = np.arange(len(points)).reshape(nx + 1, ny + 1)
    faces = [
        [int(node[i, j]), int(node[i + 1, j]), int(node[i + 1, j + 1]), int(node[i, j + 1])]
        for i in range(nx)
        for j in range(ny)
    ]
    return points, faces


@st.composite
def odd_obj(draw, points, faces):
    """``points`` and ``faces`` as OBJ text with what the format allows and the reader skips: texture coordinates and
    normals of other counts, ``v/vt``, ``v//vn``, ``v/vt/vn``, relative indices (vertices written as the faces need
    them), weights, colours, comments, ``g``/``o``/``s``/``usemtl``/``mtllib``, tabs, trailing spaces, continued lines,
    CRLF."""
    space = draw(st.sampled_from([" ", "\t", "  ", " \t"]))
    n_vt, n_vn = draw(st.integers(1, 7)), draw(st.integers(1, 3))
    lines = draw(st.lists(st.sampled_from(["# exported", "mtllib roof.mtl", "o Roof", "g shell"]), max_size=3))
    lines += [space.join(["vt", str(k / n_vt), "0.5"]) for k in range(n_vt)]
    lines += [space.join(["vn", "0", "0", "1"]) for _ in range(n_vn)]
    written = 0

    def vertex(k):
        extra = draw(st.sampled_from([[], ["1.0"], ["0.8", "0.1", "0.1"]]))
        return space.join(["v", *(repr(float(c)) for c in points[k]), *extra])

    for face in faces:
        while written <= max(face):
            lines.append(vertex(written))
            written += 1
        lines += draw(st.lists(st.sampled_from(["s off", "s 1", "usemtl Steel", "g panel", "# face"]), max_size=1))
        corners = []
        for k in face:
            index = str(k - written) if draw(st.booleans()) else str(k + 1)
            style = draw(st.sampled_from(["{v}", "{v}/{t}", "{v}//{n}", "{v}/{t}/{n}"]))
            corners.append(style.format(v=index, t=draw(st.integers(1, n_vt)), n=draw(st.integers(1, n_vn))))
        statement = space.join(["f", *corners])
        if draw(st.booleans()):  # continued on the next line
            statement = statement.replace(space, " \\\n", 1)
        lines.append(statement)
    lines += [vertex(k) for k in range(written, len(points))]
    trailing = draw(st.sampled_from(["", " ", "\t", "  # end"]))
    newline = draw(st.sampled_from(["\n", "\r\n"]))
    return newline.join(line + trailing for line in lines) + newline


#: Words that break a statement: no numbers, numbers out of range, odd spellings, indices that are no index.
HOSTILE_WORDS = ["nan", "inf", "-inf", "1e400", "0", "-0", "1_0", "abc", "9" * 30, "-99", "//", "1/2/3/4", "\\", "#"]


@st.composite
def mutated_text(draw, text):
    """``text`` with a few drawn mutations: a word replaced by a hostile one, a line dropped or repeated, the text cut
    short."""
    lines = text.splitlines()
    for _ in range(draw(st.integers(1, 3))):
        if not lines:
            break
        k = draw(st.integers(0, len(lines) - 1))
        action = draw(st.sampled_from(["word", "drop", "repeat", "cut"]))
        if action == "word" and lines[k].split():
            words = lines[k].split()
            words[draw(st.integers(0, len(words) - 1))] = draw(st.sampled_from(HOSTILE_WORDS))
            lines[k] = " ".join(words)
        elif action == "drop":
            del lines[k]
        elif action == "repeat":
            lines.insert(k, lines[k])
        elif action == "cut":
            lines = lines[:k] + [lines[k][: draw(st.integers(0, len(lines[k])))]]
    return "\n".join(lines) + "\n"


#: JSON values that a field may be given instead of its own.
HOSTILE_VALUES = [True, None, 10**400, -1, 0, 400, 1e308, -1e308, "x", [], {}, [[[]]], [0.5], [[1, 2]], float("nan")]


def _numbers_in(node, path=()):
    """The paths to every number in the JSON value ``node``."""
    if isinstance(node, dict):
        return [p for key in sorted(node) for p in _numbers_in(node[key], (*path, key))]
    if isinstance(node, list):
        return [p for k, x in enumerate(node) for p in _numbers_in(x, (*path, k))]
    return [path] if isinstance(node, (int, float)) and not isinstance(node, bool) else []


@st.composite
def mutated_description(draw, d):
    """The JSON description ``d`` with one entry somewhere in it (a field, a row, a point, a number) replaced by a
    hostile value, or one of its numbers moved by up to 10 %, as JSON text (NaN written as JSON's ``NaN``)."""
    d = json.loads(json.dumps(d))
    moved = draw(st.booleans())
    if moved:
        path = draw(st.sampled_from(_numbers_in(d)))
    else:
        path, node = [], d
        while isinstance(node, (dict, list)) and node and (not path or draw(st.booleans())):
            key = draw(st.sampled_from(sorted(node) if isinstance(node, dict) else range(len(node))))
            path.append(key)
            node = node[key]
    parent = d
    for key in path[:-1]:
        parent = parent[key]
    if moved:
        parent[path[-1]] = parent[path[-1]] * draw(st.floats(0.9, 1.1)) + draw(st.floats(-0.1, 0.1))
    else:
        parent[path[-1]] = draw(st.sampled_from(HOSTILE_VALUES))
    return json.dumps(d)
