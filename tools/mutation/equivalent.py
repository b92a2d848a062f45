"""The arguments for equivalent mutants (``equivalent.toml``), matched to survivors by their statements.

A survivor is either a gap in the tests (then a test is added that kills it) or an *equivalent* mutant that
no test can kill; each argument in :data:`PATH` says why some mutants are equivalent and names them by
``module`` (a path from the repository's root), ``function`` (``f`` or ``Class.method``), the ``original``
statement and the ``mutated`` statements, all as :func:`tools.mutation.mutants.normalised` writes them.

A survivor matches an argument on (module, original, mutated): formatting changes none of them, and renaming
the function leaves them too unless the statement itself names a renamed function.  The function is a hint:
if several functions of the module hold the same statement and mutation with different arguments, the one
of the survivor's function is taken; a hint that names no function holding the statement is reported by
:func:`check` (``python -m tools.mutation --check``), which also reports every argued mutant that the current
code no longer makes (an orphan).
"""

import tomllib
from pathlib import Path

from .mutants import statements

PATH = Path(__file__).with_name("equivalent.toml")
ROOT = Path(__file__).resolve().parents[2]


class Arguments:
    """The arguments of ``equivalent.toml``: ``why(module, function, original, mutated)`` and the entries."""

    def __init__(self, arguments):
        #: One entry per argued mutant: (module, function, original, mutated, why).
        self.entries = [
            (s["module"], s["function"], s["original"], mutated, argument["why"])
            for argument in arguments
            for s in argument["statement"]
            for mutated in s["mutated"]
        ]
        self._index = {}
        for module, function, original, mutated, why in self.entries:
            self._index.setdefault((module, original, mutated), []).append((function, why))

    def why(self, module, function, original, mutated):
        """Why this mutant is equivalent, or None if no argument names it."""
        found = self._index.get((module, original, mutated), [])
        same = [why for f, why in found if f == function]
        reasons = set(same or [why for _, why in found])
        return reasons.pop() if len(reasons) == 1 else None


def load(path=PATH):
    """The :class:`Arguments` of the TOML file ``path``."""
    return Arguments(tomllib.loads(Path(path).read_text())["argument"])


def check(arguments, mutants_of):
    """The argued mutants that the current code does not make, and the hints that name the wrong function.

    ``mutants_of(module)`` is the list of :class:`~tools.mutation.mutants.Mutant` of a module, or None for a
    module the tool does not know.  Returns ``(orphans, hints)``: ``orphans`` the entries (module, function,
    original, mutated) no mutant of the module matches, ``hints`` those matched in other functions only,
    with the functions that hold them.
    """
    made = {}
    orphans, hints = [], []
    for module, function, original, mutated, _ in arguments.entries:
        if module not in made:
            found = mutants_of(module) or []
            made[module] = {}
            for m in found:
                made[module].setdefault((m.original, m.mutated), set()).add(m.function)
        functions = made[module].get((original, mutated))
        if not functions:
            orphans.append((module, function, original, mutated))
        elif function not in functions:
            hints.append((module, function, original, mutated, sorted(functions)))
    return orphans, hints


def missing_originals(arguments, root=ROOT):
    """The argued entries whose original statement is in no function of their module: orphans for sure.

    Needs neither mutmut nor a run: the module's statements come from :func:`~tools.mutation.mutants.statements`.
    """
    held = {}
    missing = []
    for module, function, original, mutated, _ in arguments.entries:
        if module not in held:
            path = root / module
            held[module] = set().union(*statements(path.read_text()).values()) if path.is_file() else set()
        if original not in held[module]:
            missing.append((module, function, original, mutated))
    return missing
