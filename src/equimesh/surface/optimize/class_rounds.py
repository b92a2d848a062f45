"""The rounds of the classes objective (:func:`~.objectives.classes_stages`, beyond the paper): members pulled to
their nearest nominal length, the nominals moved and merged, the key the objective minimises.

After Singh and Schaefer 2010 ("Triangle surfaces with discrete equivalence classes") and Fu et al. 2010 ("K-set
tilable surfaces"): an assignment of the members to nominal lengths alternating with a solve towards them
(:func:`class_rounds`), the nominals moved to their members' middle and the emptiest dropped every
``CLASSES_MERGE_EVERY`` rounds (:func:`merged_nominals`), each round's Cauchy scale given by :func:`class_scale`
(from bounded's result) or :func:`half_tolerance` (from a remap that kept the lattice); docs/decisions.md, "The
classes objective".
"""

import numpy as np

from ...classes import TOP_CLASSES, length_classes, on_catalogue
from ...tolerance import (
    BOUNDED_FTOL,
    BOUNDED_ROUND_ITERATIONS,
    BOUNDED_STEP,
    CLASSES_MERGE_EVERY,
    CLASSES_ROUNDS,
    CLASSES_SCALE_DECAY,
    CLASSES_SCALE_START,
    CLASSES_START,
)
from .members import cauchy
from .stage import Stage, WorkSpent


def class_scale(k, tolerance):
    """The Cauchy scale of round ``k`` of the rounds from bounded's result, relative to l: ``CLASSES_SCALE_START
    tolerance`` shrunk by ``CLASSES_SCALE_DECAY`` a round down to half the ``tolerance`` (a continuation: first the
    members far from every nominal length, the strip's, are pulled to the nearest too, at the end only those within
    the tolerance of one).  The rounds from the remapped mesh keep half the tolerance throughout
    (:func:`half_tolerance`): their lattice members are exact, so a wider pull has nothing to gain there and can only
    move them (tests/surface/optimize/test_classes_objective.py's developable vault keeps its classes)."""
    return max(0.5 * tolerance, CLASSES_SCALE_START * tolerance * CLASSES_SCALE_DECAY**k)


def class_rounds(problem, members, x, best, scale):
    """The rounds from ``x``, nominal lengths from its classes (or the catalogue), the Cauchy scale of round ``k``
    ``scale(k, tolerance)``, ``best`` updated with every better round end (by :func:`class_key`); True when the work
    bound ended them (:class:`WorkSpent`)."""
    tolerance, catalogue = problem.tolerance, problem.catalogue
    if catalogue is not None:
        nominal = np.asarray(catalogue, dtype=float)
    else:
        start = length_classes(members.ratio(x), 1.0, tolerance)
        largest = start.nominal[start.largest(CLASSES_START)]
        nominal = np.unique(np.append(np.clip(largest, members.target, members.high), members.target))
    limit = problem.step_limit(BOUNDED_STEP * problem.length)
    closest = None  # the round end outside [l, 2l] with the fewest classes, if fewer than the best's
    for k in range(CLASSES_ROUNDS):
        ratio = members.ratio(x)
        goal = nominal[np.argmin(np.abs(ratio[:, None] - nominal[None, :]), axis=1)]
        weight, goal = members.pulled(ratio, cauchy(ratio - goal, scale(k, tolerance)), goal)
        stage = Stage(
            *members.weighted(weight, goal),
            f"members to the nearest of {len(nominal)} nominal lengths, round {k + 1}",
            BOUNDED_FTOL,
            BOUNDED_ROUND_ITERATIONS,
            start=x if k == 0 else None,  # the driver ended elsewhere: bounded's result is its best round, not its last
            limit=limit,
        )
        try:
            x = yield stage
        except WorkSpent:  # the work bound: the fewest classes so far (bounded's result at least)
            return True
        ratio = members.ratio(x)
        key = class_key(ratio, tolerance, catalogue)
        if key < best["key"] and problem.sound(x):
            if members.inside(ratio):
                best.update(x=np.array(x), stage=stage, key=key)
            elif closest is None or key < closest[0]:
                closest = (key, np.array(x), weight, goal, len(nominal))
        if catalogue is None:
            nominal = merged_nominals(nominal, ratio, tolerance, k, members)
    if closest is None or not closest[0] < best["key"]:
        return False
    # A round end outside [l, 2l] beat the best: its members into [l, 2l] by the band penalty.
    key, x, weight, goal, count = closest
    stage = Stage(
        *members.weighted(weight, goal, members.band_penalty()),
        f"members to the nearest of {count} nominal lengths and into [l, 2l] by a penalty",
        BOUNDED_FTOL,
        start=x,
        limit=limit,
        feasible=members.feasible,
        violation=members.violation,
    )
    try:
        x = yield stage
    except WorkSpent:
        return True
    ratio = members.ratio(x)
    key = class_key(ratio, tolerance, catalogue)
    if key < best["key"] and members.inside(ratio) and problem.sound(x):
        best.update(x=np.array(x), stage=stage, key=key)
    return False


def class_key(ratio, tolerance, catalogue):
    """What the classes objective minimises at ``ratio = L / l``: (members off the catalogue, classes, minus the share
    in the ten largest)."""
    off = 0 if catalogue is None else int(np.count_nonzero(~on_catalogue(ratio, 1.0, catalogue, tolerance)))
    classes = length_classes(ratio, 1.0, tolerance)
    return off, len(classes), -float(np.sort(classes.count)[::-1][:TOP_CLASSES].sum() / max(len(ratio), 1))


def merged_nominals(nominal, ratio, tolerance, k, members):
    """The nominal lengths after round ``k``: each moved to the middle of the members within ``tolerance`` of it (the
    class at l stays; at most ``high``), and every ``CLASSES_MERGE_EVERY`` rounds the one holding the fewest dropped."""
    nearest = np.argmin(np.abs(ratio[:, None] - nominal[None, :]), axis=1)
    near = np.abs(ratio - nominal[nearest]) <= tolerance
    moved = nominal.copy()
    for q in np.flatnonzero(nominal != members.target):
        held = ratio[near & (nearest == q)]
        if held.size:  # above the target: a member below it is nearer to the target (the first nominal) than to q
            moved[q] = min(0.5 * (held.min() + held.max()), members.high)
    if (k + 1) % CLASSES_MERGE_EVERY or len(moved) == 1:
        return moved
    counts = np.bincount(nearest[near], minlength=len(nominal))
    candidates = np.flatnonzero(nominal != members.target)
    return np.delete(moved, candidates[np.argmin(counts[candidates])])


def half_tolerance(k, tolerance):
    """The Cauchy scale of every round from a remap that kept the lattice: half the ``tolerance`` (:func:`class_scale`
    says why)."""
    return 0.5 * tolerance
