"""Input and output of an insertion engine, and the constrained Delaunay triangulation."""

import ctypes
import os
import sys
import tempfile
from contextlib import contextmanager
from dataclasses import dataclass

import numpy as np
import triangle

from ...errors import InternalError


@dataclass(frozen=True)
class Region:
    """A polygonal region to fill, given by its boundary as constraint segments.

    Attributes
    ----------
    points : (n, 2) float array, the fixed initial points (all endpoints of
        the segments, and possibly more).
    segments : (k, 2) int array, the constraint segments; together they form
        the boundary of the region (outer boundary and the boundary of holes).
    holes : (h, 2) float array, one seed point inside each hole.
    """

    points: np.ndarray
    segments: np.ndarray
    holes: np.ndarray


@dataclass(frozen=True)
class Insertion:
    """Result of farthest-point insertion.

    ``points[:n_initial]`` are the region's initial points in their order;
    the rest were inserted, in insertion order.  ``segments`` are the
    constraints after inserted points split them; ``triangles`` the
    constrained Delaunay triangulation of the region (Step 5).
    """

    points: np.ndarray
    triangles: np.ndarray
    segments: np.ndarray
    n_initial: int
    values: np.ndarray


def constrained_delaunay(points, segments, holes):
    """Constrained Delaunay triangulation of a region (paper, Definition 1).

    Uses Shewchuk's Triangle (switch ``p``: planar straight-line graph,
    triangles outside the outer boundary and inside holes are removed; no
    quality switches, so no Steiner point is added).  Triangle's exact
    predicates make the result valid on cocircular lattices.
    """
    data = {"vertices": np.asarray(points, dtype=float), "segments": np.asarray(segments, dtype=np.int32)}
    if len(holes):
        data["holes"] = np.asarray(holes, dtype=float)
    with captured_stdout() as printed:
        try:
            out = triangle.triangulate(data, "pQ")
        except RuntimeError:
            out = None
    if out is None:
        said = printed().strip().splitlines()
        raise InternalError(
            "Triangle failed on a validated input"
            + (f" ({said[0]})" if said else "")
            + ": a bug in equimesh, please report it"
        )
    if "triangles" not in out:
        return np.empty((0, 3), dtype=np.int64)
    if len(out["vertices"]) != len(points):
        raise InternalError(
            "constrained Delaunay triangulation added Steiner points (constraints intersect): a bug in equimesh"
        )
    return np.asarray(out["triangles"], dtype=np.int64)


_LIBC = ctypes.CDLL(None)


@contextmanager
def captured_stdout():
    """Redirect file descriptor 1 to a temporary file (Triangle prints its errors there, not to Python).

    Yields a function returning what was printed.  The descriptor is restored
    in ``finally``, so nothing Triangle prints reaches our standard output.
    """
    if sys.stdout is not None:  # None: descriptor 1 was closed when the interpreter started
        sys.stdout.flush()
    try:
        saved = os.dup(1)
    except OSError:  # descriptor 1 is closed: Triangle's prints go nowhere, and nothing opened here can take it
        yield lambda: ""
        return
    with tempfile.TemporaryFile(mode="w+b") as sink:
        text = []
        try:
            os.dup2(sink.fileno(), 1)
            yield lambda: "".join(text)
        finally:
            _LIBC.fflush(None)
            os.dup2(saved, 1)
            os.close(saved)
            sink.seek(0)
            text.append(sink.read().decode(errors="replace"))
