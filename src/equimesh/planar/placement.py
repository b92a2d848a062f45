"""Beyond the paper: choosing the lattice placement of Problem 2.

The lattice of Problem 2 may be rotated and shifted freely; the placement
changes how many lattice triangles fit at clearance from the boundary, hence
how many edges end up in G1.  The lattice is invariant under rotation by 60
degrees and under translation by a lattice vector, so the search space is
``angle in [0, 60)`` times one lattice cell of offsets.

Objective: the number of edges of the kept lattice part K (edges of kept
lattice triangles).  Every one of them is a G1 edge of the final mesh; the
final mesh can add a few more (lattice neighbours joined across the strip),
so the objective is a lower bound on the G1 count that needs no insertion
run, which keeps the search cheap.

Search (deterministic): a grid of ``n_angles`` angles times ``n_offsets^2``
offsets (fractions of the two lattice vectors), then ``refine`` rounds of a
3 x 3 x 3 grid of half the previous step around the incumbent.  Ties keep the
first placement in search order (angle, then offset along a1, then along a2),
and the default placement (0, (0, 0)) is evaluated first, so the search never
returns a worse placement than the default.

Cost: ``1 + n_angles n_offsets^2 + 27 refine`` evaluations (247 by default),
each O(A / l^2) elementwise array operations on the lattice's bounding-box
grid plus O((clearance + 1) P / l) point-segment distances for the vertices
near the boundary (:mod:`equimesh.planar.clearance`; A the area, P the
perimeter), where measuring every grid vertex against every boundary edge
would cost O(A P / l^3) (docs/performance.md, "Problem 2 and the placement
search").
"""

from dataclasses import dataclass

import numpy as np

from .._checks import check_count, check_length
from ..classes import DEFAULT_TOLERANCE, TOP_CLASSES, length_classes
from ..errors import EquimeshError
from .insertion import DEFAULT_ENGINE
from .lattice import kept_vertices, lattice_basis, lattice_triangle_masks
from .limits import MAX_NODES, check_max_nodes, check_size, planar_estimate
from .polygon import as_polygon
from .strip import check_clearance, strip_estimate, uniform_triangulation

#: Beyond the paper (docs/decisions.md, "The lattice placement search"): the most
#: placements one search may evaluate,
#: ``1 + n_angles n_offsets^2 + 27 refine`` (16 times the default 247).  Each
#: evaluation builds the lattice grid (bounded through ``max_nodes``), so this
#: bounds the search (``n_offsets=10**6`` would ask for 1.2e13 evaluations).
#: Test: tests/planar/test_placement.py::test_placement_search_is_bounded.
MAX_EVALUATIONS = 4096


@dataclass(frozen=True)
class Placement:
    """A lattice placement and its objective.

    ``angle`` in degrees, ``offset`` the position of lattice vertex (0, 0);
    ``lattice_edges`` the number of edges of K at this placement,
    ``default_lattice_edges`` the same at angle 0, offset (0, 0);
    ``evaluations`` how many placements were tried.
    """

    angle: float
    offset: tuple
    lattice_edges: int
    default_lattice_edges: int
    evaluations: int

    @property
    def gain(self):
        """Relative gain in lattice edges over the default placement.

        0 when neither placement has a lattice edge, ``inf`` when only the
        default has none.
        """
        if self.default_lattice_edges == 0:
            return 0.0 if self.lattice_edges == 0 else float("inf")
        return self.lattice_edges / self.default_lattice_edges - 1.0


def lattice_edge_count(poly, l, angle, offset, clearance=1.0):
    """Number of edges of the kept lattice part K (all in G1) for one placement."""
    *_, kept = kept_vertices(poly, l, angle, offset, clearance)
    up, down = lattice_triangle_masks(kept)
    # Edge (i,j)-(i+1,j): up(i,j) or down(i,j-1).  Edge (i,j)-(i,j+1): up(i,j)
    # or down(i-1,j).  Edge (i+1,j)-(i,j+1): up(i,j) or down(i,j).
    pad_j = np.pad(down, ((0, 0), (1, 0)))[:, :-1]
    pad_i = np.pad(down, ((1, 0), (0, 0)))[:-1, :]
    return int(np.count_nonzero(up | pad_j) + np.count_nonzero(up | pad_i) + np.count_nonzero(up | down))


