"""OBJ files in (``io/_obj.py``): what modellers write reads back as the positions and faces a plain writer gives, and
what is not a mesh is refused in one line naming the line and the vertex or face by the file's own numbers.

What must hold: for any mesh, a file written with any of the features of the format the reader skips (texture
coordinates and normals of other counts, ``v/vt/vn``, ``v//vn``, relative indices, colours, weights, comments,
groups, materials, CRLF, tabs, trailing spaces, continued lines) reads back exactly as the same mesh written by
meshio's plain writer.
"""

import meshio
import numpy as np
import pytest
from hostile_files import MODELLER_OBJ, SQUARE, grid_meshes, odd_obj
from hypothesis import given
from hypothesis import strategies as st
from refusals import assert_one_line

from equimesh import InvalidSurfaceError, TriangulatedSurface
from equimesh.io import load_surface
from equimesh.io._obj import read_obj


def _file(tmp_path, text, name="m.obj"):
    path = tmp_path / name
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    return path


@pytest.mark.parametrize("case", sorted(MODELLER_OBJ))
def test_files_modellers_write_are_read(tmp_path, case):
    """Each reads as the 10 x 10 square: two triangles (or a quad split in two), one boundary loop of 4 vertices."""
    surface = load_surface(_file(tmp_path, MODELLER_OBJ[case]))
    assert isinstance(surface, TriangulatedSurface)
    assert len(surface.triangles) == 2 and [len(loop) for loop in surface.loops] == [4]
    np.testing.assert_array_equal(np.sort(surface.vertices[:, :2], axis=0), [[0, 0], [0, 0], [10, 10], [10, 10]])


def test_relative_indices_count_back_from_the_last_vertex_before_the_face(tmp_path):
    """``-1`` is the last vertex written before the face, not the last of the file."""
    text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -3 -2 -1\nv 0 1 0\nf 1 3 -1\n"
    points, blocks = read_obj(_file(tmp_path, text), "m.obj")
    assert len(points) == 4
    assert [(kind, cells.tolist()) for kind, cells in blocks] == [("triangle", [[0, 1, 2], [0, 2, 3]])]


def test_faces_keep_the_file_order_in_runs_of_one_kind(tmp_path):
    text = SQUARE + "v 20 0 0\nv 20 10 0\nf 1 2 3\nf 2 5 6 3\nf 1 3 4\n"
    _, blocks = read_obj(_file(tmp_path, text), "m.obj")
    assert [(kind, cells.tolist()) for kind, cells in blocks] == [
        ("triangle", [[0, 1, 2]]),
        ("quad", [[1, 4, 5, 2]]),
        ("triangle", [[0, 2, 3]]),
    ]


NO_INDEX = "whose vertex is no index (indices count from 1, or back from -1)"
ONLY_3_OR_4 = "only triangles and quadrilaterals are read (triangulate the mesh when exporting it)"

#: Files that are no mesh -> the refusal after the file's path.
REFUSED = {
    "face past the vertices": (
        SQUARE + "f 1 2 3 9\n",
        ", line 5: face 1 refers to vertex 9, but the file has 4 vertices",
    ),
    "relative index before the first vertex": (
        SQUARE + "f 1 2 3\nf -1 -2 -5\n",
        ", line 6: face 2 refers to vertex -5, but only 4 vertices come before it",
    ),
    "index 0": (SQUARE + "f 0 1 2\n", f", line 5: face 1 has the corner '0', {NO_INDEX}"),
    "index -0": (SQUARE + "f 1 2 -0\n", f", line 5: face 1 has the corner '-0', {NO_INDEX}"),
    "index 0 of 30 digits": (
        SQUARE + "f 1 2 " + "0" * 30 + "\n",
        f", line 5: face 1 has the corner '{'0' * 30}', {NO_INDEX}",
    ),
    "corner without a vertex": (SQUARE + "f 1 2 /3\n", f", line 5: face 1 has the corner '/3', {NO_INDEX}"),
    "corner not a number": (SQUARE + "f 1 2 x\n", f", line 5: face 1 has the corner 'x', {NO_INDEX}"),
    "index with an underscore": (SQUARE + "f 1 2 1_0\n", f", line 5: face 1 has the corner '1_0', {NO_INDEX}"),
    "index of 30 digits": (
        SQUARE + "f 1 2 " + "9" * 30 + "\n",
        f", line 5: face 1 refers to vertex {'9' * 30}, beyond the file",
    ),
    "index of 30 digits after a sign": (
        SQUARE + "f 1 2 -" + "9" * 30 + "\n",
        f", line 5: face 1 refers to vertex -{'9' * 30}, beyond the file",
    ),
    "a comment's words as corners": (
        SQUARE + "f 1 2 3 # a # b\nf 1 2 # 4\n",
        f", line 6: face 2 has 2 corners; {ONLY_3_OR_4}",
    ),
    "two corners": (SQUARE + "f 1 2\n", f", line 5: face 1 has 2 corners; {ONLY_3_OR_4}"),
    "five corners": (SQUARE + "v 5 15 0\nf 1 2 3 5 4\n", f", line 6: face 1 has 5 corners; {ONLY_3_OR_4}"),
    "vertex of two numbers": ("v 0 0 0\nv 1 0\n", ", line 2: vertex 2 has 2 coordinates; a vertex is 'v x y z'"),
    "coordinate not a number": ("v 0 0 0\nv 1 0 z\n", ", line 2: vertex 2 has a coordinate that is no number: 'z'"),
    "coordinate with an underscore": ("v 1_0 0 0\n", ", line 1: vertex 1 has a coordinate that is no number: '1_0'"),
    "coordinate NaN": ("v 0 0 0\n\nv 1 nan 0\n", ", line 3: vertex 2 is not finite: (1, nan, 0)"),
    "coordinate beyond the float range": ("v 0 0 1e400\n", ", line 1: vertex 1 is not finite: (0, 0, inf)"),
    "no faces": (SQUARE + "vt 0 0\nl 1 2\n", " has no triangles (it holds no cells); export the surface as triangles"),
    "empty": ("", " has no points and no triangles"),
    "binary": (bytes(range(256)) * 4, " has no points and no triangles"),
}


