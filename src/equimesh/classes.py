"""Length classes: the fewest nominal member lengths that fit every member within a tolerance (beyond the paper).

A roof or a space frame is cheaper the fewer *different* members it has.  The
paper's G1 group (Section 4) is one such class; after the optimisation the
other members still have many lengths.  At a fabrication tolerance ``tol``
(relative to the target length l, e.g. 0.5 %), a *length class* is a set of
members that can all be cut to one nominal length c, i.e. every member length
L in it has ``|L - c| <= tol * l``.  :func:`length_classes` groups the members
into the fewest such classes (the proof of optimality is in its docstring);
:func:`equimesh.metrics.distinct_lengths` is their count.

The tolerance is given as a fraction of l, or as a string with a percent sign
(:func:`check_tolerance`); it must lie in ``(0, MAX_TOLERANCE)``.

A *catalogue* is a caller's list of stock lengths in [l, 2l] (:func:`check_catalogue`):
:func:`catalogue_classes` puts every member within the tolerance of a stock
length into that stock length's class and groups the rest (off the
catalogue) by :func:`length_classes`.
"""

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ._checks import check_length, number_text, real_array, real_number
from .errors import EquimeshError, InvalidCatalogueError, InvalidToleranceError, number
from .tolerance import at_least, at_most

#: Upper limit (exclusive) of the relative tolerance: at 50 % of l a class of
#: width ``2 tol l = l`` would hold every member of [l, 2l] (Theorems 1 and 3)
#: in one or two classes, which is no fabrication tolerance any more.
MAX_TOLERANCE = 0.5

#: Tolerance used when none is given (the command line's ``--tolerance``):
#: +/-0.5 % of l, the "exactly l" share reported by the comparison with other meshers.
DEFAULT_TOLERANCE = 0.005

#: Columns of :meth:`LengthClasses.table`, the classes CSV.
CLASS_COLUMNS = ("class", "count", "nominal_length", "min_length", "max_length")

#: How many of the largest classes the "top-10 share" counts (the members a fabricator cuts from the few
#: lengths stocked in bulk).
TOP_CLASSES = 10


def check_tolerance(tolerance):
    """Return the relative tolerance as a float in ``(0, MAX_TOLERANCE)``.

    ``tolerance`` is a number (``0.005``) or a string, either a number
    (``"0.005"``) or a percentage (``"0.5%"``, i.e. 0.005), written as
    :data:`equimesh._checks.NUMBER_TEXT` allows (``"1_0%"`` is refused, not
    read as 10 %).

    Raises
    ------
    InvalidToleranceError
        not a number, not finite, or outside ``(0, 50 %)``.
    """
    if isinstance(tolerance, str):
        text = tolerance.strip()
        percent = text.endswith("%")
        try:
            value = number_text(text[:-1] if percent else text, "tolerance", InvalidToleranceError)
        except InvalidToleranceError:
            raise InvalidToleranceError(
                f"tolerance must be a number such as 0.005 or a percentage such as 0.5%, got {tolerance!r}"
            ) from None
        value *= 0.01 if percent else 1.0
    else:
        value = real_number(tolerance, "tolerance", InvalidToleranceError)
    if not (math.isfinite(value) and 0.0 < value < MAX_TOLERANCE):
        shown = tolerance if isinstance(tolerance, str) else repr(value)
        raise InvalidToleranceError(f"tolerance must be above 0 and below {MAX_TOLERANCE:.0%} of l, got {shown}")
    return value


@dataclass(frozen=True)
class LengthClasses:
    """Members grouped into length classes (see :func:`length_classes`).

    Attributes
    ----------
    member_class : (E,) int
        Class id of each member, in the members' order; ids are 0, 1, ...
        in increasing length.
    count : (k,) int
        Members per class.
    nominal : (k,) float
        Nominal length of each class, the midpoint of its shortest and longest
        member: every member is within ``tolerance * length`` of it.
    min, max : (k,) float
        Shortest and longest member of each class.
    length : float
        The target length l.
    tolerance : float
        The relative tolerance.
    stock : (k,) bool or None
        With a catalogue (:func:`catalogue_classes`): whether each class is a
        stock length (its nominal the catalogue's); None without one.
    """

    member_class: np.ndarray
    count: np.ndarray
    nominal: np.ndarray
    min: np.ndarray
    max: np.ndarray
    length: float
    tolerance: float
    stock: np.ndarray = None

    def __len__(self):
        return len(self.count)

    def largest(self, k=TOP_CLASSES):
        """The indices of the ``k`` largest classes, largest first, of equal counts the shorter nominal length first
        (all of them for ``k`` None)."""
        return np.argsort(-self.count, kind="stable")[:k]

    def top_share(self, k=TOP_CLASSES):
        """The share of the members in the ``k`` largest classes (:meth:`largest`; ``nan`` without members)."""
        total = int(self.count.sum())
        return float(self.count[self.largest(k)].sum() / total) if total else float("nan")

    def off_catalogue(self):
        """Members in no stock length's class (0 without a catalogue)."""
        return 0 if self.stock is None else int(self.count[~self.stock].sum())

    def table(self):
        """The classes as a DataFrame with :data:`CLASS_COLUMNS`, one row per class, and with a catalogue a column
        ``stock`` (``yes`` for a stock length's class, ``no`` for one off the catalogue)."""
        table = pd.DataFrame(
            dict(zip(CLASS_COLUMNS, (np.arange(len(self)), self.count, self.nominal, self.min, self.max)))
        )
        if self.stock is not None:
            table["stock"] = np.where(self.stock, "yes", "no")
        return table


