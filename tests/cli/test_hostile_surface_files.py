"""Hostile surfaces through the command line: a mesh (exit 0) or one line of ours (exit 2), never exit 3 or a traceback.

The same inputs as the library's tests (tests/surface/test_hostile_surfaces.py, tests/planar/test_hostile_polygons.py):
closed-ended tubes and spherical caps, NURBS weights and parameter ranges out of reach of eq. (1), a steep net whose
flattened boundary bends within l, a flat mesh with a corner that rounds to 0 degrees; and the same bytes whatever
the BLAS's thread count.
"""

import json
import textwrap

import pytest
from blas_threads import outputs_with_one_and_two_threads
from repository import SURFACES
from surface_cases import STEEP_NET, vault_nurbs
from triangle_meshes import closed_tube, spherical_cap

from equimesh._cli import main
from equimesh.surface.optimize.solver import INSTALLED


def write_obj(path, surface):
    """A triangle mesh as an OBJ file."""
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in surface.vertices.tolist()]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in surface.triangles.tolist()]
    path.write_text("\n".join(lines) + "\n")
    return path


def mesh(capsys, tmp_path, surface_file, *options):
    """Exit code and standard error of ``equimesh mesh``; a refusal writes nothing and says one line."""
    out = tmp_path / "out.vtu"
    code = main(["mesh", str(surface_file), "-q", "-o", str(out), *map(str, options)])
    err = capsys.readouterr().err
    assert code in (0, 2), err
    assert out.exists() == (code == 0)
    if code:
        assert err.count("\n") == 1 and "Traceback" not in err and "Residuals" not in err, err
    return code, err


@pytest.mark.parametrize(
    "surface, l",
    [(closed_tube(1.0, 17.0), 0.5), (closed_tube(1.0, 20.0), 0.5), (spherical_cap(3.0, 170.0), 0.5)],
    ids=["tube 1 x 17", "tube 1 x 20", "cap 170"],
)
def test_tubes_and_caps_are_meshed_or_refused_in_one_line(surface, l, tmp_path, capsys):
    mesh(capsys, tmp_path, write_obj(tmp_path / "in.obj", surface), "-l", l, "--optimize", "none")


def test_a_tube_the_flattening_stretches_is_refused_on_its_flattened_area(tmp_path, capsys):
    code, err = mesh(
        capsys, tmp_path, write_obj(tmp_path / "tube.obj", closed_tube(1.0, 16.0)), "-l", 0.25, "--max-nodes", 6000
    )
    assert code == 2 and "flattened surface" in err


@pytest.mark.parametrize("radius, length", [(1.0, 10.0), (2.0, 30.0)], ids=["tube 1 x 10", "tube 2 x 30"])
def test_a_tube_the_flattening_stretches_is_refused_before_the_optimisation(radius, length, tmp_path, capsys):
    """The default objective on a closed-ended tube whose remapped members are nearly all shorter than l / 2 on the
    surface: refused at once (docs/decisions.md, "A work bound for the optimisation"), exit 2, one line, no file."""
    tube = write_obj(tmp_path / "tube.obj", closed_tube(radius, length))
    code, err = mesh(capsys, tmp_path, tube, "-l", radius, "--max-nodes", "none")
    assert code == 2 and "optimisation (bounded): no mesh with every member in [l, 2l] within reach" in err, err


@pytest.mark.parametrize(
    "surface, match",
    [
        (vault_nurbs(weight=1e8), "samples the surface too unevenly to flatten"),
        (vault_nurbs(u_range=3e-300), "the parameter range of u"),
        (vault_nurbs(u_range=1e300), "the parameter range of u"),
        ({"type": "bezier", "control_points": STEEP_NET}, "the flattened boundary bends so sharply"),
    ],
    ids=["weights 1e8 apart", "u range 3e-300", "u range 1e300", "steep net"],
)
def test_surfaces_out_of_reach_of_section_4_are_refused_in_their_terms(surface, match, tmp_path, capsys):
    path = tmp_path / "surface.json"
    path.write_text(json.dumps(surface))
    code, err = mesh(capsys, tmp_path, path, "-l", 2.5, "--optimize", "none")
    assert code == 2 and match in err


def test_a_flat_mesh_with_a_corner_that_rounds_to_zero_degrees_is_refused(tmp_path, capsys):
    """The quadrilateral whose corner rounds to exactly 0 degrees (a ZeroDivisionError once), as two flat triangles."""
    quad = [
        [-4.752209060842619, -5.879333958263281, 0.0],
        [-8.146644104301632, -11.758667916526562, 0.0],
        [-6.109983078226224, -8.231067541568594, 0.0],
        [-2.0366610260754086, -5.879333958263281, 0.0],
    ]
    path = tmp_path / "quad.obj"
    path.write_text("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in quad) + "f 1 2 3\nf 1 3 4\n")
    code, _ = mesh(capsys, tmp_path, path, "-l", 0.5)
    assert code == 2


_DOME_ON_A_FINE_GRID = textwrap.dedent(f"""
    import hashlib, pathlib, tempfile
    from equimesh._cli import main
    out = pathlib.Path(tempfile.mkdtemp()) / "dome.vtu"
    dome = {str(SURFACES / "reference_dome.json")!r}
    code = main(["mesh", dome, "-l", "5", "--grid", "50", "50", "-q", "-o", str(out)])
    print(code, hashlib.sha256(out.read_bytes()).hexdigest())
""")


@pytest.mark.parametrize("factorisation", INSTALLED)
def test_the_same_bytes_whatever_the_blas_thread_count(factorisation):
    """The reference dome on a 50 x 50 grid: its connectivity changed with ``OPENBLAS_NUM_THREADS`` 1 and 2."""
    outputs = outputs_with_one_and_two_threads(_DOME_ON_A_FINE_GRID, factorisation)
    assert outputs[0] == outputs[1] and outputs[0].split()[0] == "0"