def best_lattice_placement(
    vertices, l, *, holes=None, clearance=1.0, n_angles=12, n_offsets=4, refine=2, max_nodes="default"
):
    """Search the lattice angle and offset that maximise the number of G1 lattice edges.

    Parameters
    ----------
    vertices : (n, 2) array_like
        The polygon (simple).
    l : float
        Lattice spacing.
    holes : list of (k, 2) array_like, optional
        Openings, as in :func:`equimesh.uniform_triangulation`; the lattice
        is kept ``clearance * l`` from them too.
    clearance : float
        As in :func:`equimesh.uniform_triangulation`.
    n_angles, n_offsets, refine : int
        Coarse grid size (positive) and number of refinement rounds (>= 0);
        at most :data:`MAX_EVALUATIONS` placements in all.
    max_nodes : int, None or "default"
        The size guard of :func:`equimesh.uniform_triangulation` with the
        default engine (the lattice grid each evaluation builds is bounded
        through it); None for no limit.

    Returns
    -------
    Placement
        Pass ``angle`` and ``offset`` to :func:`equimesh.uniform_triangulation`.
    """
    l = check_length(l)
    clearance = check_clearance(clearance)
    n_angles = check_count(n_angles, "n_angles", 1)
    n_offsets = check_count(n_offsets, "n_offsets", 1)
    refine = check_count(refine, "refine", 0)
    planned = 1 + n_angles * n_offsets**2 + 27 * refine
    if planned > MAX_EVALUATIONS:
        raise EquimeshError(
            f"n_angles = {n_angles}, n_offsets = {n_offsets} and refine = {refine} ask for {planned} placements "
            f"(1 + n_angles n_offsets^2 + 27 refine), more than {MAX_EVALUATIONS}; use smaller counts"
        )
    max_nodes = check_max_nodes(max_nodes, MAX_NODES[DEFAULT_ENGINE])
    poly = as_polygon(vertices, l, holes)
    check_size(*planar_estimate(poly, l, strip_estimate(poly, l, clearance), DEFAULT_ENGINE), max_nodes, l)
    evaluations = 0

    def score(angle, frac):
        nonlocal evaluations
        evaluations += 1
        offset = np.asarray(frac) @ lattice_basis(l, angle)
        return lattice_edge_count(poly, l, angle, offset, clearance)

    default = score(0.0, (0.0, 0.0))
    best = (default, 0.0, (0.0, 0.0))
    angles = 60.0 * np.arange(n_angles) / n_angles
    fracs = np.arange(n_offsets) / n_offsets
    for angle in angles:
        for fi in fracs:
            for fj in fracs:
                s = score(angle, (fi, fj))
                if s > best[0]:
                    best = (s, float(angle), (float(fi), float(fj)))
    da, df = 60.0 / n_angles, 1.0 / n_offsets
    for _ in range(refine):
        da, df = da / 2, df / 2
        _, a0, (f0, g0) = best
        for angle in (a0 - da, a0, a0 + da):
            for fi in (f0 - df, f0, f0 + df):
                for fj in (g0 - df, g0, g0 + df):
                    s = score(angle % 60.0, (fi % 1.0, fj % 1.0))
                    if s > best[0]:
                        best = (s, float(angle % 60.0), (float(fi % 1.0), float(fj % 1.0)))
    s, angle, frac = best
    offset = tuple(float(x) for x in np.asarray(frac) @ lattice_basis(l, angle))
    return Placement(angle, offset, s, default, evaluations)


#: Beyond the paper (docs/decisions.md, "The placement with the fewest classes"): offsets per lattice vector
#: tried at each candidate angle of :func:`fewest_classes_placement` (a grid of ``CLASS_OFFSETS^2``), and
#: the degrees within which two sides' directions count as one candidate angle.
CLASS_OFFSETS = 3
CLASS_ANGLE = 1.0
#: A vertex where the polygon turns by at least this many degrees is a corner of
#: :func:`fewest_classes_placement`'s sides (the corners of a roof, not the small
#: turns of a resampled curve).
CLASS_CORNER_TURN = 30.0


