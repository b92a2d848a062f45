"""The lattice placement search of Problem 2 (``planar/placement.py``; docs/decisions.md, "The lattice placement
search").

What must hold: the objective counts the edges of the kept lattice part K
(each edge of a kept triangle once); the search is the documented one,
placement for placement: the default (0, (0, 0)) first, then the coarse grid
of ``n_angles`` angles times ``n_offsets^2`` offsets in order (angle, then
the offset along a1, then along a2), then ``refine`` rounds of the 3 x 3 x 3
grid of half the previous steps around the incumbent (angles mod 60,
fractions mod 1), a placement replacing the incumbent only when strictly
better; the gain is relative to the default; too many placements or too
large a lattice are refused before any work, and the counts are integers.
On generated polygons it is deterministic, never worse than the default in its
objective, a lower bound on the G1 count of the mesh built with it, and fast
enough for the surface pipeline (the time on a ~1,000-edge mesh is printed,
not asserted).
"""

import time

import invariants_uniform as inv
import numpy as np
import pytest
import shapely
import strategies_simple as ss
from hypothesis import given

import equimesh
from equimesh import G1
from equimesh.errors import EquimeshError, InvalidPolygonError, MeshTooLargeError
from equimesh.planar import lattice, placement
from equimesh.planar.placement import Placement, best_lattice_placement, fewest_classes_placement, lattice_edge_count
from equimesh.planar.polygon import as_polygon
from equimesh.testing.generators import rectangle, regular_polygon

SQUARE10 = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]])


@pytest.mark.parametrize(
    "kwargs",
    [{"n_angles": 0}, {"n_offsets": -1}, {"refine": -1}, {"n_angles": 2.5}, {"n_offsets": True}, {"refine": np.nan}],
)
def test_placement_counts_must_be_integers(kwargs):
    name = next(iter(kwargs))
    with pytest.raises(EquimeshError, match=rf"{name} must be an integer of at least"):
        equimesh.best_lattice_placement(SQUARE10, 1.0, **kwargs)


def test_count_messages_show_plain_numbers():
    with pytest.raises(EquimeshError, match=r"n_angles must be an integer of at least 1, got 2\.5$"):
        equimesh.best_lattice_placement(SQUARE10, 1.0, n_angles=np.float64(2.5))


@pytest.mark.parametrize("kwargs", [{"n_offsets": 10**6}, {"refine": 10**9}, {"n_angles": 4096}])
def test_placement_search_is_bounded(kwargs):
    with pytest.raises(EquimeshError, match=r"placements \(1 \+ n_angles n_offsets\^2 \+ 27 refine\), more than 4096"):
        equimesh.best_lattice_placement(SQUARE10, 1.0, **kwargs)


def test_placement_search_may_use_the_whole_budget():
    assert equimesh.best_lattice_placement(SQUARE10, 4.0, n_angles=4095, n_offsets=1, refine=0).evaluations == 4096


SQUARE6 = np.array([[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]])


L_SHAPE = np.array([[0.0, 0.0], [8.0, 0.0], [8.0, 3.5], [3.2, 3.5], [3.2, 7.0], [0.0, 7.0]])


HEXAGON = 6.5 * np.array([[np.cos(a), np.sin(a)] for a in np.radians(np.arange(0.0, 360.0, 60.0) + 10.0)])


HOLE = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])


def part_edges(poly, l, angle, offset, clearance):
    """Edges of the lattice part K, counted from its triangles."""
    tri = lattice.lattice_part(poly, l, angle, offset, clearance).triangles
    return len(np.unique(np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1), axis=0))


def test_objective_by_hand():
    """The lattice part of a 6 l square at offset (0.5, 1): 28 triangles, 14 boundary edges, (3 * 28 + 14) / 2 = 49."""
    assert lattice_edge_count(as_polygon(SQUARE6, 1.0), 1.0, 0.0, (0.5, 1.0)) == 49


