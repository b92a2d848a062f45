"""Problem 2 at sharp corners (docs/proofs.md, "Sharp corners"): meshed within every theorem, or refused by kind.

Corners below 60 degrees get staggered Step 2 points, a search for short sides and a grid search of the corners
left closer than l.  What must hold: every mesh satisfies every guarantee of Problem 2
(``tests/invariants_uniform.py``); every refusal is one line saying whether no mesh exists (a side shorter than
l, the sector lemma) or the method has no placement (a limit of the paper's method), and each proof is
confirmed by sampling (``tests/corner_sampling.py``).
"""

import math

import invariants_uniform as inv
import numpy as np
import pytest
import strategies_sharp as sss
import strategies_simple as ss
from conditions import exercised
from corner_sampling import at, corners, sampled_chain, sampled_placement
from hypothesis import example, given
from hypothesis import strategies as st

import equimesh
import equimesh.planar.polygon
from equimesh import (
    InvalidPolygonError,
)
from equimesh.planar.boundary.sides import stagger_reach
from equimesh.planar.insertion import ENGINES
from equimesh.testing.shapes import sharp_corner_shape, sharp_dart

H = math.radians(20.0) / 2.0


TIP20 = [[0, 0], [12 * math.cos(H), -12 * math.sin(H)], [18, -6], [18, 6], [12 * math.cos(H), 12 * math.sin(H)]]


# --------------------------------------------------------------------------- the reported corners, by hand


@pytest.mark.parametrize("vertices", [[[0, 0], [10, 0], [10, 2]], TIP20], ids=["11 degrees", "20 degree tip"])
def test_reported_sharp_corners_are_meshed_validly(vertices):
    """Inputs once accepted with invalid meshes (edges of 0.29 l to 0.52 l), then refused: the staggered
    Step 2 now meshes them within every guarantee of Problem 2."""
    inv.assert_problem2_invariants(equimesh.uniform_triangulation(vertices, 1.0), vertices, 1.0)


def test_the_thin_triangle_refused_before_is_meshed_by_the_continued_zigzag():
    """6.3 degrees with sides of 10 and 9.06 l (the staggered points up to K l = 10 l do not fit): the
    stagger continues along the whole short side, odd multiples of l on one side, even on the other."""
    vertices = [[0, 0], [10, 0], [9, 1]]
    mesh = equimesh.uniform_triangulation(vertices, 1.0)
    inv.assert_problem2_invariants(mesh, vertices, 1.0)
    bottom = mesh.points[: mesh.n_boundary][mesh.points[: mesh.n_boundary, 1] == 0.0, 0]
    assert np.array_equal(np.sort(bottom), [0, 1, 3, 5, 7, 9, 10])


def test_a_corner_below_the_proven_side_length_is_placed_by_the_grid_search():
    """5.7 degrees: the staggered Step 2 is proven for sides of K l + l = 12 l (K = ceil(1 / sin 5.7) = 11); with
    sides of 10 and 10.05 l the short-side search finds no placement, the grid search of the corner does
    (docs/proofs.md, "Sharp corners"), and every guarantee of Problem 2 holds."""
    vertices = [[0, 0], [10, 0], [10, 1]]
    inv.assert_problem2_invariants(equimesh.uniform_triangulation(vertices, 1.0), vertices, 1.0)


def test_two_corners_separable_alone_but_not_together_are_refused_naming_both():
    """A thin triangle with corners of 29.4 and 23.07 degrees sharing a side of 4.25 l: each corner alone can be
    separated, the two together cannot (decided jointly on a grid of cells, planar/boundary/chain.py), which the
    message says is a limit of the method, naming both corners and the three sides."""
    tip = [2.1 * np.cos(np.radians(29.4)), 2.1 * np.sin(np.radians(29.4))]
    with pytest.raises(
        InvalidPolygonError,
        match=r"^the corners at vertex 0 at \(0, 0\) \(29.4 degrees\) and vertex 1 at \(4.25, 0\) "
        r"\(23.0697 degrees\) cannot "
        r"meet Lemma 3 \(1\) together for l = 1.0: no split of their sides of 2.1, 4.25, 2.63084273\d* .*not a proof "
        r"that no "
        r"mesh exists",
    ):
        equimesh.uniform_triangulation([[0, 0], [4.25, 0], tip], 1.0)


#: Largest polygon area drawn by the property tests, in units of l^2.
MAX_AREA = 1500.0


# --------------------------------------------------------------------------- generated sharp corners and the proven
# refusals


