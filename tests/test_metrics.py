"""Edge-length statistics (Table 1 columns) and fabrication figures."""

import warnings

import numpy as np
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st
from scipy.spatial import ConvexHull, Delaunay

from equimesh.mesh import single_edges, unique_edges
from equimesh.metrics import (
    COMPARISON_COLUMNS,
    FABRICATION_COLUMNS,
    MEMBER_KINDS,
    SUMMARY_KEYS,
    TABLE1_COLUMNS,
    TABLE1_HEADINGS,
    angle_range,
    classes_by_kind,
    comparison_figures,
    distinct_lengths,
    edge_lengths,
    fabrication_figures,
    fabrication_summary,
    length_stats,
    node_figures,
    quality_summary,
    share_in_bounds,
    share_within,
    sharp_share,
    summary_rows,
    table1_row,
    triangle_angles,
)


def test_length_stats_values_and_population_std():
    s = length_stats([4.0, 5.0, 6.0, 5.0])
    assert s == {"members": 4, "mean": 5.0, "min": 4.0, "max": 6.0, "std": pytest.approx(np.sqrt(0.5))}
    assert tuple(s) == TABLE1_COLUMNS
    assert set(TABLE1_HEADINGS) == set(TABLE1_COLUMNS)
    assert length_stats([5.0])["std"] == 0.0  # ddof = 0: defined for one member


def test_empty_group():
    s = length_stats([])
    assert s["members"] == 0 and all(np.isnan(s[k]) for k in ("mean", "min", "max", "std"))


def test_table1_row():
    row = table1_row("plane (G1)", np.full(774, 5.0))
    assert row == {"row": "plane (G1)", "members": 774, "mean": 5.0, "min": 5.0, "max": 5.0, "std": 0.0}


def test_share_within():
    x = np.array([5.0, 5.04, 5.06, 4.96, 4.7, 5.3])
    assert share_within(x, 5.0, 0.01) == pytest.approx(3 / 6)  # 5.0, 5.04, 4.96
    assert share_within(x, 5.0, 0.05) == pytest.approx(4 / 6)  # and 5.06
    assert np.isnan(share_within([], 5.0, 0.01))


def test_distinct_lengths_examples():
    assert distinct_lengths([], 5.0) == 0
    assert distinct_lengths([5.0] * 10, 5.0) == 1
    assert distinct_lengths([5.0, 5.1], 5.0) == 1  # span 0.1 = 2 % of l: one nominal length 5.05
    assert distinct_lengths([5.0, 5.1001], 5.0) == 2
    assert distinct_lengths([5.0, 5.06, 5.12, 5.18], 5.0) == 2


def test_share_in_bounds_counts_l_and_2l_themselves():
    assert share_in_bounds([5.0, 10.0, 7.0, 4.999, 10.001], 5.0) == pytest.approx(3 / 5)
    assert share_in_bounds([5.0 * (1 - 1e-10)], 5.0) == 1.0  # REL_TOL, as every guarantee
    assert np.isnan(share_in_bounds([], 5.0))


def test_fabrication_summary():
    s = fabrication_summary([5.0, 5.0, 5.02, 5.3, 9.0], 5.0, 0.005)
    assert tuple(s) == SUMMARY_KEYS
    assert s == {
        "members": 5,
        "classes": 3,
        "largest_class_share": 0.6,
        "top10_share": 1.0,
        "min_length": 5.0,
        "max_length": 9.0,
        "within_tolerance": 0.6,
        "angle_min": pytest.approx(np.nan, nan_ok=True),
        "angle_max": pytest.approx(np.nan, nan_ok=True),
        "sharp_share": pytest.approx(np.nan, nan_ok=True),
        "off_catalogue": 0,
    }
    # With a catalogue: 5.0 and 5.02 (within 0.5 % of 5 of 5.0) and 9.0 are stock, 5.3 is off it.
    c = fabrication_summary([5.0, 5.0, 5.02, 5.3, 9.0], 5.0, 0.005, catalogue=[5.0, 9.0])
    assert (c["classes"], c["off_catalogue"], c["largest_class_share"]) == (3, 1, 0.6)
    # With triangles: the angle range, and no joint too sharp.
    t = fabrication_summary([1.0] * 3, 1.0, 0.005, [[0, 0, 0], [1, 0, 0], [0.5, 0.75**0.5, 0]], [[0, 1, 2]])
    assert (t["angle_min"], t["angle_max"], t["sharp_share"]) == (pytest.approx(60.0), pytest.approx(60.0), 0.0)