@pytest.mark.parametrize(
    "angle, offset, clearance",
    [
        (0.0, (0.0, 0.0), 1.0),
        (17.0, (0.3, 0.8), 1.0),
        (45.0, (1.1, -0.4), 1.5),
        (30.0, (0.0, 0.0), 1.0),
        (59.0, (0.5, 0.5), 2.0),
    ],
)
@pytest.mark.parametrize("vertices, holes", [(L_SHAPE, None), (HEXAGON, [HOLE])], ids=["L", "hexagon with a hole"])
def test_objective_counts_each_edge_of_the_lattice_part_once(vertices, holes, angle, offset, clearance):
    """Every edge of a kept up or down triangle, whichever triangles it borders, counted once."""
    poly = as_polygon(vertices, 1.0, holes)
    assert lattice_edge_count(poly, 1.0, angle, offset, clearance) == part_edges(poly, 1.0, angle, offset, clearance)


def documented_search(score, n_angles, n_offsets, refine):
    """The search as the module documents it, written out, with ``score(angle, fractions)``.

    Returns the best (score, angle, fractions), the default's score and the placements tried, in order.
    """
    tried = []

    def scored(angle, frac):
        tried.append((angle, frac))
        return score(angle, frac)

    default = scored(0.0, (0.0, 0.0))
    best = (default, 0.0, (0.0, 0.0))
    coarse = [
        (60.0 * a / n_angles, (i / n_offsets, j / n_offsets))
        for a in range(n_angles)
        for i in range(n_offsets)
        for j in range(n_offsets)
    ]
    for angle, frac in coarse:
        s = scored(angle, frac)
        best = (s, angle, frac) if s > best[0] else best
    da, df = 60.0 / n_angles, 1.0 / n_offsets
    for _ in range(refine):
        da, df = da / 2.0, df / 2.0
        _, a0, (f0, g0) = best
        for angle in (a0 - da, a0, a0 + da):
            for fi in (f0 - df, f0, f0 + df):
                for fj in (g0 - df, g0, g0 + df):
                    placed = (angle % 60.0, (fi % 1.0, fj % 1.0))
                    s = scored(*placed)
                    best = (s, *placed) if s > best[0] else best
    return best, default, tried


def offset_of(angle, frac, l=1.0):
    """The offset of the placement ``(angle, fractions)``, as the search computes it."""
    return np.asarray(frac) @ lattice.lattice_basis(l, angle)


@pytest.mark.parametrize(
    "vertices, holes, clearance, counts",
    [
        (L_SHAPE, None, 1.0, (3, 2, 2)),
        (L_SHAPE, None, 1.0, (12, 4, 2)),  # the defaults
        (HEXAGON, [HOLE], 1.5, (5, 3, 1)),
        (SQUARE6, None, 1.0, (2, 2, 3)),
    ],
    ids=["L small", "L default", "hexagon with a hole", "square"],
)
def test_search_is_the_documented_one(vertices, holes, clearance, counts):
    """Same best placement, objective, default objective and number of placements as the search written out."""
    n_angles, n_offsets, refine = counts
    poly = as_polygon(vertices, 1.0, holes)
    (s, angle, frac), default, tried = documented_search(
        lambda a, f: lattice_edge_count(poly, 1.0, a, offset_of(a, f), clearance), *counts
    )
    kwargs = {} if counts == (12, 4, 2) else {"n_angles": n_angles, "n_offsets": n_offsets, "refine": refine}
    p = best_lattice_placement(vertices, 1.0, holes=holes, clearance=clearance, **kwargs)
    assert (p.angle, p.lattice_edges, p.default_lattice_edges, p.evaluations) == (angle, s, default, len(tried))
    assert p.offset == tuple(float(x) for x in offset_of(angle, frac))
    assert len(tried) == 1 + n_angles * n_offsets**2 + 27 * refine
    assert type(p.angle) is float and all(type(x) is float for x in p.offset)
    assert s > default  # the search found a better placement than the default in each case


def near(x, target, period):
    """Distance from ``x`` to ``target`` on a circle of ``period``."""
    d = abs(x - target) % period
    return min(d, period - d)