def length_classes(lengths, l, tolerance=DEFAULT_TOLERANCE):
    """Group member lengths into the fewest classes of half-width ``tolerance * l``.

    A class is a set of members all within ``t = tolerance * l`` of one
    nominal length, i.e. whose longest and shortest members differ by at most
    ``w = 2 t``.  The greedy sweep: sort the lengths; the shortest member not
    yet in a class, ``s``, opens a class that takes every member of length
    ``<= s + w``; repeat.  Its nominal length is the midpoint of its shortest
    and longest member, within ``t`` of both.

    Optimality (the fewest classes).  Let the sweep open ``k`` classes at
    ``s_1 < s_2 < ... < s_k``.  Each ``s_{j+1}`` was left out of class j, so
    ``s_{j+1} > s_j + w``: the k opening members are pairwise more than ``w``
    apart.  A class spans at most ``w``, so no class of any grouping holds two
    of them, and every grouping needs at least k classes.  The sweep uses
    exactly k.  (Members of equal length always fall into the same class.)

    Parameters
    ----------
    lengths : (E,) float
        Member lengths.
    l : float
        Target length; the tolerance is relative to it.
    tolerance : float or str
        See :func:`check_tolerance`.

    Returns
    -------
    LengthClasses

    Raises
    ------
    EquimeshError
        a length that is not a positive finite number (named by its index).
    """
    l = check_length(l)
    tolerance = check_tolerance(tolerance)
    x = real_array(lengths, "member lengths", EquimeshError).ravel()
    bad = np.flatnonzero(~(np.isfinite(x) & (x > 0.0)))
    if bad.size:
        k = int(bad[0])
        raise EquimeshError(f"member lengths must be positive and finite, but length {k} is {number(x[k], None)}")
    order = np.argsort(x, kind="stable")
    sorted_x = x[order]
    width = 2.0 * tolerance * l
    starts, i = [], 0
    while i < sorted_x.size:
        starts.append(i)
        i = int(np.searchsorted(sorted_x, sorted_x[i] + width, side="right"))
    starts = np.asarray(starts, dtype=np.int64)
    ends = np.append(starts[1:], sorted_x.size)[: starts.size]
    member_class = np.empty(x.size, dtype=np.int64)
    member_class[order] = np.repeat(np.arange(starts.size), ends - starts)
    lo, hi = sorted_x[starts], sorted_x[ends - 1]
    return LengthClasses(
        member_class=member_class,
        count=ends - starts,
        nominal=0.5 * (lo + hi),
        min=lo,
        max=hi,
        length=l,
        tolerance=tolerance,
    )


def check_catalogue(catalogue, l):
    """Return the stock lengths as a sorted float array, each in [l, 2l] (up to ``REL_TOL``).

    ``catalogue`` is a sequence of numbers or a comma-separated string
    (``"5,5.8,7.1"``); repeated lengths count once.

    Raises
    ------
    InvalidCatalogueError
        empty, not numbers, not finite, or a length outside [l, 2l].
    """
    l = check_length(l)
    items = catalogue.split(",") if isinstance(catalogue, str) else catalogue
    try:
        values = np.array(
            [
                number_text(item, "lengths", InvalidCatalogueError)
                if isinstance(item, str)
                else real_number(item, "lengths", InvalidCatalogueError)
                for item in items
            ],
            dtype=float,
        )
    except (TypeError, InvalidCatalogueError):
        raise InvalidCatalogueError(
            f"lengths must be numbers separated by commas, such as 5,5.8,7.1, got {catalogue!r}"
        ) from None
    if values.size == 0:
        raise InvalidCatalogueError("lengths: the catalogue is empty; give at least one stock length in [l, 2l]")
    bad = ~(np.isfinite(values) & at_least(values, l) & at_most(values, 2.0 * l))
    if np.any(bad):
        raise InvalidCatalogueError(
            f"lengths: {number(values[bad][0])} is outside [l, 2l] = [{number(l)}, {number(2 * l)}]; "
            "every stock length must be a member length the mesh may have"
        )
    return np.unique(values)


