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

:func:`fabrication_summary` is what ``equimesh mesh`` prints after meshing
(length classes at the chosen tolerance, :mod:`equimesh.classes`; the lines
are :func:`summary_rows`, also in its ``--report``), and
:func:`comparison_figures` the one measure of ``experiments/compare_peers.py``,
applied alike to equimesh and to other meshers.  :func:`node_figures` is what a
connector designer asks of each node: on the boundary or not, how many members
meet there and the smallest and largest angle between two of them.
"""

import numpy as np

from .classes import DEFAULT_TOLERANCE, TOP_CLASSES, catalogue_classes, length_classes
from .errors import number
from .mesh import G1, edge_keys, edge_lengths, single_edges, unique_edges
from .tolerance import JOINT_ANGLE, at_least, at_most

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

    The smallest number of nominal lengths such that every member is within
    ``tol * l`` of one of them: the number of classes of
    :func:`equimesh.classes.length_classes`, whose greedy sweep is optimal.
    """
    return len(length_classes(lengths, l, tol))


def share_in_bounds(lengths, l):
    """Fraction of members in [l, 2l] (Theorems 1 and 3), up to :data:`equimesh.tolerance.REL_TOL`."""
    x = np.asarray(lengths, dtype=float).ravel()
    if x.size == 0:
        return np.nan
    return float(np.mean(at_least(x, l) & at_most(x, 2.0 * l)))


#: Keys of :func:`fabrication_summary`, in the order the command line prints them.
SUMMARY_KEYS = (
    "members",
    "classes",
    "largest_class_share",
    "top10_share",
    "min_length",
    "max_length",
    "within_tolerance",
    "angle_min",
    "angle_max",
    "sharp_share",
    "off_catalogue",
)


def fabrication_summary(lengths, l, tolerance=DEFAULT_TOLERANCE, points=None, triangles=None, catalogue=None):
    """What a fabricator asks of a member schedule at a tolerance (beyond the paper), keyed by :data:`SUMMARY_KEYS`.

    Members; length classes (:func:`equimesh.classes.length_classes`, or with
    a catalogue of stock lengths :func:`equimesh.classes.catalogue_classes`);
    the share of members in the largest class and in the
    :data:`~equimesh.classes.TOP_CLASSES` largest; the shortest and longest
    member (``nan`` without members); the share within ``tolerance * l`` of l;
    the smallest and largest triangle angle in degrees and the share of
    triangles with an angle below :data:`~equimesh.tolerance.JOINT_ANGLE`
    (:func:`sharp_share`; ``nan`` without ``triangles``); the members off the
    catalogue (0 without one).
    """
    x = np.asarray(lengths, dtype=float).ravel()
    classes = length_classes(x, l, tolerance) if catalogue is None else catalogue_classes(x, l, catalogue, tolerance)
    angles = None if triangles is None else triangle_angles(points, triangles)
    lo, hi, sharp = (np.nan,) * 3 if angles is None else (float(angles.min()), float(angles.max()), sharp_share(angles))
    return {
        "members": int(x.size),
        "classes": len(classes),
        "largest_class_share": float(classes.count.max() / x.size) if x.size else np.nan,
        "top10_share": classes.top_share(TOP_CLASSES),
        "min_length": float(x.min()) if x.size else np.nan,
        "max_length": float(x.max()) if x.size else np.nan,
        "within_tolerance": share_within(x, l, classes.tolerance),
        "angle_min": lo,
        "angle_max": hi,
        "sharp_share": sharp,
        "off_catalogue": classes.off_catalogue(),
    }


def summary_rows(lengths, l, tolerance=DEFAULT_TOLERANCE, points=None, triangles=None, deviation=None, catalogue=None):
    """:func:`fabrication_summary` as ``(label, text)`` pairs: the summary ``equimesh mesh`` prints and its report
    shows; with ``triangles`` the angle range and the share of triangles with a joint too sharp (:func:`sharp_share`),
    with ``deviation`` (max, mean) the nodes' distance from the surface, with a ``catalogue`` the members off it."""
    s = fabrication_summary(lengths, l, tolerance, points, triangles, catalogue)
    return rows_of_summary(s, l, tolerance, deviation, catalogue)


