"""Edge-length statistics (Table 1 columns) and fabrication figures."""

import numpy as np
import pytest

from equimesh.mesh import unique_edges
from equimesh.metrics import (
    COMPARISON_COLUMNS,
    FABRICATION_COLUMNS,
    SUMMARY_KEYS,
    TABLE1_COLUMNS,
    TABLE1_HEADINGS,
    angle_range,
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
        "min_length": 5.0,
        "max_length": 9.0,
        "within_tolerance": 0.6,
    }


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