def test_comparison_figures_of_two_triangles():
    """A unit rhombus of two equilateral triangles: 5 members of length 1, angles 60 degrees."""
    s3 = np.sqrt(3.0)
    points = np.array([[0, 0, 0], [1, 0, 0], [0.5, s3 / 2, 0], [1.5, s3 / 2, 0]])
    f = comparison_figures(points, [[0, 1, 2], [1, 3, 2]], 1.0)
    assert tuple(f) == COMPARISON_COLUMNS
    assert f["members"] == 5 and f["classes_0.5pct"] == 1 and f["length_std"] == pytest.approx(0.0, abs=1e-15)
    assert f["within_0.5pct"] == f["in_l_2l"] == 1.0
    assert f["angle_min"] == pytest.approx(60.0) and f["angle_max"] == pytest.approx(60.0)
    g = comparison_figures(points, [[0, 1, 2], [1, 3, 2]], 1.004)
    assert g["within_0.5pct"] == 1.0 and g["in_l_2l"] == 0.0


def test_angles():
    s3 = np.sqrt(3.0)
    points = np.array([[0, 0, 0], [2, 0, 0], [1, s3, 0], [0, 0, 1]], dtype=float)
    triangles = np.array([[0, 1, 2], [0, 1, 3]])
    a = triangle_angles(points, triangles)
    np.testing.assert_allclose(a[0], 60.0)
    np.testing.assert_allclose(a.sum(axis=1), 180.0)
    assert a[1, 0] == pytest.approx(90.0)
    lo, hi = angle_range(points, triangles)
    assert hi == pytest.approx(90.0) and lo == pytest.approx(np.degrees(np.arctan(0.5)))


def test_quality_summary_keys_and_values():
    s3 = np.sqrt(3.0)
    points = np.array([[0, 0, 0], [5, 0, 0], [2.5, 2.5 * s3, 0], [7.5, 2.5 * s3, 0]])
    triangles = np.array([[0, 1, 2], [1, 3, 2]])
    edges = np.array([[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]])
    groups = np.array([1, 1, 1, 0, 0])
    q = quality_summary(points, triangles, edges, 5.0, groups)
    assert q["g1_members"] == 3 and q["total_members"] == 5
    assert q["within_1pct"] == 1.0 and q["distinct_lengths_1pct"] == 1
    assert q["angle_min"] == pytest.approx(60.0) and q["angle_max"] == pytest.approx(60.0)
    np.testing.assert_allclose(edge_lengths(points, edges), 5.0)


def test_fabrication_figures_of_a_group_without_triangles():
    """A group such as G1 has no triangles of its own: its angle range is nan, the rest is computed."""
    f = fabrication_figures([5.0, 5.04, 5.2], 5.0)
    assert tuple(f) == FABRICATION_COLUMNS
    assert f["within_1pct"] == pytest.approx(2 / 3) and f["within_5pct"] == 1.0
    assert f["distinct_lengths_1pct"] == 2
    assert np.isnan(f["angle_min"]) and np.isnan(f["angle_max"])


def test_node_figures_of_a_hexagon_fan():
    """Six equilateral triangles around a centre: the centre meets six members at 60 to 180 degrees, each rim node
    three members (two rim, one spoke) at 60 to 120, and only the rim is boundary."""
    rim = [[np.cos(a), np.sin(a), 0.0] for a in np.arange(6) * np.pi / 3]
    points = np.array([[0.0, 0.0, 0.0], *rim])
    triangles = np.array([[0, 1 + k, 1 + (k + 1) % 6] for k in range(6)])
    f = node_figures(points, triangles, unique_edges(triangles))
    assert f["boundary"].tolist() == [False] + [True] * 6
    assert f["valence"].tolist() == [6] + [3] * 6
    np.testing.assert_allclose(f["min_angle"], 60.0, atol=1e-12)
    np.testing.assert_allclose(f["max_angle"], [180.0] + [120.0] * 6, atol=1e-12)