def rows_of_summary(s, l, tolerance=DEFAULT_TOLERANCE, deviation=None, catalogue=None):
    """The rows of :func:`summary_rows` from figures ``s`` of :func:`fabrication_summary` already computed (at ``l``,
    ``tolerance`` and ``catalogue``): the angle rows where ``s`` has angles."""
    tol = f"+-{100 * tolerance:.3g} %"
    rows = [
        ("members", f"{s['members']}"),
        ("length classes", f"{s['classes']} (every member within {tol} of L of its class's nominal length)"),
        ("in the largest class", f"{100 * s['largest_class_share']:.1f} %"),
        ("in the 10 largest classes", f"{100 * s['top10_share']:.1f} %"),
        ("shortest member", f"{number(s['min_length'])} ({s['min_length'] / l:.4f} L)"),
        ("longest member", f"{number(s['max_length'])} ({s['max_length'] / l:.4f} L)"),
        (f"within {tol} of L", f"{100 * s['within_tolerance']:.1f} %"),
    ]
    if not np.isnan(s["angle_min"]):
        rows.append(("triangle angles", f"{s['angle_min']:.1f} to {s['angle_max']:.1f} degrees"))
        rows.append((f"an angle below {JOINT_ANGLE:g} degrees", f"{100 * s['sharp_share']:.1f} % of triangles"))
    if deviation is not None:
        rows.append(("off the surface", "max {}, mean {}".format(*(number(d) for d in deviation))))
    if catalogue is not None:
        rows.append(("off the catalogue", f"{s['off_catalogue']} members"))
    return rows


#: Keys of :func:`comparison_figures`: the one set of figures every mesher is measured by
#: (``experiments/compare_peers.py``).
COMPARISON_COLUMNS = (
    "members",
    "within_0.5pct",
    "within_1pct",
    "within_5pct",
    "in_l_2l",
    "classes_0.5pct",
    "classes_1pct",
    "largest_0.5pct",
    "top10_0.5pct",
    "length_std",
    "angle_min",
    "angle_max",
    "below_30deg",
)


def comparison_figures(points, triangles, l):
    """Member-length and angle figures of any triangle mesh at target length ``l``, keyed by :data:`COMPARISON_COLUMNS`.

    The members are the unique edges of ``triangles``; ``largest_0.5pct`` and
    ``top10_0.5pct`` are the shares of members in the largest and the
    :data:`~equimesh.classes.TOP_CLASSES` largest classes at +-0.5 %;
    ``length_std`` is relative to l (population standard deviation over l);
    ``below_30deg`` the share of triangles with an angle below 30 degrees (a
    joint that cannot be built, :func:`sharp_share`).
    """
    lengths = edge_lengths(points, unique_edges(triangles))
    angles = triangle_angles(points, triangles)
    classes = length_classes(lengths, l, 0.005)
    return {
        "members": int(lengths.size),
        "within_0.5pct": share_within(lengths, l, 0.005),
        "within_1pct": share_within(lengths, l, 0.01),
        "within_5pct": share_within(lengths, l, 0.05),
        "in_l_2l": share_in_bounds(lengths, l),
        "classes_0.5pct": len(classes),
        "classes_1pct": distinct_lengths(lengths, l, 0.01),
        "largest_0.5pct": float(classes.count.max() / lengths.size),
        "top10_0.5pct": classes.top_share(TOP_CLASSES),
        "length_std": float(np.std(lengths) / l),
        "angle_min": float(angles.min()),
        "angle_max": float(angles.max()),
        "below_30deg": sharp_share(angles),
    }


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


def sharp_share(angles):
    """The share of triangles (rows of ``angles``, :func:`triangle_angles`) with an angle below
    :data:`~equimesh.tolerance.JOINT_ANGLE`: joints too sharp to build (:mod:`equimesh.surface.optimize.joints`)."""
    return float(np.mean(np.asarray(angles).min(axis=1) < JOINT_ANGLE)) if len(angles) else np.nan


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


#: Keys of :func:`node_figures`, in the column order of the node schedule (``equimesh mesh --nodes``).
NODE_COLUMNS = ("boundary", "valence", "min_angle", "max_angle")


#: The kinds of member of :func:`classes_by_kind`.
MEMBER_KINDS = ("boundary", "strip", "interior")


