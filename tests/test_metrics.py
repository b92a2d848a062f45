"""Edge-length statistics (Table 1 columns) and fabrication figures."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from equimesh.metrics import (
    FABRICATION_COLUMNS,
    TABLE1_COLUMNS,
    TABLE1_HEADINGS,
    angle_range,
    distinct_lengths,
    edge_lengths,
    fabrication_figures,
    length_stats,
    quality_summary,
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


@settings(max_examples=50, deadline=None)
@given(
    seed=st.integers(0, 2**32 - 1),
    n=st.integers(1, 60),
    tol=st.sampled_from([0.005, 0.01, 0.05]),
)
def test_distinct_lengths_is_an_optimal_cover(seed, n, tol):
    """Greedy count k: the interval starts are pairwise > 2 tol l apart (so no cover uses fewer),
    and the k intervals cover every length."""
    l = 5.0
    x = np.sort(np.random.default_rng(seed).uniform(l, 2 * l, size=n))
    k = distinct_lengths(x, l, tol)
    starts, i = [], 0
    while i < n:
        starts.append(x[i])
        i = int(np.searchsorted(x, x[i] + 2 * tol * l, side="right"))
    assert len(starts) == k
    assert np.all(np.diff(starts) > 2 * tol * l)
    centre = np.array(starts) + tol * l
    assert np.all(np.min(np.abs(x[:, None] - centre[None, :]), axis=1) <= tol * l * (1 + 1e-12))


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