def test_search_visits_the_documented_placements_and_wraps(monkeypatch):
    """An objective peaked at angle 55, fractions (0.8, 0.8) (a stand-in for the lattice count, recorded): the coarse
    grid keeps the default (0, (0, 0)); the first refinement wraps below 0 to (52.5, (0.75, 0.75)), the second
    goes on from there to 56.25.  Every placement is the documented one, in the documented order."""

    def peaked(angle, frac):
        return -round(
            1e6 * (near(angle, 55.0, 60.0) ** 2 + near(frac[0], 0.8, 1.0) ** 2 + near(frac[1], 0.8, 1.0) ** 2)
        )

    seen = []

    def recorded(poly, l, angle, offset, clearance):
        seen.append((angle, tuple(offset), clearance))
        frac = offset @ np.linalg.inv(lattice.lattice_basis(l, angle))
        return peaked(angle, frac)

    monkeypatch.setattr(placement, "lattice_edge_count", recorded)
    (s, angle, frac), default, tried = documented_search(peaked, 4, 2, 2)
    assert (angle, frac) == (56.25, (0.75, 0.75))
    p = best_lattice_placement(SQUARE6 * 0.5, 0.5, clearance=1.25, n_angles=4, n_offsets=2, refine=2)
    assert seen == [(a, tuple(offset_of(a, f, 0.5)), 1.25) for a, f in tried]
    expected = (56.25, tuple(float(x) for x in offset_of(56.25, frac, 0.5)), default, 71)
    assert (p.angle, p.offset, p.default_lattice_edges, p.evaluations) == expected


def test_search_at_another_length():
    """At l = 2.5 (the L and its answer scaled by 2.5): the same angle, the offset scaled."""
    a = best_lattice_placement(L_SHAPE, 1.0, n_angles=3, n_offsets=2, refine=1)
    b = best_lattice_placement(L_SHAPE * 2.5, 2.5, n_angles=3, n_offsets=2, refine=1)
    assert (a.angle, a.lattice_edges, a.default_lattice_edges) == (b.angle, b.lattice_edges, b.default_lattice_edges)
    np.testing.assert_allclose(np.array(b.offset), 2.5 * np.array(a.offset), rtol=1e-12, atol=1e-12)


def test_ties_keep_the_default():
    """A square of 1.5 l holds no lattice triangle at any placement: every score ties at 0, the default is kept."""
    p = best_lattice_placement(SQUARE6 / 4.0, 1.0, n_angles=2, n_offsets=2, refine=1)
    assert p == Placement(0.0, (0.0, 0.0), 0, 0, 1 + 8 + 27)


@pytest.mark.parametrize(
    "edges, default, gain", [(0, 0, 0.0), (5, 0, float("inf")), (6, 4, 0.5), (4, 4, 0.0), (3, 4, -0.25)]
)
def test_gain_by_hand(edges, default, gain):
    assert Placement(0.0, (0.0, 0.0), edges, default, 1).gain == gain


def test_too_many_placements_are_refused_in_full(monkeypatch):
    """1 + n_angles n_offsets^2 + 27 refine placements: MAX_EVALUATIONS = 4096 of them at most, refused before any
    work (4097 placements would take seconds); with the limit lowered to 10, exactly 10 run."""
    with pytest.raises(EquimeshError) as err:
        best_lattice_placement(SQUARE6, 1.0, n_angles=4096, n_offsets=1, refine=0)
    assert str(err.value) == (
        "n_angles = 4096, n_offsets = 1 and refine = 0 ask for 4097 placements "
        "(1 + n_angles n_offsets^2 + 27 refine), more than 4096; use smaller counts"
    )
    monkeypatch.setattr(placement, "MAX_EVALUATIONS", 10)
    assert best_lattice_placement(SQUARE6, 1.0, n_angles=9, n_offsets=1, refine=0).evaluations == 10
    with pytest.raises(EquimeshError, match=r"^n_angles = 3, n_offsets = 2 and refine = 0 ask for 13 placements"):
        best_lattice_placement(SQUARE6, 1.0, n_angles=3, n_offsets=2, refine=0)
    with pytest.raises(EquimeshError, match=r"^n_angles = 1, n_offsets = 1 and refine = 1 ask for 29 placements"):
        best_lattice_placement(SQUARE6, 1.0, n_angles=1, n_offsets=1, refine=1)