def fewest_classes_placement(
    vertices,
    l,
    *,
    holes=None,
    boundary_spacing=1.5,
    boundary="equal",
    tolerance=DEFAULT_TOLERANCE,
    engine=DEFAULT_ENGINE,
    start=None,
):
    """The lattice placement whose Problem 2 mesh has the fewest length classes (beyond the paper).

    A lattice line parallel to a side makes the strip along it periodic, so
    its members repeat (and a lattice line at 90 degrees to a side is one at
    30 degrees to its own, every two rows).  The candidates are the
    directions of the polygon's sides from corner to corner (the vertices
    where it turns by at least :data:`CLASS_CORNER_TURN` degrees: a curved
    side resampled into many short edges is one side), each modulo 60 and
    counted once within :data:`CLASS_ANGLE` degrees, in the order of the sides
    from the ring's first corner, each with ``CLASS_OFFSETS^2`` offsets, after
    ``start`` (a :class:`Placement`, e.g.
    :func:`best_lattice_placement`'s; angle 0 at the origin by default).  Each
    is meshed by :func:`equimesh.uniform_triangulation`, with no node limit of
    its own (the caller's size guard bounds the search), and scored by its
    length classes at ``tolerance`` (:func:`equimesh.classes.length_classes`),
    then by the share of its members in the
    :data:`~equimesh.classes.TOP_CLASSES` largest; ties keep the first.  A
    candidate that Problem 2 refuses is skipped, ``start``'s refusal raised.

    Returns
    -------
    Placement
        ``lattice_edges`` is the winner's class count, ``default_lattice_edges``
        the start's, ``evaluations`` the placements meshed.
    """
    l = check_length(l)
    ring = np.asarray(vertices, dtype=float)
    before, after = ring - np.roll(ring, 1, axis=0), np.roll(ring, -1, axis=0) - ring
    turn = np.degrees(
        np.abs(np.arctan2(before[:, 0] * after[:, 1] - before[:, 1] * after[:, 0], np.sum(before * after, axis=1)))
    )
    corner = np.flatnonzero(turn >= CLASS_CORNER_TURN)
    sides = np.roll(ring[corner], -1, axis=0) - ring[corner] if len(corner) > 1 else np.zeros((0, 2))
    angles = []
    for a in np.degrees(np.arctan2(sides[:, 1], sides[:, 0])) % 60.0:
        a = 0.0 if a >= 60.0 - CLASS_ANGLE else a  # within a degree of 60 is 0 (the lattice's symmetry)
        if all(abs(a - b) > CLASS_ANGLE for b in angles):  # none of [59, 60) is left to meet 0 across the wrap
            angles.append(float(a))
    start = start or Placement(0.0, (0.0, 0.0), 0, 0, 0)
    tried = [(start.angle, tuple(start.offset))]
    fracs = np.arange(CLASS_OFFSETS) / CLASS_OFFSETS
    for angle in angles:
        basis = lattice_basis(l, angle)
        tried += [(angle, tuple(float(v) for v in np.array([fi, fj]) @ basis)) for fi in fracs for fj in fracs]
    best, evaluations = None, 0
    for k, (angle, offset) in enumerate(tried):
        try:
            mesh = uniform_triangulation(
                vertices,
                l,
                holes=holes,
                angle=angle,
                offset=offset,
                boundary_spacing=boundary_spacing,
                boundary=boundary,
                engine=engine,
                max_nodes=None,
            )
        except EquimeshError:
            if k == 0:
                raise
            continue
        evaluations += 1
        classes = length_classes(mesh.edge_lengths(), l, tolerance)
        key = (len(classes), -classes.top_share(TOP_CLASSES))
        if best is None or key < best[0]:
            best = (key, angle, offset)
        if k == 0:
            first = len(classes)
    (count, _), angle, offset = best
    return Placement(angle, offset, count, first, evaluations)
