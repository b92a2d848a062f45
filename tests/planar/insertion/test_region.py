"""The constrained Delaunay triangulation of an insertion region (``planar/insertion/region.py``), tested directly.

What must hold (Definition 1 of the paper): the triangulation respects every
constraint segment, removes the triangles inside holes (one seed each) and
adds no point; integer input is taken as the same numbers; crossing
constraints (a Steiner point) and a failure of Triangle are bugs of ours,
reported as ``InternalError`` with the first line Triangle printed, and
nothing Triangle prints reaches our standard output.  Each test runs in
milliseconds, so that the mutants of ``region.py`` (``make mutation``) are
cheap to kill.
"""

import ctypes
import os
import subprocess
import sys

import numpy as np
import pytest

import equimesh
from equimesh.errors import InternalError
from equimesh.planar.insertion import region
from equimesh.planar.insertion.region import constrained_delaunay

SQUARE10 = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


def test_triangle_failure_is_an_internal_error_and_prints_nothing(monkeypatch, capfd):
    """Triangle's own messages go to fd 1 from C; they never reach our stdout, and its failure is ours."""

    def failing(data, switches):
        os.write(1, b"Internal error in finddirection():  Unable to find a triangle.\n")
        raise RuntimeError("triangle failed")

    monkeypatch.setattr(region.triangle, "triangulate", failing)
    with pytest.raises(InternalError, match=r"Triangle failed .*finddirection"):
        equimesh.increment(SQUARE10, 1.0)
    assert capfd.readouterr().out == ""


SQUARE = np.array([[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]])


RING = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])


NO_HOLES = np.empty((0, 2))


def as_sets(triangles):
    """Triangles as a set of vertex sets."""
    return {frozenset(t) for t in np.asarray(triangles).tolist()}


def area(points, triangles):
    """Signed area of the triangles (positive when counter-clockwise)."""
    a, b, c = (points[triangles[:, k]] for k in range(3))
    return 0.5 * np.sum((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


@pytest.mark.parametrize("diagonal, expected", [([0, 2], [{0, 1, 2}, {0, 2, 3}]), ([1, 3], [{0, 1, 3}, {1, 2, 3}])])
def test_a_constraint_decides_between_cocircular_diagonals(diagonal, expected):
    """A square's four corners are cocircular: the constrained diagonal is the one used; triangles counter-clockwise."""
    tri = constrained_delaunay(SQUARE, np.vstack([RING, [diagonal]]), NO_HOLES)
    assert as_sets(tri) == {frozenset(e) for e in expected}
    assert tri.dtype == np.int64 and tri.shape == (2, 3)
    assert area(SQUARE, tri) == 4.0 and np.all([area(SQUARE, t[None]) > 0 for t in tri])


def test_a_hole_seed_carves_its_hole():
    """A 4 x 4 square around a 2 x 2 hole: 12 with the seed (given as a list), 16 without."""
    points = np.vstack([SQUARE * 2.0, SQUARE + 1.0])
    segments = np.vstack([RING, RING + 4])
    assert area(points, constrained_delaunay(points, segments, [[2.0, 2.0]])) == 12.0
    assert area(points, constrained_delaunay(points, segments, NO_HOLES)) == 16.0


def test_integer_input_is_the_same_numbers():
    """Integer coordinates, int64 segments and an integer hole seed give the triangles of their float values."""
    points = np.vstack([SQUARE * 2.0, SQUARE + 1.0])
    segments = np.vstack([RING, RING + 4]).astype(np.int64)
    expected = constrained_delaunay(points, segments, np.array([[2.0, 2.0]]))
    assert np.array_equal(constrained_delaunay(points.astype(int).tolist(), segments, np.array([[2, 2]])), expected)


def test_a_region_carved_whole_has_no_triangle():
    """A seed inside the outer boundary removes every triangle: an empty (0, 3) int64 array."""
    tri = constrained_delaunay(SQUARE, RING, np.array([[1.0, 1.0]]))
    assert tri.shape == (0, 3) and tri.dtype == np.int64


def test_crossing_constraints_are_a_bug():
    """Both diagonals as constraints: Triangle adds their crossing point, which the region never has."""
    with pytest.raises(InternalError) as err:
        constrained_delaunay(SQUARE, np.vstack([RING, [[0, 2], [1, 3]]]), NO_HOLES)
    assert str(err.value) == (
        "constrained Delaunay triangulation added Steiner points (constraints intersect): a bug in equimesh"
    )


@pytest.mark.parametrize(
    "said, shown",
    [(b"Error:  the input is bad.\nA second line.\n", " (Error:  the input is bad.)"), (b"", ""), (b"\n\n", "")],
)
def test_a_failure_of_triangle_is_a_bug_with_what_it_printed(monkeypatch, capfd, said, shown):
    """Triangle prints its errors on file descriptor 1 and fails: the first line it printed, in our message only."""

    def failing(data, switches):
        assert switches == "pQ" and data["vertices"].dtype == float and data["segments"].dtype == np.int32
        os.write(1, said)
        raise RuntimeError("Triangle failed")

    monkeypatch.setattr(region.triangle, "triangulate", failing)
    with pytest.raises(InternalError) as err:
        constrained_delaunay(SQUARE, RING, NO_HOLES)
    assert str(err.value) == f"Triangle failed on a validated input{shown}: a bug in equimesh, please report it"
    assert capfd.readouterr().out == ""


def test_captured_stdout_takes_what_c_and_the_descriptor_print_and_restores_it(capfd):
    """C's buffered printf and raw writes to descriptor 1 inside the block are returned, not shown; after it,
    descriptor 1 is the one before (what Python printed before the block was flushed there first)."""
    print("before", end="")
    with region.captured_stdout() as printed:
        ctypes.CDLL(None).printf(b"from C\n")
        os.write(1, b"raw\n")
    os.write(1, b"after\n")
    assert printed() == "from C\nraw\n"
    assert capfd.readouterr().out == "beforeafter\n"


def test_captured_stdout_with_descriptor_1_closed_captures_nothing_and_leaves_it_closed():
    """Descriptor 1 closed (``equimesh mesh ... >&-``; Python's ``sys.stdout`` is then None): the block runs, Triangle
    included, with nothing to capture, and no file opened in it takes descriptor 1."""
    code = """if True:
        import os, sys
        from equimesh.planar.insertion import region
        os.close(1)
        sys.stdout = None
        square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
        triangles = region.constrained_delaunay(square, [[0, 1], [1, 2], [2, 3], [3, 0]], [])  # captures inside
        with region.captured_stdout() as printed:
            os.write(2, b"")
        try:
            os.fstat(1)
            sys.stderr.write("descriptor 1 open")
        except OSError:
            sys.stderr.write(f"closed {printed()!r} {len(triangles)}")
    """
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stderr == "closed '' 2"