def test_a_lattice_too_large_is_refused_before_any_work(monkeypatch):
    """The size guard of the default engine, before any placement is scored: max_nodes 10 refuses a 6 l square
    (about 55 nodes, the message in full), and by default (10^6 nodes) a 6 x 6 square at l = 0.005 (1.67e6); None
    lifts it; a polygon wider than MAX_EXTENT l is refused as such, not by the size guard."""
    calls = []
    monkeypatch.setattr(placement, "lattice_edge_count", lambda *a: calls.append(a) or 0)
    with pytest.raises(MeshTooLargeError) as err:
        best_lattice_placement(SQUARE6, 1.0, max_nodes=10)
    assert str(err.value) == (
        "l = 1.0 would need about 54.6 nodes in the polygon, more than max_nodes = 10; use a larger "
        "l or raise max_nodes (--max-nodes on the command line; None for no limit)"
    )
    with pytest.raises(
        MeshTooLargeError,
        match=r"^l = 0\.005 would need about 1\.67e\+06 nodes in the polygon, more than "
        r"max_nodes = 1000000;",
    ):
        best_lattice_placement(SQUARE6, 0.005)
    with pytest.raises(InvalidPolygonError, match="^polygon spans 196608.0 = 196608.0 l, more than the 65536 l"):
        best_lattice_placement(SQUARE6 * 2.0**15, 1.0, max_nodes=None)
    assert calls == []
    assert best_lattice_placement(SQUARE6, 1.0, max_nodes=None, n_angles=1, n_offsets=1, refine=0).evaluations == 2
    assert [c[4] for c in calls] == [1.0, 1.0]


@pytest.mark.parametrize(
    "name, kwargs, message",
    [
        ("clearance", {"clearance": 0.5}, "clearance must be at least 1"),
        ("n_angles", {"n_angles": 0}, "n_angles must be an integer of at least 1, got 0"),
        ("n_offsets", {"n_offsets": 0}, "n_offsets must be an integer of at least 1, got 0"),
        ("refine", {"refine": -1}, "refine must be an integer of at least 0, got -1"),
    ],
)
def test_bad_arguments_are_refused(name, kwargs, message):
    with pytest.raises(EquimeshError, match="^" + message):
        best_lattice_placement(SQUARE6, 1.0, **kwargs)
    if name in ("n_angles", "n_offsets"):  # 1 is allowed
        assert (
            best_lattice_placement(SQUARE6, 1.0, **{"n_angles": 1, "n_offsets": 1, "refine": 0, name: 1}).evaluations
            == 2
        )
    if name == "refine":
        assert best_lattice_placement(SQUARE6, 1.0, n_angles=1, n_offsets=1, refine=0).evaluations == 2


#: Polygons of the property tests: the search costs ~250 lattice evaluations.
MAX_AREA = 400.0


def lattice_part_edges(mesh):
    """Edges of the lattice part K of a mesh (edges of its all-G1 triangles)."""
    tri = mesh.triangles[inv.lattice_mask(mesh)]
    if not len(tri):
        return 0
    return len(np.unique(np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1), axis=0))


@given(ss.cases(MAX_AREA))
def test_placement_deterministic_and_never_worse(case):
    """Same input, same placement; its objective is at least the default placement's, which it reports exactly."""
    vertices, l = case
    a = equimesh.best_lattice_placement(vertices, l)
    b = equimesh.best_lattice_placement(vertices.copy(), l)
    assert a == b
    assert a.lattice_edges >= a.default_lattice_edges
    assert a.gain >= 0.0
    poly = as_polygon(vertices)
    assert a.default_lattice_edges == lattice_edge_count(poly, l, 0.0, (0.0, 0.0))
    assert a.lattice_edges == lattice_edge_count(poly, l, a.angle, a.offset)
    assert 0.0 <= a.angle < 60.0


@given(ss.cases(MAX_AREA))
def test_placement_objective_is_a_lower_bound_on_g1(case):
    """The objective (edges of K) equals the edges of K in the mesh and is at most its G1 count; the mesh is valid."""
    vertices, l = case
    p = equimesh.best_lattice_placement(vertices, l)
    mesh = equimesh.uniform_triangulation(vertices, l, angle=p.angle, offset=p.offset)
    assert p.lattice_edges == lattice_part_edges(mesh)
    assert p.lattice_edges <= int(np.count_nonzero(mesh.edge_groups == G1))
    inv.check_theorem3(mesh, l)
    inv.check_triangulation(mesh, vertices, l)