def test_node_figures_are_exact_for_collinear_members():
    """Two members on a straight line meet at exactly 180 degrees (atan2, where arccos would lose digits)."""
    points = np.array([[0.0, 0.0, 0.0], [1.0, 1e-9, 0.0], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0]])
    triangles = np.array([[0, 1, 3], [1, 2, 3]])
    f = node_figures(points, triangles, unique_edges(triangles))
    assert f["max_angle"][1] == pytest.approx(180.0 - np.degrees(2e-9), abs=1e-12)


def test_summary_rows():
    """The lines ``equimesh mesh`` prints: lengths 5, 5, 5.02, 5.3, 9 at l = 5 and +-0.5 % (three classes, the
    largest of three members, 5.3 off the stock lengths 5 and 9), a right triangle of legs 2 and 1 (its angle of
    26.6 degrees too sharp a joint) and an equilateral one."""
    lengths = [5.0, 5.0, 5.02, 5.3, 9.0]
    rows = [
        ("members", "5"),
        ("length classes", "3 (every member within +-0.5 % of L of its class's nominal length)"),
        ("in the largest class", "60.0 %"),
        ("in the 10 largest classes", "100.0 %"),
        ("shortest member", "5 (1.0000 L)"),
        ("longest member", "9 (1.8000 L)"),
        ("within +-0.5 % of L", "60.0 %"),
    ]
    assert summary_rows(lengths, 5.0, 0.005) == rows
    points = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, np.sqrt(3.0), 0.0]]
    extra = summary_rows(lengths, 5.0, 0.005, points, [[0, 1, 2], [0, 1, 3]], (0.012, 0.0034), [5.0, 9.0])
    assert extra == [
        *rows,
        ("triangle angles", "26.6 to 90.0 degrees"),
        ("an angle below 30 degrees", "50.0 % of triangles"),
        ("off the surface", "max 0.012, mean 0.0034"),
        ("off the catalogue", "1 members"),
    ]
    assert summary_rows([1.2, 1.3], 1.0, 0.0125)[1:2] == [
        ("length classes", "2 (every member within +-1.25 % of L of its class's nominal length)")
    ]


def test_sharp_share_counts_the_triangles_with_an_angle_below_the_joint_angle():
    """An equilateral triangle, one of 31, 59 and 90 degrees and one of 29, 61 and 90: one of three is too sharp."""
    points = [[0.0, 0.0], [1.0, 0.0], [0.5, np.sqrt(0.75)]]
    for angle in (31.0, 29.0):
        points += [[0.0, 0.0], [1.0, 0.0], [1.0, np.tan(np.radians(angle))]]
    angles = triangle_angles(points, [[0, 1, 2], [3, 4, 5], [6, 7, 8]])
    assert sharp_share(angles) == pytest.approx(1 / 3)
    assert sharp_share(angles[:2]) == 0.0 and sharp_share(angles[2:]) == 1.0
    assert sharp_share([[30.0, 60.0, 90.0]]) == 0.0  # an angle of 30 degrees is not below 30
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no triangle: nan without the mean of nothing
        assert np.isnan(sharp_share(np.zeros((0, 3))))


def _four_triangles(l):
    """Four triangles apart, of sides (in l) 1, 1, 1; 1.008, 1.015 and its hypotenuse; 1, 0.5 and its hypotenuse
    (an angle of atan(1 / 2) = 26.6 degrees); 1, tan(30.5 degrees) and its hypotenuse (30.5 degrees)."""
    s3, t = np.sqrt(3.0), np.tan(np.radians(30.5))
    corners = [
        [(0, 0), (1, 0), (0.5, s3 / 2)],
        [(3, 0), (4.008, 0), (3, 1.015)],
        [(6, 0), (7, 0), (6, 0.5)],
        [(9, 0), (10, 0), (9, t)],
    ]
    points = l * np.array([(x, y, 0.0) for triangle in corners for x, y in triangle])
    ratios = [1, 1, 1, 1.008, 1.015, np.hypot(1.008, 1.015), 1, 0.5, np.hypot(1, 0.5), 1, t, np.hypot(1, t)]
    return points, np.arange(12).reshape(4, 3), np.array(ratios)


