"""Rhino files (.3dm) in: NURBS surfaces and single-face Breps, picking one of several, refusals in one line."""

import subprocess
import sys
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from refusals import assert_one_line
from repository import SURFACES
from strategies_nurbs import cylinder, nurbs
from surface_invariants import assert_valid_surface_mesh

import equimesh
from equimesh import InvalidSurfaceError, MissingDependencyError, NurbsSurface, SurfaceWarning
from equimesh.io import load_surface, to_rhino_surface


@pytest.fixture
def rhino3dm():
    return pytest.importorskip("rhino3dm", reason="rhino3dm (the optional extra [rhino]) is not installed")


def write(path, *objects):
    """A .3dm file holding ``(name, geometry)`` objects in order; surfaces are added as surfaces, Breps as Breps."""
    import rhino3dm

    model = rhino3dm.File3dm()
    for name, geometry in objects:
        attributes = rhino3dm.ObjectAttributes()
        attributes.Name = name
        if isinstance(geometry, NurbsSurface):
            geometry = to_rhino_surface(geometry)
        add = {rhino3dm.Brep: model.Objects.AddBrep, rhino3dm.Point3d: model.Objects.AddPoint}.get(
            type(geometry), model.Objects.AddSurface
        )
        add(geometry, attributes)
    assert model.Write(str(path), 7)
    return path


def same_surface(a, b):
    assert a.degree == b.degree and a.domain == b.domain
    uv = a.domain.at_fractions(*np.random.default_rng(0).uniform(0, 1, (2, 20)))
    np.testing.assert_allclose(
        b.evaluate(*uv.T), a.evaluate(*uv.T), rtol=0, atol=1e-12 * (1 + np.abs(a.control_points).max())
    )


@settings(max_examples=10, deadline=None)
@given(s=nurbs())
def test_nurbs_round_trip_through_a_rhino_file(tmp_path_factory, s):
    pytest.importorskip("rhino3dm")
    path = write(tmp_path_factory.mktemp("rhino") / "s.3dm", ("s", s))
    got = load_surface(path)
    same_surface(s, got)
    # Rhino keeps no superfluous end knots (they do not act on the domain): the reader repeats their neighbours.
    assert np.array_equal(got.knots_u[1:-1], s.knots_u[1:-1]) and np.array_equal(got.knots_v[1:-1], s.knots_v[1:-1])
    np.testing.assert_allclose(got.weights, s.weights, rtol=1e-15)


def test_single_face_brep_is_its_surface(rhino3dm, tmp_path):
    s = cylinder()
    path = write(tmp_path / "b.3dm", ("vault", rhino3dm.Brep.CreateFromSurface(to_rhino_surface(s))))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an untrimmed face gives no warning
        same_surface(s, load_surface(path))


@pytest.fixture
def several(rhino3dm, tmp_path):
    """Objects: 0 a point, 1 'vault', 2 'plate' (trimmed), 3 'vault' again, 4 'box' (6 faces)."""
    circle = rhino3dm.Circle(rhino3dm.Point3d(0, 0, 0), 5.0).ToNurbsCurve()
    return write(
        tmp_path / "several.3dm",
        ("marker", rhino3dm.Point3d(1, 2, 3)),
        ("vault", cylinder()),
        ("plate", rhino3dm.Brep.CreateTrimmedPlane(rhino3dm.Plane.WorldXY(), circle)),
        ("vault", cylinder(radius=5.0)),
        ("box", rhino3dm.Brep.CreateFromBox(rhino3dm.Box(rhino3dm.BoundingBox(0, 0, 0, 1, 1, 1)))),
    )


LISTING = "1 'vault', 2 'plate', 3 'vault', 4 'box'"


@pytest.mark.parametrize(
    "choice, fragment",
    [
        (None, f"holds 4 surfaces ({LISTING}); choose one by name or index"),
        ("vault", f"holds 2 surfaces named 'vault' ({LISTING}); choose one by index"),
        ("roof", f"has no surface 'roof'; its surfaces are {LISTING}"),
        (0, f"has no surface 0; its surfaces are {LISTING}"),
        ("7", "has no surface '7'"),
        (4, "object 4 'box' of "),
    ],
)
def test_choosing_an_object(several, choice, fragment):
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(several, object=choice)
    assert fragment in str(err.value)
    assert_one_line(str(err.value))


def test_object_by_index_or_name(several, rhino3dm, tmp_path):
    same_surface(cylinder(radius=5.0), load_surface(several, object=3))
    same_surface(cylinder(radius=5.0), load_surface(several, object="3"))
    one = write(tmp_path / "one.3dm", ("vault", cylinder()), ("marker", rhino3dm.Point3d(0, 0, 0)))
    same_surface(cylinder(), load_surface(one, object="vault"))
    same_surface(cylinder(), load_surface(one))


def test_trimmed_face_is_read_untrimmed_with_a_warning(several):
    with pytest.warns(
        SurfaceWarning, match=r"object 2 'plate' of .* is a trimmed face: it is meshed on its untrimmed surface"
    ):
        s = load_surface(several, object="plate")
    assert s.degree == (1, 1)
    assert np.all(s.domain.upper - s.domain.lower >= 10.0)  # the plane around the whole circle


def test_not_a_rhino_file_and_no_surface(rhino3dm, tmp_path):
    fake = tmp_path / "fake.3dm"
    fake.write_text('{"type": "bezier"}')
    points = write(tmp_path / "points.3dm", ("a", rhino3dm.Point3d(0, 0, 0)))
    for path, fragment in (
        (fake, "is not a Rhino .3dm file"),
        (points, "holds no surface and no single-face Brep (1 objects: Point)"),
    ):
        with pytest.raises(InvalidSurfaceError) as err:
            load_surface(path)
        assert fragment in str(err.value)
        assert_one_line(str(err.value))


def test_missing_rhino3dm_says_how_to_install(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "rhino3dm", None)  # import rhino3dm now raises ImportError
    path = tmp_path / "roof.3dm"
    path.write_bytes(b"anything")
    with pytest.raises(MissingDependencyError, match=r"pip install 'equimesh\[rhino\]'") as err:
        load_surface(path)
    assert_one_line(str(err.value))


def test_object_is_refused_for_json(tmp_path):
    path = tmp_path / "s.json"
    path.write_text('{"type": "bezier", "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]]}')
    with pytest.raises(
        InvalidSurfaceError, match=r"choosing an object applies to files with several surfaces \(\.3dm\)"
    ):
        load_surface(path, object="roof")


def test_example_roof_file_meshes_through_the_command_line(rhino3dm, tmp_path):
    """experiments/surfaces/roof.3dm's roof, written alone to a file, through `equimesh mesh` (the INPUT_FORMATS
    row)."""

    roof = load_surface(SURFACES / "roof.3dm", object="roof")
    path = write(tmp_path / "roof.3dm", ("roof", roof))
    out = tmp_path / "roof.obj"
    run = subprocess.run(
        [
            sys.executable,
            "-m",
            "equimesh._cli",
            "mesh",
            str(path),
            "--length",
            "6",
            "--grid",
            "8",
            "8",
            "--optimize",
            "none",
            "-o",
            str(out),
            "--quiet",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 0, run.stderr
    mesh = equimesh.mesh_surface(roof, 6.0, grid=(8, 8), optimize="none")
    assert_valid_surface_mesh(mesh, roof)
    assert out.stat().st_size > 0