@given(ss.cases(MAX_AREA, families=["sharp wedge", "sharp rhombus"]))
def test_every_invariant_holds_at_sharp_corners(case):
    """Corners of 10 to 60 degrees with sides at the proven limit of the staggered Step 2 (docs/proofs.md,
    "Sharp corners"): accepted, and every guarantee of Problem 2 holds (Theorem 3 included)."""
    vertices, l = case
    inv.assert_problem2_invariants(equimesh.uniform_triangulation(vertices, l), vertices, l)


def _sector_closer_than_l(vertices, holes, l, samples=40):
    """Sampled, independently of polygon.py: a corner with a side shorter than 2l whose far end is closer than l
    to every point of the sector of radii l to 2l between the corner's sides (the impossibility lemma of
    docs/proofs.md, "Sharp corners")."""
    r, t = np.meshgrid(np.linspace(l, 2.0 * l, samples), np.linspace(0.0, 1.0, samples))
    for ring in inv.rings(vertices, holes):
        for prev, v, nxt in zip(np.roll(ring, 1, axis=0), ring, np.roll(ring, -1, axis=0)):
            u, w = nxt - v, prev - v
            theta = math.atan2(u[0] * w[1] - u[1] * w[0], float(np.dot(u, w))) % (2.0 * math.pi)
            start = math.atan2(u[1], u[0])
            sector = v + np.stack([r * np.cos(start + t * theta), r * np.sin(start + t * theta)], axis=-1)
            for end in (nxt, prev):
                if np.linalg.norm(end - v) < 2.0 * l and np.linalg.norm(sector - end, axis=-1).max() < l:
                    return True
    return False


def _first_points_closer_than_l(vertices, holes, l, samples=40):
    """Sampled, independently of polygon.py: a corner where the first boundary points of its two sides are
    closer than l wherever a split into parts of [l, 2l] puts them (docs/proofs.md, "Sharp corners")."""

    def first(length):
        return np.array([length]) if length < 2.0 * l else np.linspace(l, min(2.0 * l, length - l), samples)

    for ring in inv.rings(vertices, holes):
        for prev, v, nxt in zip(np.roll(ring, 1, axis=0), ring, np.roll(ring, -1, axis=0)):
            u, w = nxt - v, prev - v
            a, b = first(np.linalg.norm(u)), first(np.linalg.norm(w))
            pa = v + a[:, None] * u / np.linalg.norm(u)
            pb = v + b[:, None] * w / np.linalg.norm(w)
            if np.linalg.norm(pa[:, None] - pb[None], axis=2).max() < l:
                return True
    return False


def _no_sampled_placement(vertices, holes, l):
    """Sampled, independently of polygon.py: a corner below 60 degrees whose two sides have no split into parts of
    [l, 2l] (steps of l/8) keeping every two points of different sides l apart (docs/proofs.md, "Sharp corners")."""
    return any(
        theta < math.radians(60.0) and sampled_placement(theta, (a / l, b / l), 1.0) is None
        for theta, a, b in corners(inv.rings(vertices, holes))
    )


def _no_sampled_chain_placement(vertices, holes, l):
    """Sampled, independently of polygon.py: two or more consecutive corners below 60 degrees with no split of
    the sides they share (steps of l/8) for which the first and last corners' other sides can be split too, keeping
    every corner's two sides l apart (docs/proofs.md, "Sharp corners")."""
    for ring in inv.rings(vertices, holes):
        found = list(corners([ring]))
        n = len(found)
        for i in range(n):
            run = 1
            while run < n - 1 and found[(i + run) % n][0] < math.radians(60.0) and found[i][0] < math.radians(60.0):
                run += 1
                chain = [found[(i + k) % n] for k in range(run)]
                thetas = tuple(theta for theta, _, _ in chain)
                lengths = (chain[0][2] / l, *(leaving / l for _, leaving, _ in chain))
                if sampled_chain(thetas, lengths, 1.0) is None:
                    return True
    return False


def _refusal_kind(error):
    """The kind of a refusal at a sharp corner, named by its one-line message."""
    text = str(error)
    assert "\n" not in text and isinstance(error, equimesh.InvalidPolygonError), text
    kinds = {
        "impossible": "no mesh with every edge in [l, 2l] exists",
        "no separation": "cannot meet Lemma 3 (1)",
        "not handled": "is not handled for l",
        "narrow": "is too narrow for l",
    }
    found = [kind for kind, marker in kinds.items() if marker in text]
    assert found, f"unexpected refusal: {text}"
    return found[0]


