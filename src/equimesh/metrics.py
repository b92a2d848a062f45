"""Edge-length and angle statistics of a mesh (the paper's Table 1 and more).

Table 1 of the paper lists, per edge group (G1 and total), the number of
members and the mean, minimum, maximum and standard deviation D of the member
lengths.  D is the *population* standard deviation (``numpy.std`` with
``ddof=0``); the paper does not say which, and for hundreds of members the two
differ by well under 0.1 %.

Beyond Table 1 the fabrication-oriented figures are: the share of members
within 1 % and 5 % of l, the number of distinct member lengths at a +/-1 %
tolerance (:func:`distinct_lengths`) and the range of triangle angles
(:func:`fabrication_figures`).  ``experiments/table1.py`` builds its two
tables from :func:`table1_row` and :func:`fabrication_figures`.
"""

import numpy as np

from .mesh import G1, edge_lengths

#: Keys of :func:`length_stats`, in the column order of Table 1.
TABLE1_COLUMNS = ("members", "mean", "min", "max", "std")

#: The paper's headings of those columns.
TABLE1_HEADINGS = {
    "members": "no. of members",
    "mean": "mean",
    "min": "min.",
    "max": "max.",
    "std": "std. dev.",
}


def length_stats(lengths):
    """Table 1 columns for one group of members.

    Returns
    -------
    dict
        ``members`` (int), ``mean``, ``min``, ``max`` and ``std`` (population
        standard deviation, ``ddof=0``) as floats; the four are ``nan`` for an
        empty group.
    """
    x = np.asarray(lengths, dtype=float).ravel()
    if x.size == 0:
        return {"members": 0, "mean": np.nan, "min": np.nan, "max": np.nan, "std": np.nan}
    return {
        "members": int(x.size),
        "mean": float(np.mean(x)),
        "min": float(np.min(x)),
        "max": float(np.max(x)),
        "std": float(np.std(x, ddof=0)),
    }


def table1_row(name, lengths):
    """One row of Table 1: ``{"row": name, **length_stats(lengths)}``."""
    return {"row": str(name), **length_stats(lengths)}


#: Keys of :func:`fabrication_figures`, in the column order of ``results/table1_quality.csv``.
FABRICATION_COLUMNS = ("within_1pct", "within_5pct", "distinct_lengths_1pct", "angle_min", "angle_max")


def share_within(lengths, l, rel):
    """Fraction of members whose length is within ``rel * l`` of ``l`` (``|L - l| <= rel l``)."""
    x = np.asarray(lengths, dtype=float).ravel()
    if x.size == 0:
        return np.nan
    return float(np.mean(np.abs(x - l) <= rel * l))


def distinct_lengths(lengths, l, tol=0.01):
    """Number of distinct member lengths needed at a fabrication tolerance of ``+/- tol * l``.

    Definition: the smallest number of nominal lengths ``c_1 .. c_k`` such that
    every member is within ``tol * l`` of one of them; equivalently the fewest
    intervals of width ``2 tol l`` covering all lengths.  Computed greedily,
    which is optimal for covering points on a line: sort the lengths, open an
    interval at the smallest uncovered length ``x`` (nominal length
    ``x + tol l``), let it cover every length ``<= x + 2 tol l``, repeat.
    """
    x = np.sort(np.asarray(lengths, dtype=float).ravel())
    width = 2.0 * tol * l
    count, i = 0, 0
    while i < x.size:
        count += 1
        i = int(np.searchsorted(x, x[i] + width, side="right"))
    return count


def triangle_angles(points, triangles):
    """Interior angles in degrees, (M, 3), angle k at vertex ``triangles[:, k]`` (2D or 3D points)."""
    p = np.asarray(points, dtype=float)
    t = np.asarray(triangles, dtype=np.int64).reshape(-1, 3)
    angles = np.empty(t.shape)
    for k in range(3):
        a, b, c = p[t[:, k]], p[t[:, (k + 1) % 3]], p[t[:, (k + 2) % 3]]
        u, v = b - a, c - a
        cos = np.sum(u * v, axis=1) / (np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1))
        angles[:, k] = np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))
    return angles


def angle_range(points, triangles):
    """``(min, max)`` interior angle in degrees over all triangles."""
    a = triangle_angles(points, triangles)
    return float(a.min()), float(a.max())


def fabrication_figures(lengths, l, points=None, triangles=None):
    """The figures beyond Table 1 for one group of members, keyed by :data:`FABRICATION_COLUMNS`.

    Shares of members within 1 % and 5 % of ``l``, distinct lengths at
    +/-1 % of ``l``, and the angle range of ``triangles`` (``nan`` when no
    triangles are given: a group such as G1 does not form whole triangles).
    """
    lo, hi = (np.nan, np.nan) if triangles is None else angle_range(points, triangles)
    return {
        "within_1pct": share_within(lengths, l, 0.01),
        "within_5pct": share_within(lengths, l, 0.05),
        "distinct_lengths_1pct": distinct_lengths(lengths, l, 0.01),
        "angle_min": lo,
        "angle_max": hi,
    }


def quality_summary(points, triangles, edges, l, groups=None):
    """Table 1 rows (G1 and total) and the fabrication figures of one mesh, as a flat dict.

    Keys: ``g1_<col>`` and ``total_<col>`` for each of :data:`TABLE1_COLUMNS`
    (``g1_*`` only when ``groups``, the edge groups, are given) and
    :data:`FABRICATION_COLUMNS` of all members.
    """
    lengths = edge_lengths(points, edges)
    out = {}
    if groups is not None:
        out.update({f"g1_{k}": v for k, v in length_stats(lengths[np.asarray(groups) == G1]).items()})
    out.update({f"total_{k}": v for k, v in length_stats(lengths).items()})
    out.update(fabrication_figures(lengths, l, points, triangles))
    return out