def test_comparison_figures_of_four_triangles():
    """Twelve members: five of l, one within 1 % (1.008 l), one within 5 % (1.015 l), two below l.  At +-0.5 % the
    classes are 0.5, 0.589, {1 (five), 1.008}, 1.015 and the three hypotenuses: seven, the largest of six members;
    at +-1 % 1.015 joins the class of l: six.  One triangle of four has an angle below 30 degrees."""
    l = 2.0
    points, triangles, ratios = _four_triangles(l)
    f = comparison_figures(points, triangles.astype(float).tolist(), l)
    assert {k: f[k] for k in ("members", "classes_0.5pct", "classes_1pct")} == {
        "members": 12,
        "classes_0.5pct": 7,
        "classes_1pct": 6,
    }
    shares = ("within_0.5pct", "within_1pct", "within_5pct", "in_l_2l", "largest_0.5pct", "top10_0.5pct")
    assert [f[k] for k in shares] == pytest.approx([5 / 12, 6 / 12, 7 / 12, 10 / 12, 6 / 12, 1.0], rel=1e-15)
    assert f["below_30deg"] == 0.25 and f["length_std"] == pytest.approx(np.std(ratios), rel=1e-12)
    assert f["angle_min"] == pytest.approx(np.degrees(np.arctan(0.5)), rel=1e-12) and f["angle_max"] == 90.0


def test_comparison_figures_count_the_ten_largest_classes():
    """Twelve triangles of one member length each, 1 + k / 50 l (k = 0 to 11): twelve classes of three members,
    the ten largest holding ten twelfths."""
    rim = [(1 + k / 50) * np.array([[0, 0, 0], [1, 0, 0], [0.5, np.sqrt(0.75), 0]]) + [3 * k, 0, 0] for k in range(12)]
    f = comparison_figures(np.concatenate(rim), np.arange(36).reshape(12, 3), 1.0)
    assert (f["classes_0.5pct"], f["largest_0.5pct"]) == (12, 3 / 36) and f["top10_0.5pct"] == pytest.approx(10 / 12)


def test_share_within_counts_its_ends_and_one_member():
    """At l = 4 and 1/4 of l (exact in binary), 5 and 3 are exactly l / 4 from l."""
    assert share_within([5.0, 3.0, 5.5], 4.0, 0.25) == pytest.approx(2 / 3)
    assert share_within([5.0], 5.0, 0.01) == 1.0 and share_within([5.1], 5.0, 0.01) == 0.0


def test_fabrication_summary_at_a_tolerance_and_of_no_member():
    """At +-1 % of l = 5 (width 0.1) 5.0, 5.04 and 5.08 are one class, 5.3 and 9.0 one each; with the catalogue
    5, 9 at +-1 %, 5.0 to 5.05 go to 5 (three), 9.0 to 9, 5.08 and 5.3 off it, two classes of their own (at
    +-0.5 % 5.04 would be off it too)."""
    lengths = [5.0, 5.04, 5.08, 5.3, 9.0, 5.0]
    s = fabrication_summary(lengths, 5.0, 0.01)
    assert (s["classes"], s["largest_class_share"], s["within_tolerance"]) == (3, 4 / 6, 3 / 6)
    c = fabrication_summary(lengths, 5.0, 0.01, catalogue=[5.0, 9.0])
    assert (c["classes"], c["off_catalogue"], c["largest_class_share"]) == (4, 2, 3 / 6)
    empty = fabrication_summary([], 5.0, 0.01)
    assert (empty["members"], empty["classes"], empty["off_catalogue"]) == (0, 0, 0)
    assert all(np.isnan(empty[k]) for k in ("largest_class_share", "top10_share", "min_length", "max_length"))