@pytest.mark.exercised("a short-sided sharp corner is meshed", share=0.5)
@given(sss.sharp_cases())
def test_short_sided_sharp_corners_are_meshed_within_every_theorem_or_refused_by_kind(case):
    """Corners of 10 to 60 degrees with sides from l to past the proven limit (thin triangles, short wedges,
    spikes, dart-shaped holes): a mesh satisfies every guarantee of Problem 2; a refusal is one line saying
    whether it is proven impossible (a side shorter than l, or the sector lemma, confirmed here by sampling)
    or a limit of this method (docs/proofs.md, "Sharp corners")."""
    vertices, holes, l = case
    _meshed_or_refused_by_kind(vertices, holes, l)


def _meshed_or_refused_by_kind(vertices, holes, l):
    """Problem 2 on ``vertices``: every guarantee checked on a mesh; a refusal's kind confirmed by sampling
    (docs/proofs.md, "Sharp corners").  Returns the kind, or "meshed"."""
    try:
        mesh = equimesh.uniform_triangulation(vertices, l, holes=holes or None)
    except equimesh.InvalidPolygonError as error:
        exercised("a short-sided sharp corner is meshed", False)
        kind = _refusal_kind(error)
        if kind == "impossible" and "shorter than l" not in str(error):
            assert _sector_closer_than_l(vertices, holes, l)
        if kind == "no separation":
            confirm = _first_points_closer_than_l if "first boundary points" in str(error) else _no_sampled_placement
            together = "together" in str(error)  # refused jointly (planar/boundary/chain.py)
            assert (_no_sampled_chain_placement if together else confirm)(vertices, holes, l)
        return kind
    exercised("a short-sided sharp corner is meshed", True)
    inv.assert_problem2_invariants(mesh, vertices, l, holes=holes)
    return "meshed"


@given(st.floats(10.0, 59.0), st.floats(10.0, 59.0), st.floats(0.0, 1.0))
@example(29.4, 23.069711979788835, 3.25 / 8.0)  # the triangle of PROVEN_REFUSALS["no joint placement"]
def test_triangles_with_two_sharp_corners_on_one_side_are_meshed_or_refused_with_a_proof(angle_1, angle_2, size):
    """Two corners of 10 to 59 degrees at the ends of a base from l to where they stop sharing any point of it
    (``K_1 l + K_2 l + 3 l``): meshed within every theorem, or refused by kind, a proof confirmed by sampling
    (jointly: planar/boundary/chain.py).
    Rarely "not handled" (docs/proofs.md, "Sharp corners", what is not decided)."""
    base = 1.0 + size * (stagger_reach(angle_1, 1.0) + stagger_reach(angle_2, 1.0) + 2.0)
    a, b = math.radians(angle_1), math.radians(angle_2)
    side = base * math.sin(b) / math.sin(a + b)
    _meshed_or_refused_by_kind(np.array([[0.0, 0.0], [base, 0.0], [side * math.cos(a), side * math.sin(a)]]), [], 1.0)


@given(sss.darts())
@example((sharp_dart(30.0, (30.0, 30.0), 3.5), 1.0))  # the dart of PROVEN_REFUSALS["no chain placement"]
def test_darts_are_meshed_or_refused_with_a_proof(case):
    """Arrowheads with three sharp corners in a row (tip and barbs of 10 to 60 degrees): meshed within every
    theorem, or refused by kind, a proof confirmed by sampling (jointly for the corners in a row:
    planar/boundary/chain.py); none is "not handled" (docs/proofs.md, "Sharp corners")."""
    vertices, l = case
    assert _meshed_or_refused_by_kind(vertices, [], l) != "not handled"


SHARP_EXAMPLES = {
    "6.3-degree triangle": ([[0, 0], [10, 0], [9, 1]], []),
    "0.52-degree triangle": ([[0, 0], [100, 0], [99.5, 0.9]], []),
    "42-degree corner, side 2.85": ([[0, 0], [13.009, 0], [2.108, 1.918]], []),
    "20-degree spike": (sharp_corner_shape("spike", 20.0, stagger_reach(20.0, 1.0) + 2.0, 0.2, 0.5, 0.5)[0], []),
    "15-degree dart hole": sharp_corner_shape("dart hole", 15.0, stagger_reach(15.0, 1.0) + 2.0, 0.3, 0.5, 0.5),
}


