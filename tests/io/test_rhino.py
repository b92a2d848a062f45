"""Rhino files (.3dm) in: NURBS surfaces and single-face Breps, picking one of several, refusals in one line."""

import sys
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from refusals import assert_one_line
from strategies_nurbs import cylinder, nurbs

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
        add = {
            rhino3dm.Brep: model.Objects.AddBrep,
            rhino3dm.Point3d: model.Objects.AddPoint,
            rhino3dm.LineCurve: model.Objects.AddCurve,
        }.get(type(geometry), model.Objects.AddSurface)
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
    "choice, message",
    [
        (None, f"{{path}} holds 4 surfaces ({LISTING}); choose one by name or index"),
        ("vault", f"{{path}} holds 2 surfaces named 'vault' ({LISTING}); choose one by index"),
        ("roof", f"{{path}} has no surface 'roof'; its surfaces are {LISTING}"),
        (0, f"{{path}} has no surface 0; its surfaces are {LISTING}"),
        ("7", f"{{path}} has no surface '7'; its surfaces are {LISTING}"),
        (3.0, f"{{path}} has no surface 3.0; its surfaces are {LISTING}"),
        (True, f"{{path}} has no surface true; its surfaces are {LISTING}"),
        (
            4,
            "object 4 'box' of {path} is a Brep of 6 faces; only single-face Breps (or surfaces) can be meshed: "
            "explode it in Rhino and pick one face",
        ),
    ],
)
def test_choosing_an_object(several, choice, message):
    """A name, an index (an integer or its digits; not a float or a bool), or a one-line refusal."""
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(several, object=choice)
    assert str(err.value) == message.format(path=several)
    assert_one_line(str(err.value))


def test_an_unnamed_surface_is_listed_by_its_index(rhino3dm, tmp_path):
    path = write(tmp_path / "two.3dm", ("", cylinder()), ("vault", cylinder(radius=5.0)))
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(path)
    assert str(err.value) == f"{path} holds 2 surfaces (0 (unnamed), 1 'vault'); choose one by name or index"
    same_surface(cylinder(), load_surface(path, object=np.int64(0)))


def test_object_by_index_or_name(several, rhino3dm, tmp_path):
    same_surface(cylinder(radius=5.0), load_surface(several, object=3))
    same_surface(cylinder(radius=5.0), load_surface(several, object="3"))
    one = write(tmp_path / "one.3dm", ("vault", cylinder()), ("marker", rhino3dm.Point3d(0, 0, 0)))
    same_surface(cylinder(), load_surface(one, object="vault"))
    same_surface(cylinder(), load_surface(one))


def test_trimmed_face_is_read_untrimmed_with_a_warning(several):
    with pytest.warns(SurfaceWarning) as caught:
        s = load_surface(several, object="plate")
    (warning,) = caught
    assert str(warning.message) == (
        f"object 2 'plate' of {several} is a trimmed face: it is meshed on its untrimmed surface, not on the trimmed "
        "outline"
    )
    assert s.degree == (1, 1)
    assert np.all(s.domain.upper - s.domain.lower >= 10.0)  # the plane around the whole circle


def test_not_a_rhino_file_and_no_surface(rhino3dm, tmp_path):
    fake = tmp_path / "fake.3dm"
    fake.write_text('{"type": "bezier"}')
    points = write(tmp_path / "points.3dm", ("a", rhino3dm.Point3d(0, 0, 0)))
    line = rhino3dm.LineCurve(rhino3dm.Point3d(0, 0, 0), rhino3dm.Point3d(1, 0, 0))
    two = write(tmp_path / "two.3dm", ("a", rhino3dm.Point3d(0, 0, 0)), ("b", line))
    empty = write(tmp_path / "empty.3dm")
    for path, message in (
        (fake, "{path} is not a Rhino .3dm file rhino3dm can read"),
        (points, "{path} holds no surface and no single-face Brep (1 objects: Point)"),
        (two, "{path} holds no surface and no single-face Brep (2 objects: LineCurve, Point)"),
        (empty, "{path} holds no surface and no single-face Brep (0 objects: nothing)"),
    ):
        with pytest.raises(InvalidSurfaceError) as err:
            load_surface(path)
        assert str(err.value) == message.format(path=path)
        assert_one_line(str(err.value))


def test_a_weight_that_is_not_positive_is_refused(rhino3dm, tmp_path):
    surface = to_rhino_surface(cylinder())
    surface.Points[2, 1] = rhino3dm.Point4d(0.0, 0.0, 0.0, 0.0)
    path = write(tmp_path / "w.3dm", ("vault", surface))
    with pytest.raises(InvalidSurfaceError) as err:
        load_surface(path)
    assert str(err.value) == f"object 0 'vault' of {path}: control point [2][1] has weight 0.0, not positive"


def test_missing_rhino3dm_says_how_to_install(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "rhino3dm", None)  # import rhino3dm now raises ImportError
    path = tmp_path / "roof.3dm"
    path.write_bytes(b"anything")
    with pytest.raises(MissingDependencyError) as err:
        load_surface(path)
    assert str(err.value) == (
        f"reading Rhino files needs rhino3dm, which is not installed: pip install 'equimesh[rhino]' ({path})"
    )


def test_object_is_refused_for_json(tmp_path):
    path = tmp_path / "s.json"
    path.write_text('{"type": "bezier", "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]]}')
    with pytest.raises(
        InvalidSurfaceError, match=r"choosing an object applies to files with several surfaces \(\.3dm\)"
    ):
        load_surface(path, object="roof")