def test_fabrication_summary_counts_the_ten_largest_classes():
    """Twelve lengths 1 + k / 50 (one class each at +-0.5 %), the first three times: the ten largest classes hold
    12 of 14 members."""
    lengths = [1.0, 1.0, *(1 + np.arange(12) / 50)]
    s = fabrication_summary(lengths, 1.0, 0.005)
    assert (s["classes"], s["top10_share"], s["largest_class_share"]) == (12, pytest.approx(12 / 14), 3 / 14)
    rows = dict(summary_rows(lengths, 1.0, 0.005))
    assert (rows["in the largest class"], rows["in the 10 largest classes"]) == ("21.4 %", "85.7 %")


def test_fabrication_figures_within_5pct():
    f = fabrication_figures([5.0, 5.04, 5.2, 5.3], 5.0)
    assert (f["within_1pct"], f["within_5pct"]) == (0.5, 0.75)


@pytest.mark.parametrize("a, b", [((0.61, 0.73), 3.0), ((0.73, 0.18), -3.0)])
def test_angles_of_flat_triangles_are_0_or_180(a, b):
    """Corners 0, a and b a, on one line: cos of the angle at 0 rounds to +-1.0000000000000002, read as +-1."""
    a = np.array([*a, 0.0])
    angles = triangle_angles(np.array([0 * a, a, b * a]), np.array([[0.0, 1.0, 2.0]]))
    assert angles[0, 0] == (0.0 if b > 0 else 180.0) and np.all(np.isfinite(angles))


def test_node_figures_of_a_hexagon_fan_numbered_from_the_rim():
    """The fan with its centre last, an unused node after it, in the plane: the centre is no boundary node (its
    members are used twice), the unused node meets none."""
    rim = [[np.cos(a), np.sin(a)] for a in np.arange(6) * np.pi / 3]
    points = np.array([*rim, [0.0, 0.0], [5.0, 5.0]])
    triangles = np.array([[6, k, (k + 1) % 6] for k in range(6)])
    f = node_figures(points, triangles, unique_edges(triangles).astype(float))
    assert f["boundary"].dtype == bool and f["boundary"].tolist() == [True] * 6 + [False, False]
    assert f["valence"].tolist() == [3] * 6 + [6, 0]
    np.testing.assert_allclose(f["min_angle"][:7], 60.0, atol=1e-12)
    np.testing.assert_allclose(f["max_angle"][:7], [120.0] * 6 + [180.0], atol=1e-12)
    assert np.isnan(f["min_angle"][7]) and np.isnan(f["max_angle"][7])


def test_node_figures_of_one_triangle_and_of_none():
    """Each corner of an equilateral triangle meets two members at 60 degrees; no node, no figures."""
    points = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, np.sqrt(0.75), 0.0]])
    f = node_figures(points, [[0, 1, 2]], [[0, 1], [0, 2], [1, 2]])
    assert f["valence"].tolist() == [2, 2, 2]
    np.testing.assert_allclose([f["min_angle"], f["max_angle"]], 60.0, atol=1e-12)
    none = node_figures(np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int64), np.zeros((0, 2), dtype=np.int64))
    assert all(len(v) == 0 for v in none.values())


def _grid(n):
    """An n x n grid of unit squares, each split by the diagonal from its lower left corner."""
    points = np.array([[x, y, 0.0] for y in range(n + 1) for x in range(n + 1)])
    a = np.array([j * (n + 1) + i for j in range(n) for i in range(n)])
    return points, np.concatenate([np.column_stack([a, a + 1, a + n + 2]), np.column_stack([a, a + n + 2, a + n + 1])])


def test_classes_by_kind_counts_the_members_and_classes_of_each_kind():
    """3 x 3 squares: 12 members along the outline (length 1), 16 in the strip (8 sides, 8 diagonals), 5 inside (4
    sides, 1 diagonal); the largest class, length 1, holds 8 of the strip's and 4 of the interior's, the members
    within 5 % of l (the diagonals, sqrt(2), are not)."""
    points, triangles = _grid(3)
    assert classes_by_kind(points, triangles, 1.0) == {
        "boundary": (12, 1, 1.0, 1.0),
        "strip": (16, 2, 1.0, 0.5),
        "interior": (5, 2, 1.0, 0.8),
    }
    assert classes_by_kind(points, triangles, 1.0, k=1) == {
        "boundary": (12, 1, 1.0, 1.0),
        "strip": (16, 2, 0.5, 0.5),
        "interior": (5, 2, 0.8, 0.8),
    }
    assert tuple(classes_by_kind(points, triangles, 1.0)) == MEMBER_KINDS