def test_placement_runtime_on_a_1000_edge_mesh(record_property):
    """Runtime of the search on a polygon whose mesh has ~1,000 edges (printed, not asserted)."""
    vertices = rectangle(18.0, 18.0)
    start = time.perf_counter()
    p = equimesh.best_lattice_placement(vertices, 1.0)
    seconds = time.perf_counter() - start
    default = equimesh.uniform_triangulation(vertices, 1.0)
    best = equimesh.uniform_triangulation(vertices, 1.0, angle=p.angle, offset=p.offset)
    g1_default, g1_best = (int(np.count_nonzero(m.edge_groups == G1)) for m in (default, best))
    record_property("placement_seconds", seconds)
    print(
        f"best_lattice_placement on an 18x18 square ({len(default.edges)} mesh edges): {seconds:.3f} s, "
        f"{p.evaluations} placements, G1 {g1_default} -> {g1_best} (gain {p.gain:+.1%} in lattice edges)"
    )
    assert 800 <= len(default.edges) <= 1300
    assert g1_best >= p.lattice_edges >= p.default_lattice_edges


def test_gain_when_no_lattice_triangle_fits():
    """A polygon too small for any lattice triangle: the reported gain is 0, not -100%."""
    p = equimesh.best_lattice_placement(rectangle(1.5, 1.5), 1.0)
    assert p.lattice_edges == p.default_lattice_edges == 0
    assert p.gain == 0.0


def test_search_builds_the_region_once(monkeypatch):
    """Every evaluation of a search measures against the same shapely region (``Polygon.region``, built once)."""
    built = []
    monkeypatch.setattr(shapely, "Polygon", lambda *a: built.append(a) or shapely.geometry.Polygon(*a))
    equimesh.best_lattice_placement(regular_polygon(6, 6.0), 1.0, n_angles=2, n_offsets=2, refine=1)
    assert len(built) == 1


def test_fewest_classes_placement_is_never_worse_than_its_start():
    """The search tries its start first and keeps it on ties: the winner's classes are at most the start's, and
    the lattice lines of the winner run along a side of the rectangle (angle 0 or 30 modulo 60)."""
    box = [[0.0, 0.0], [13.7, 0.0], [13.7, 9.3], [0.0, 9.3]]
    start = best_lattice_placement(box, 1.0)
    found = fewest_classes_placement(box, 1.0, start=start)
    assert found.lattice_edges <= found.default_lattice_edges and found.evaluations == 1 + 2 * 9
    mesh = equimesh.uniform_triangulation(box, 1.0, angle=found.angle, offset=found.offset)
    assert len(equimesh.length_classes(mesh.edge_lengths(), 1.0)) == found.lattice_edges
    assert found == fewest_classes_placement(box, 1.0, start=start)  # deterministic


def test_fewest_classes_placement_scores_the_boundary_it_is_given():
    """With ``boundary="lattice"`` every candidate is meshed with Step 2 in phase with its lattice: the winner's
    count is that of its phased mesh (fewer than the equal parts' on this rectangle)."""
    box = [[0.0, 0.0], [13.7, 0.0], [13.7, 9.3], [0.0, 9.3]]
    equal, phased = (fewest_classes_placement(box, 1.0, boundary=b) for b in ("equal", "lattice"))
    mesh = equimesh.uniform_triangulation(box, 1.0, angle=phased.angle, offset=phased.offset, boundary="lattice")
    assert len(equimesh.length_classes(mesh.edge_lengths(), 1.0)) == phased.lattice_edges < equal.lattice_edges


def test_fewest_classes_placement_takes_the_sides_between_corners(monkeypatch):
    """A rectangle turned by 20 degrees whose sides carry vertices of their own (a resampled outline): its sides
    between the corners (turns of at least CLASS_CORNER_TURN) give the two candidate angles, 20 and 110 modulo 60
    = 50, each with CLASS_OFFSETS^2 offsets after the start; the winner's lattice runs along one of them."""
    turn = np.radians(20.0)
    rotation = np.array([[np.cos(turn), np.sin(turn)], [-np.sin(turn), np.cos(turn)]])
    ring = [(0, 0), (4.5, 0), (9, 0), (13.7, 0), (13.7, 3.1), (13.7, 6.2), (13.7, 9.3), (7, 9.3), (0, 9.3), (0, 4.6)]
    box = np.array(ring, dtype=float) @ rotation
    found = fewest_classes_placement(box, 1.0)
    assert found.evaluations == 1 + 2 * placement.CLASS_OFFSETS**2
    assert found.angle == 0.0 or min(abs(found.angle - a) for a in (20.0, 50.0)) <= 1e-9
    tried = []
    real = placement.uniform_triangulation

    def spy(vertices, l, **options):
        tried.append(round(options["angle"] % 60.0, 9))
        return real(vertices, l, **options)

    monkeypatch.setattr(placement, "uniform_triangulation", spy)
    fewest_classes_placement(box, 1.0)
    assert sorted(set(tried)) == [0.0, 20.0, 50.0] and tried.count(20.0) == tried.count(50.0) == 9