@pytest.mark.parametrize("case", sorted(REFUSED))
def test_what_is_not_a_mesh_is_refused_in_one_line_in_the_files_numbers(tmp_path, case):
    text, rest = REFUSED[case]
    path = _file(tmp_path, text)
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(path)
    assert str(err.value) == f"{path}{rest}"
    assert_one_line(str(err.value))


def test_words_after_a_vertexs_coordinates_and_a_statement_continued_to_the_end_of_the_file_are_read(tmp_path):
    """``v x y z`` and whatever follows (a colour's name here); a comment holding ``#``; a last line ending in ``\\``
    continues into nothing, and a line of a lone ``\\`` into the next."""
    text = "v 0 0 0 red\nv 1 0 0 1 0 0\nv 1 1 0 # a # b\n\\\nv 0 1 0\nf 1 2 3 # c # d\nf 1 \\\n3 \\\n 4 \\"
    points, blocks = read_obj(_file(tmp_path, text), "m.obj")
    np.testing.assert_array_equal(points, [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]])
    assert [(kind, cells.tolist()) for kind, cells in blocks] == [("triangle", [[0, 1, 2], [0, 2, 3]])]
    assert read_obj(_file(tmp_path, SQUARE + "f 1 2 3\n\\"), "m.obj")[1][0][1].tolist() == [[0, 1, 2]]
    continued = "v 0 0 0\nv 1 0\\\n0\nv 1 1 0\nf 1 2\\\n3\n"  # the backslash right after a word ends it
    points, blocks = read_obj(_file(tmp_path, continued), "m.obj")
    assert points.tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0]] and blocks[0][1].tolist() == [[0, 1, 2]]


def test_line_numbers_count_crlf_lines_and_continued_statements_start_where_they_begin(tmp_path):
    text = "v 0 0 0\r\nv 1 0 0\r\nf 1 \\\r\n 2 \\\r\n 3\r\n"
    with pytest.raises(InvalidSurfaceError, match=r"line 3: face 1 refers to vertex 3, but the file has 2"):
        load_surface(_file(tmp_path, text))


# --------------------------------------------------------------------------- generated files


def plain_blocks(faces):
    """The faces as runs of one kind, as the reader gives them."""
    blocks = []
    for face in faces:
        kind = "triangle" if len(face) == 3 else "quad"
        if not blocks or blocks[-1][0] != kind:
            blocks.append((kind, []))
        blocks[-1][1].append(face)
    return [(kind, np.array(cells)) for kind, cells in blocks]


@given(st.data())
def test_odd_but_valid_files_read_back_as_a_plain_writers(tmp_path_factory, data):
    points, faces = data.draw(grid_meshes())
    folder = tmp_path_factory.mktemp("obj")
    plain = folder / "plain.obj"
    meshio.write(plain, meshio.Mesh(points, [(kind, cells) for kind, cells in plain_blocks(faces)]))
    odd = _file(folder, data.draw(odd_obj(points, faces)), "odd.obj")
    for path in (plain, odd):
        got_points, got_blocks = read_obj(path, path.name)
        np.testing.assert_array_equal(got_points, points)
        assert [(kind, cells.tolist()) for kind, cells in got_blocks] == [
            (kind, cells.tolist()) for kind, cells in plain_blocks(faces)
        ]