def on_catalogue(lengths, l, catalogue, tolerance):
    """(E,) bool: each member within ``tolerance * l`` of a stock length of ``catalogue`` (all lengths absolute; a
    catalogue of :func:`check_catalogue`, not empty)."""
    x = np.asarray(lengths, dtype=float).ravel()
    stock = np.asarray(catalogue, dtype=float).ravel()
    return np.min(np.abs(x[:, None] - stock[None, :]), axis=1) <= tolerance * l


def catalogue_classes(lengths, l, catalogue, tolerance=DEFAULT_TOLERANCE):
    """Members grouped by a catalogue of stock lengths: a class per stock length, then the fewest classes of the rest.

    A member within ``tolerance * l`` of a stock length goes to the nearest
    such one (its class's nominal length is the stock length, ``stock``
    True); the members off the catalogue are grouped by :func:`length_classes`
    (``stock`` False).  Stock lengths that no member uses have no class.
    Class ids run over the stock classes by length, then the others by length.
    """
    l = check_length(l)
    tolerance = check_tolerance(tolerance)
    stock = check_catalogue(catalogue, l)
    x = np.asarray(lengths, dtype=float).ravel()
    nearest = np.argmin(np.abs(x[:, None] - stock[None, :]), axis=1)
    on = on_catalogue(x, l, stock, tolerance)
    used = np.unique(nearest[on])
    rest = length_classes(x[~on], l, tolerance)
    member_class = np.empty(x.size, dtype=np.int64)
    member_class[on] = np.searchsorted(used, nearest[on])
    member_class[~on] = rest.member_class + len(used)
    count = np.concatenate([np.bincount(member_class[on]), rest.count]).astype(np.int64)  # every used class has one
    lo = np.array([x[on][member_class[on] == k].min() for k in range(len(used))])
    hi = np.array([x[on][member_class[on] == k].max() for k in range(len(used))])
    return LengthClasses(
        member_class=member_class,
        count=count,
        nominal=np.concatenate([stock[used], rest.nominal]),
        min=np.concatenate([lo, rest.min]),
        max=np.concatenate([hi, rest.max]),
        length=l,
        tolerance=tolerance,
        stock=np.concatenate([np.ones(len(used), dtype=bool), np.zeros(len(rest), dtype=bool)]),
    )


#: Beyond the paper (docs/decisions.md, "A catalogue of stock lengths"): :func:`holds`
#: merges the sums it can reach into at most this many intervals per count of
#: members, a bound on its work (a side of 10^4 l is then decided in a second).
MAX_SUM_INTERVALS = 4096


def holds(total, catalogue, l, tolerance):
    """Whether some members, each within ``tolerance * l`` of a stock length, add up to ``total``.

    The sums of ``m`` such members form a union of intervals (each stock
    length widened by ``tolerance * l``, added ``m`` times); ``m`` runs up
    from 0 until ``total`` lies in one of them or below them all, at most to
    ``floor(total / min)`` of the widened lengths (a finite ``total``: a stock
    length is at least l and the tolerance below l / 2, so every widened
    length is positive), the intervals of one count merged where they overlap
    (into at most :data:`MAX_SUM_INTERVALS` by closing the narrowest gaps
    between them: beyond that the answer errs towards "holds").
    """
    stock = np.asarray(catalogue, dtype=float).ravel()
    low, high = stock - tolerance * l, stock + tolerance * l
    if total <= 0:
        return total == 0
    reach = np.array([[0.0, 0.0]])
    while not np.any((reach[:, 0] <= total) & (total <= reach[:, 1])):
        sums = (reach[:, None, :] + np.stack([low, high], axis=1)[None, :, :]).reshape(-1, 2)
        sums = sums[sums[:, 0] <= total]
        if not len(sums):
            return False
        reach = _merge(sums)
    return True


def _merge(intervals):
    """The union of ``intervals`` (rows ``[a, b]``) as sorted disjoint rows; beyond :data:`MAX_SUM_INTERVALS` rows the
    narrowest gaps between them are closed, every gap as narrow as the last one needed with them (so that no order
    among equal gaps counts), and the rows cover the union and a little more."""
    intervals = intervals[np.argsort(intervals[:, 0], kind="stable")]
    merged = [intervals[0].copy()]
    for a, b in intervals[1:]:
        if a <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], b)
        else:
            merged.append(np.array([a, b]))
    merged = np.array(merged)
    if len(merged) > MAX_SUM_INTERVALS:
        gaps = merged[1:, 0] - merged[:-1, 1]
        kept = gaps > np.sort(gaps)[len(merged) - MAX_SUM_INTERVALS - 1]
        merged = np.column_stack([merged[np.append(True, kept), 0], merged[np.append(kept, True), 1]])
    return merged
