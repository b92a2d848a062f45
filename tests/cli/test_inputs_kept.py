"""No run destroys its input: an output spelled as the input file (the same path, ``./path``, through a folder and
back, a symbolic link, a hard link, another case where the file system folds case) is refused with exit code 2,
before any work, and the input keeps its bytes; so are two outputs of one run that are one file."""

import contextlib
import io
import json
import os

import meshio
import pytest
from hypothesis import given
from hypothesis import strategies as st

from equimesh._cli import main
from equimesh.io._atomic import probe_folder
from equimesh.surface import pipeline
from equimesh.testing.meshes import roof_mesh

MESH_INPUTS = (".obj", ".stl", ".ply", ".vtk", ".vtu")
OPTIONS = ("-o", "--members", "--nodes")


def write_input(folder, ext, width, depth, cells, rise):
    """A roof as a triangle mesh file, or as the JSON of a bilinear Bezier patch with its rise in the middle."""
    path = folder / f"roof{ext}"
    if ext == ".json":
        net = [
            [[0, 0, 0], [0, depth / 2, rise], [0, depth, 0]],
            [[width, 0, 0], [width, depth / 2, rise], [width, depth, 0]],
        ]
        path.write_text(json.dumps({"type": "bezier", "control_points": net}))
    else:
        vertices, triangles = roof_mesh(width, depth, cells, rise)
        meshio.write(path, meshio.Mesh(vertices, [("triangle", triangles)]))
    return path


def spelled(path, how):
    """``path`` spelled another way (the links are made beside it)."""
    folder = path.parent
    if how == "same":
        return path
    if how == "dot":
        return folder / "." / path.name
    if how == "up and back":
        (folder / "sub").mkdir(exist_ok=True)
        return folder / "sub" / ".." / path.name
    if how == "symbolic link":
        os.symlink(path, folder / f"link{path.suffix}")
        return folder / f"link{path.suffix}"
    if how == "hard link":
        os.link(path, folder / f"hard{path.suffix}")
        return folder / f"hard{path.suffix}"
    return folder / path.name.swapcase()  # "case": the same file only where the file system folds case


SPELLINGS = ["same", "dot", "up and back", "symbolic link", "hard link"]


def _never_called(*args, **kwargs):
    raise AssertionError("mesh_surface must not run")


@given(
    ext=st.sampled_from(MESH_INPUTS + (".json",)),
    width=st.floats(8, 40),
    depth=st.floats(8, 40),
    cells=st.tuples(st.integers(2, 8), st.integers(2, 8)),
    rise=st.floats(0, 6),
    how=st.sampled_from(SPELLINGS + ["case"]),
    option=st.sampled_from(OPTIONS),
    data=st.data(),
)
def test_an_output_spelled_as_the_input_is_refused(ext, width, depth, cells, rise, how, option, data, tmp_path_factory):
    folder = tmp_path_factory.mktemp("kept")
    if how == "case" and not probe_folder(folder, ".obj"):
        how = data.draw(st.sampled_from(SPELLINGS), label="how (this file system does not fold case)")
    source = write_input(folder, ext, width, depth, cells, rise)
    before = source.read_bytes()
    target = spelled(source, how)
    made = sorted(folder.iterdir())
    args = [
        "mesh",
        source,
        "--length",
        1,
        "-q",
        option,
        target,
        *(["-o", folder / "out.obj"] if option != "-o" else []),
    ]
    with pytest.MonkeyPatch.context() as patch, contextlib.redirect_stderr(io.StringIO()) as stderr:
        patch.setattr(pipeline, "mesh_surface", _never_called)
        code = main([str(a) for a in args])
    err = stderr.getvalue()
    assert code == 2 and err.count("\n") == 1, err
    assert source.read_bytes() == before
    assert sorted(folder.iterdir()) == made


@pytest.mark.parametrize("ext", [".obj", ".stl", ".vtu"])
@pytest.mark.parametrize("how", SPELLINGS)
def test_meshing_a_roof_onto_itself_is_refused(ext, how, tmp_path, capsys):
    """``equimesh mesh roof.obj -l 1 -o roof.obj``, also through ./, links and a folder: exit 2, the roof kept."""
    source = write_input(tmp_path, ext, 20, 14, (10, 7), 3)
    before = source.read_bytes()
    code = main(["mesh", str(source), "-l", "1", "-o", str(spelled(source, how))])
    err = capsys.readouterr().err
    assert code == 2 and "would destroy the input" in err and err.count("\n") == 1, err
    assert source.read_bytes() == before


def test_a_case_variant_is_the_input_where_the_file_system_probe_folder(tmp_path, capsys):
    if not probe_folder(tmp_path, ".obj"):
        pytest.skip(f"the file system of {tmp_path} does not fold case: ROOF.OBJ is another file there")
    source = write_input(tmp_path, ".obj", 20, 14, (10, 7), 3)
    before = source.read_bytes()
    code = main(["mesh", str(source), "-l", "1", "-o", str(tmp_path / "ROOF.OBJ")])
    assert code == 2 and "would destroy the input" in capsys.readouterr().err
    assert source.read_bytes() == before