def classes_by_kind(points, triangles, l, tolerance=DEFAULT_TOLERANCE, k=TOP_CLASSES):
    """Where a mesh's length classes go: per kind of member, ``{kind: (members, classes, in_top, near)}``.

    The kinds (:data:`MEMBER_KINDS`): ``boundary``, the members along the
    outline (edges of one triangle); ``strip``, the other members with a node
    on the outline (the spokes of Problem 2's boundary strip, and any chord);
    ``interior``, the rest.  ``classes`` is the fewest classes the kind's
    members need alone at ``tolerance`` (:func:`~equimesh.classes.length_classes`;
    a class two kinds share counts for each), ``in_top`` the share of the
    kind's members in the ``k`` largest classes of the whole mesh (ties to the
    shorter nominal length; ``nan`` for a kind without members): which kind
    keeps the mesh's top-``k`` share below 1.  ``near`` is the share of the
    kind's members within 5 % of l (``nan`` likewise): how many lie near l,
    where a mesh's largest classes are when most of its members are near l;
    ``k`` classes cover lengths spanning at most ``2 k tolerance`` l in all
    (0.1 l for the ten largest at 0.5 %), so a kind whose lengths spread over
    [l, 2l] has most of its members outside them unless its lengths repeat.
    """
    edges = unique_edges(triangles)
    lengths = edge_lengths(np.asarray(points, dtype=float), edges)
    outline = single_edges(triangles)
    keys, n = edge_keys(edges)
    along = np.isin(keys, edge_keys(outline, n)[0])
    kind = np.where(along, 0, np.where(np.isin(edges, outline).any(axis=1), 1, 2))
    classes = length_classes(lengths, l, tolerance)
    top = np.isin(classes.member_class, classes.largest(k))
    out = {}
    for index, name in enumerate(MEMBER_KINDS):
        mine = kind == index
        count = int(np.count_nonzero(mine))
        share = np.count_nonzero(top[mine]) / count if count else np.nan
        near = share_within(lengths[mine], l, 0.05)
        out[name] = (count, len(length_classes(lengths[mine], l, tolerance)), share, near)
    return out


def node_figures(points, triangles, edges):
    """What a connector designer needs at each node, keyed by :data:`NODE_COLUMNS`, one (N,) array each.

    ``boundary``: the node lies on a boundary edge (an edge of one triangle
    only); ``valence``: the members (``edges``) meeting at the node;
    ``min_angle``, ``max_angle``: the smallest and largest angle in degrees
    between two members meeting at the node, over every pair of them (``nan``
    where fewer than two meet), as ``atan2(|a x b|, a . b)``, exact near 0 and
    180 degrees where ``arccos`` is not (docs/decisions.md, "Angles between members at a node").
    """
    p = np.asarray(points, dtype=float)
    p = np.column_stack([p, np.zeros(len(p))]) if p.shape[1] == 2 else p
    e = np.asarray(edges, dtype=np.int64).reshape(-1, 2)
    n = len(p)
    boundary = np.zeros(n, dtype=bool)
    boundary[single_edges(triangles).ravel()] = True
    valence = np.bincount(e.ravel(), minlength=n)
    # Every member twice, as a vector leaving each of its nodes, grouped by node: the pairs of members at a node
    # are the pairs (k, k + a) of one group, for a = 1 up to the largest valence minus one.
    d = p[e[:, 1]] - p[e[:, 0]]
    at, vectors = np.concatenate([e[:, 0], e[:, 1]]), np.concatenate([d, -d])
    order = np.argsort(at, kind="stable")
    at, vectors = at[order], vectors[order]
    lo, hi = np.full(n, np.inf), np.full(n, -np.inf)
    for a in range(1, int(valence.max(initial=0))):
        pair = at[a:] == at[:-a]
        u, v = vectors[:-a][pair], vectors[a:][pair]
        angle = np.degrees(np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.sum(u * v, axis=1)))
        np.minimum.at(lo, at[a:][pair], angle)
        np.maximum.at(hi, at[a:][pair], angle)
    lo[valence < 2] = hi[valence < 2] = np.nan
    return {"boundary": boundary, "valence": valence, "min_angle": lo, "max_angle": hi}