BOX = [[0.0, 0.0], [13.7, 0.0], [13.7, 9.3], [0.0, 9.3]]


def scripted(monkeypatch, keys, refused=()):
    """Stand-ins for Problem 2 and the classes inside ``fewest_classes_placement``: the k-th mesh asked for is refused
    if k is in ``refused``, else its classes are ``keys[k]`` (count, share in the ten largest); the placements asked
    for, in order."""
    asked = []

    class Mesh:
        def __init__(self, k):
            self.k = k

        def edge_lengths(self):
            return self.k

    class Classes:
        def __init__(self, count, share):
            self.count, self.share = count, share

        def __len__(self):
            return self.count

        def top_share(self, k=placement.TOP_CLASSES):
            return self.share if k == placement.TOP_CLASSES else 1.0

    def triangulate(vertices, l, **options):
        asked.append((options["angle"], tuple(options["offset"])))
        if len(asked) - 1 in refused:
            raise InvalidPolygonError("refused")
        return Mesh(len(asked) - 1)

    monkeypatch.setattr(placement, "uniform_triangulation", triangulate)
    monkeypatch.setattr(placement, "length_classes", lambda k, l, tolerance: Classes(*keys[k]))
    return asked


def test_fewest_classes_placement_keeps_the_first_of_the_fewest_classes_then_the_largest_share(monkeypatch):
    """Of the rectangle's 19 placements (the start, then 9 offsets at 0 degrees, its first side's direction, and 9
    at 30, its second's) the third, fourth
    and fifth have the fewest classes, the fourth and fifth the largest share among those: the fourth wins, and
    the counts are its classes and the start's."""
    keys = [(5, 0.8), (6, 1.0), (4, 0.7), (4, 0.9), (4, 0.9)] + [(6, 1.0)] * 14
    asked = scripted(monkeypatch, keys)
    found = fewest_classes_placement(BOX, 1.0)
    assert len(asked) == 19 and asked[3] != asked[4]
    assert [angle for angle, _ in asked[1:]] == [0.0] * 9 + [30.0] * 9  # the sides in turn from the first corner
    assert ((found.angle, tuple(found.offset)), found.lattice_edges) == (asked[3], 4)
    assert (found.default_lattice_edges, found.evaluations) == (5, 19)


def test_fewest_classes_placement_skips_a_refused_candidate_and_raises_the_starts_refusal(monkeypatch):
    """A candidate that Problem 2 refuses is skipped and the search goes on to the last one, which wins; the
    start's refusal is raised."""
    keys = [(5, 0.8)] * 18 + [(3, 0.5)]
    asked = scripted(monkeypatch, keys, refused=(1,))
    found = fewest_classes_placement(BOX, 1.0)
    assert (found.angle, tuple(found.offset)) == asked[18] and (found.lattice_edges, found.evaluations) == (3, 18)
    scripted(monkeypatch, keys, refused=(0,))
    with pytest.raises(InvalidPolygonError, match="refused"):
        fewest_classes_placement(BOX, 1.0)


def test_fewest_classes_placement_meshes_past_problem_2s_node_limit(monkeypatch):
    """The search is itself bounded by its caller's size guard: its meshes are made with no node limit of their own,
    so a limit of 10 nodes for every engine does not refuse the rectangle's."""
    from equimesh.planar import strip

    monkeypatch.setattr(strip, "MAX_NODES", dict.fromkeys(strip.MAX_NODES, 10))
    with pytest.raises(MeshTooLargeError):
        equimesh.uniform_triangulation(BOX, 1.0)
    assert fewest_classes_placement(BOX, 1.0).evaluations == 19


def turned(points, degrees):
    t = np.radians(degrees)
    return np.asarray(points, dtype=float) @ np.array([[np.cos(t), np.sin(t)], [-np.sin(t), np.cos(t)]])


def spied(monkeypatch):
    """Record the options of every Problem 2 mesh ``fewest_classes_placement`` makes (meshed with the fast engine
    whatever it asks for), with each mesh's key (classes at 0.01, minus the share in the ten largest)."""
    calls = []
    real = placement.uniform_triangulation

    def spy(vertices, l, **options):
        mesh = real(vertices, l, **{**options, "engine": "fast"})
        classes = equimesh.length_classes(mesh.edge_lengths(), l, 0.01)
        calls.append({**options, "key": (len(classes), -classes.top_share(10))})
        return mesh

    monkeypatch.setattr(placement, "uniform_triangulation", spy)
    return calls


