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
from ..errors import EquimeshError
from .insertion import DEFAULT_ENGINE
from .lattice import kept_vertices, lattice_basis, lattice_triangle_masks
from .limits import MAX_NODES, check_max_nodes, check_size, planar_estimate
from .polygon import as_polygon
from .strip import check_clearance, strip_estimate

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
