"""Conditional properties that must be exercised.

A property that only says something when a
condition holds (``assume(c)``, or ``if c: check(...)``) passes vacuously if
the generated inputs never satisfy ``c``.  Such a test wraps the condition in
:func:`exercised`::

    from conditions import exercised

    assume(exercised("strip vertices globally separated (hypothesis H)", separated))

and fails when a condition it evaluated never held (``conditional property
never exercised: ...``).  A fuzz test, which accepts or refuses each
generated input, also states the share of inputs that must be accepted, so
that refusing everything fails too::

    @pytest.mark.exercised("Problem 2 accepted the polygon", share=0.3)

fails unless that condition was evaluated and held in at least 30% of its
evaluations.  The counts are those of one test (each parametrized case on
its own), taken in the process that runs it, so the check holds under
``pytest -n 2`` as without it.  ``--hypothesis-show-statistics`` shows the
share of each condition per test.

The counts live here, not in ``conftest.py``: pytest imports a conftest anew
for each session in one process (mutmut runs several), while a test module
imported once keeps the names it took, so state in the conftest would not be
the state the hook reads.
"""

from hypothesis import currently_in_test_context, event

#: The counts of the test running in this process: condition name -> [times evaluated, times held].
RUNNING = []


def exercised(name, held):
    """Record that the condition ``name`` was evaluated and whether it ``held``; returns ``held``.

    Also a hypothesis ``event`` inside a property test (``--hypothesis-show-statistics``).
    """
    held = bool(held)
    if RUNNING:
        counts = RUNNING[-1][name]
        counts[0] += 1
        counts[1] += held
    if currently_in_test_context():
        event(f"{name}: {'held' if held else 'did not hold'}")
    return held


def unexercised(counts, shares):
    """Why a test's conditions fail: ``counts`` is ``{name: (evaluated, held)}``, ``shares`` ``{name: share}``."""
    problems = [
        f"conditional property never exercised: {name!r} never held in {evaluated} evaluation(s)"
        for name, (evaluated, held) in sorted(counts.items())
        if not held
    ]
    for name, share in sorted(shares.items()):
        evaluated, held = counts.get(name, (0, 0))
        if not evaluated:
            problems.append(f"condition {name!r} was never evaluated (expected to hold in {share:.0%} or more)")
        elif held and held < share * evaluated:
            problems.append(
                f"condition {name!r} held in {held} of {evaluated} evaluations ({held / evaluated:.0%}), "
                f"less than the {share:.0%} expected"
            )
    return problems