def test_classes_by_kind_reads_the_tolerance():
    """Stretched by 0.4 % along x, the grid's sides are 1 and 1.004 long: one class at 0.5 %, two at 0.1 %."""
    points, triangles = _grid(3)
    points[:, 0] *= 1.004
    assert classes_by_kind(points, triangles, 1.0)["boundary"][1] == 1
    assert classes_by_kind(points, triangles, 1.0, tolerance=0.001)["boundary"][1] == 2
    # The largest class: every side at 0.5 %; at 0.1 % the 12 of length 1 (tied with the 12 of 1.004, the shorter).
    assert classes_by_kind(points, triangles, 1.0, k=1)["boundary"][2] == 1.0
    assert classes_by_kind(points, triangles, 1.0, tolerance=0.001, k=1)["boundary"][2] == 0.5


def test_classes_by_kind_counts_the_members_within_5_percent_of_l():
    """Stretched along x by 1.03 every side of the outline is within 5 % of l, by 1.055 only those along y: half of
    them, whatever the tolerance of the classes."""
    for stretch, near in ((1.03, 1.0), (1.055, 0.5)):
        points, triangles = _grid(3)
        points[:, 0] *= stretch
        for tolerance in (0.005, 0.06):
            assert classes_by_kind(points, triangles, 1.0, tolerance=tolerance)["boundary"][3] == near


def test_classes_by_kind_breaks_ties_to_the_shorter_class():
    """Two triangles ABC, ACD: AB = BC = 1 and DA = AC = sqrt(3) (two classes of 2, one of them the strip's AC), CD =
    1.4; the largest class is the shorter of the two."""
    a, c = np.array([0.0, 0.0]), np.array([1.5, np.sqrt(0.75)])
    r, s, d = np.sqrt(3.0), 1.4, np.sqrt(3.0)
    along = (r**2 - s**2 + d**2) / (2 * d)  # D from A along AC, then to its left
    u = (c - a) / d
    point = a + along * u + np.sqrt(r**2 - along**2) * np.array([-u[1], u[0]])
    points = np.array([a, [1.0, 0.0], c, point])
    out = classes_by_kind(points, [[0, 1, 2], [0, 2, 3]], 1.0, k=1)
    assert out["boundary"] == (4, 3, 0.5, 0.5) and out["strip"] == (1, 1, 0.0, 0.0)
    assert out["interior"][:2] == (0, 0) and np.isnan(out["interior"][2]) and np.isnan(out["interior"][3])


def test_classes_by_kind_of_one_triangle_has_no_strip_or_interior():
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an empty kind is nan without a division by zero
        out = classes_by_kind([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], [[0, 1, 2]], 1.0)
    assert out["boundary"] == (3, 2, 1.0, 2 / 3)
    assert out["strip"][:2] == (0, 0) and np.isnan(out["strip"][2]) and np.isnan(out["strip"][3])
    assert out["interior"][:2] == (0, 0) and np.isnan(out["interior"][2]) and np.isnan(out["interior"][3])


@given(st.lists(st.tuples(st.integers(0, 1000), st.integers(0, 1000)), min_size=8, max_size=40, unique=True))
def test_single_edges_of_a_delaunay_triangulation_are_its_hull(raw):
    """The edges of one triangle of a Delaunay triangulation are the sides of the convex hull (general position
    assumed: skipped where the hull has collinear points); every member is of exactly one kind."""
    points = np.array(raw, dtype=float)
    assume(np.linalg.matrix_rank(points - points[0]) == 2)
    hull = ConvexHull(points, qhull_options="Qc")
    assume(not hull.coplanar.size)
    triangles = Delaunay(points).simplices
    sides = {tuple(sorted(e)) for e in hull.simplices.tolist()}
    assert {tuple(sorted(e)) for e in single_edges(triangles).tolist()} == sides
    kinds = classes_by_kind(points, triangles, 100.0)
    assert kinds["boundary"][0] == len(sides)
    assert sum(members for members, *_ in kinds.values()) == len(unique_edges(triangles))
