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
"""

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ._checks import check_length, number_text, real_array, real_number
from .errors import EquimeshError, InvalidToleranceError, number

#: Upper limit (exclusive) of the relative tolerance: at 50 % of l a class of
#: width ``2 tol l = l`` would hold every member of [l, 2l] (Theorems 1 and 3)
#: in one or two classes, which is no fabrication tolerance any more.
MAX_TOLERANCE = 0.5

#: Tolerance used when none is given (the command line's ``--tolerance``):
#: +/-0.5 % of l, the "exactly l" share reported by the comparison with other meshers.
DEFAULT_TOLERANCE = 0.005

#: Columns of :meth:`LengthClasses.table`, the classes CSV.
CLASS_COLUMNS = ("class", "count", "nominal_length", "min_length", "max_length")


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
    """

    member_class: np.ndarray
    count: np.ndarray
    nominal: np.ndarray
    min: np.ndarray
    max: np.ndarray
    length: float
    tolerance: float

    def __len__(self):
        return len(self.count)

    def table(self):
        """The classes as a DataFrame with :data:`CLASS_COLUMNS`, one row per class."""
        return pd.DataFrame(
            dict(zip(CLASS_COLUMNS, (np.arange(len(self)), self.count, self.nominal, self.min, self.max)))
        )


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