@pytest.mark.parametrize("engine", sorted(ENGINES))
@pytest.mark.parametrize("name", sorted(SHARP_EXAMPLES))
def test_both_engines_mesh_short_sided_sharp_corners(name, engine):
    """Sides shorter than the proven limit of the stagger, meshed by the continued or mirrored stagger with
    either insertion engine, every guarantee of Problem 2 checked."""
    vertices, holes = SHARP_EXAMPLES[name]
    mesh = equimesh.uniform_triangulation(vertices, 1.0, holes=holes or None, engine=engine)
    inv.assert_problem2_invariants(mesh, vertices, 1.0, holes=holes)


PROVEN_REFUSALS = {
    # 20 degrees with a side of 1.5 l: that side is one mesh edge and every possible third node of its
    # triangle lies within l of its far end, so no mesh has every edge in [l, 2l]; limit 2 l cos 20.
    "sector lemma": (
        [[0, 0], [6, 0], [6, 3], at(20.0, 1.5)],
        r"^no mesh with every edge in \[l, 2l\] exists for l = 1.0: at the corner at vertex 0 at \(0, 0\) "
        r"\(20 degrees\) edge \(3, 0\) is 1.5 long, .* at least 1.879385242 long",
        _sector_closer_than_l,
    ),
    # 30 degrees with sides of 1.6 and 2.5 l: the first boundary points of the two sides are closer than l
    # wherever they lie (at 1.6, and within [1, 1.5]): Lemma 3 (1) cannot hold, a limit of the method.
    "no separation": (
        [[0, 0], [1.6, 0], at(30.0, 2.5)],
        r"^the corner at vertex 0 at \(0, 0\) \(30 degrees\) cannot meet Lemma 3 \(1\) for l = 1.0: with sides of "
        r"1.6 and 2.5 .* not a proof that no mesh exists.* sides of at least 3.0 are handled",
        _first_points_closer_than_l,
    ),
    # 20 degrees with both sides 3.45 l: each first point can be placed, but no split of the two sides into parts
    # of [l, 2l] keeps them l apart (the relaxation on a grid of cells finds no path): a limit of the method.
    "no placement": (
        [[0, 0], [3.45, 0], at(20.0, 3.45)],
        r"^the corner at vertex 0 at \(0, 0\) \(20 degrees\) cannot meet Lemma 3 \(1\) for l = 1.0: no split of its "
        r"sides "
        r"of 3.45 and 3.45 into parts of \[l, 2l\] .* not a proof that no mesh exists.* sides of at least 4.0 are "
        r"handled",
        _no_sampled_placement,
    ),
    # A dart with tip and barbs of 30 degrees, tip sides 3.5 l: each two corners sharing a side can be separated,
    # the three together cannot (decided jointly on a grid of cells).
    "no chain placement": (
        sharp_dart(30.0, (30.0, 30.0), 3.5).tolist(),
        r"^the corners at vertex 3 at \(3.380740392, 0.9058666579\) \(30 degrees\), vertex 0 at \(0, 0\) \(30 "
        r"degrees\) and "
        r"vertex 1 at .* cannot meet Lemma 3 \(1\) together for l = 1.0: .*\(the middle ones shared\).* at every "
        r"corner .*"
        r"not a proof that no mesh exists",
        _no_sampled_chain_placement,
    ),
    # 29.4 and 23.07 degrees sharing a side of 4.25 l: each corner alone can be separated, both together cannot
    # (no split of the shared side leaves both other sides a split; decided jointly on a grid of cells).
    "no joint placement": (
        [[0, 0], [4.25, 0], at(29.4, 2.1)],
        r"^the corners at vertex 0 at \(0, 0\) \(29.4 degrees\) and vertex 1 at \(4.25, 0\) \(23.0697 degrees\) cannot "
        r"meet "
        r"Lemma 3 \(1\) together for l = 1.0: .* not a proof that no mesh exists",
        _no_sampled_chain_placement,
    ),
}


@pytest.mark.parametrize("name", sorted(PROVEN_REFUSALS))
def test_a_refusal_proven_at_a_corner_says_what_is_proven(name):
    """Each proven refusal names the corner, its angle and the limit, says whether no mesh exists or only no
    Step 2 meets Lemma 3 (1), and the fact is confirmed by sampling, independently of polygon.py."""
    vertices, message, confirm = PROVEN_REFUSALS[name]
    with pytest.raises(equimesh.InvalidPolygonError, match=message):
        equimesh.uniform_triangulation(vertices, 1.0)
    assert confirm(np.array(vertices, dtype=float), [], 1.0)