@pytest.mark.parametrize("degrees", [0.0, 20.0])
def test_fewest_classes_placement_meshes_what_it_is_given(monkeypatch, degrees):
    """A rectangle with an arched top (a curved side: its chord is one candidate) and an opening, turned, at a
    spacing, tolerance and engine of its own: every candidate is meshed with them, the start first (angle 0 at
    the origin), then per candidate angle the nine offsets of a cell in thirds; the winner is the first of the
    fewest classes, then the largest share in the ten largest, and the counts are the classes at that tolerance."""
    x = np.linspace(14.0, 0.0, 9)
    arch = np.column_stack([x, 10.0 + 1.5 * np.sin(np.pi * x / 14.0)])  # from (14, 10) over to (0, 10)
    ring = turned(np.vstack([[(0.0, 0.0), (14.0, 0.0)], arch]), degrees)
    hole = turned([(5.0, 3.0), (9.0, 3.0), (9.0, 6.0), (5.0, 6.0)], degrees)
    calls = spied(monkeypatch)
    found = fewest_classes_placement(ring, 1.0, holes=[hole], boundary_spacing=1.2, tolerance=0.01, engine="reference")
    angles = sorted({degrees % 60.0, (degrees + 90.0) % 60.0})  # the bottom and the arch's chord, the sides
    assert found.evaluations == len(calls) == 1 + 2 * 9
    assert all(c["boundary_spacing"] == 1.2 and c["engine"] == "reference" for c in calls)
    assert all(np.array_equal(c["holes"][0], hole) for c in calls)
    assert calls[0]["angle"] == 0.0 and tuple(calls[0]["offset"]) == (0.0, 0.0)
    assert sorted({round(c["angle"], 9) for c in calls[1:]}) == angles
    for angle in angles:
        basis = lattice.lattice_basis(1.0, angle)
        offsets = [np.linalg.solve(basis.T, c["offset"]) for c in calls[1:] if abs(c["angle"] - angle) < 1e-9]
        thirds = {tuple(np.round(3 * (o % 1.0)).astype(int) % 3) for o in offsets}
        assert len(offsets) == 9 and len(thirds) == 9
    first = min(range(len(calls)), key=lambda k: calls[k]["key"])  # min keeps the first of equal keys
    assert (found.angle, tuple(found.offset)) == (calls[first]["angle"], tuple(calls[first]["offset"]))
    assert (found.lattice_edges, found.default_lattice_edges) == (calls[first]["key"][0], calls[0]["key"][0])


def _arc(first, last, n):
    t = np.linspace(first, last, n)
    return np.column_stack([8.0 * np.cos(t), 8.0 * np.sin(t)])


@pytest.mark.parametrize(
    "ring, angles",
    [
        (_arc(0.0, 2 * np.pi, 17)[:-1], []),
        (np.vstack([[16.0, 0.0], _arc(np.pi / 3, 5 * np.pi / 3, 17)]), []),
        (_arc(0.0, np.pi, 17), [0.0]),
        (
            rectangle(13.7, 9.3) @ np.array([[np.cos(1.0385), np.sin(1.0385)], [-np.sin(1.0385), np.cos(1.0385)]]),
            [0.0, round(np.degrees(1.0385) + 90.0 - 120.0, 9)],
        ),
    ],
    ids=["no corner", "one corner", "two corners", "a side less than a degree short of 60"],
)
def test_fewest_classes_placement_candidates(monkeypatch, ring, angles):
    """A polygon turning by less than CLASS_CORNER_TURN everywhere has no side to align with: only the start is
    meshed; nor has a drop, a disc drawn to a point (one corner: its one side runs from it back to it); a half
    disc has two corners, its diameter and its arc's chord one candidate; a side less than a
    degree short of 60 is the lattice's 0 (its symmetry)."""
    calls = spied(monkeypatch)
    found = fewest_classes_placement(ring, 1.0)
    assert found.evaluations == len(calls) == 1 + 9 * len(angles)
    assert sorted({round(c["angle"], 9) for c in calls[1:]}) == angles
