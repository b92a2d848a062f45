"""The mutants of a module as mutmut makes them, each keyed by statements that formatting does not change.

mutmut names a mutant after its module and function, ``equimesh.planar.lattice.x_kept_vertices__mutmut_28``
(a method: ``...xǁPolygonǁarea__mutmut_3``), and numbers the mutants of a function in the order it makes them.
Its own record of a mutant is a diff of the function's text, so a survivor's line changes whenever the code is
reformatted.  Here a mutant is also described by its *statement*: the innermost statement that holds the mutated
node, before and after the mutation, each normalised by :func:`normalised` (``ast.unparse``; a compound
statement by its header alone, ``if ...:``, ``for ...:``, ``def ...:``, unless the mutation is in its body's
structure).  Two formattings of the same code give the same statements.

:func:`statements` needs only the standard library (a cheap check of the arguments); :func:`module_mutants`
makes the mutants with mutmut's own code (``mutmut.mutation.file_mutation``, the ``[mutation]`` extra), in
process and without running a test: a second or two per module.
"""

import ast
import copy
from pathlib import Path
from typing import NamedTuple

#: The fields of a compound statement that hold statements, not its header.
_BODIES = ("body", "orelse", "finalbody", "handlers", "cases")

ROOT = Path(__file__).resolve().parents[2]


class Mutant(NamedTuple):
    """One mutant: mutmut's name, its function (``f`` or ``Class.method``) and its statement before and after."""

    name: str
    function: str
    original: str
    mutated: str


def _header(node):
    """``node`` (an ``ast`` statement) without the statements it holds and without decorators."""
    head = copy.copy(node)
    for field in _BODIES:
        if getattr(head, field, None):
            setattr(head, field, [])
    if hasattr(head, "decorator_list"):
        head.decorator_list = []
    if "body" in head._fields:
        head.body = [ast.Pass()]
    return ast.unparse(head).split("\n", 1)[0]


def _whole(node):
    """``node`` unparsed on one line."""
    return " ".join(line.strip() for line in ast.unparse(node).splitlines())


def normalised(source):
    """The key of one statement's source text: ``ast.unparse`` of it, a compound statement by its header.

    Whitespace, line breaks, redundant parentheses, quotes, trailing commas and comments do not count:
    ``x = f(a,\\n      b,)  # c`` and ``x = f(a, b)`` give the same key.
    """
    tree = ast.parse(source)
    if len(tree.body) != 1:
        raise ValueError(f"not one statement: {source!r}")
    node = tree.body[0]
    return _header(node) if any(f in node._fields for f in _BODIES) else ast.unparse(node)


def _function_name(name, cls):
    return f"{cls}.{name}" if cls else name


def statements(code):
    """Function (``f`` or ``Class.method``, as mutmut mutates them) -> the normalised statements in it.

    Statements of nested functions and classes count as their top-level function's, as mutmut's do.
    """
    found = {}

    def collect(node, into):
        for field in _BODIES:
            for child in getattr(node, field, None) or ():
                if isinstance(child, ast.stmt) and any(f in child._fields for f in _BODIES):
                    into.update((_header(child), _whole(child)))
                elif isinstance(child, ast.stmt):
                    into.add(ast.unparse(child))
                collect(child, into)

    def top(nodes, cls=None):
        for node in nodes:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                into = found.setdefault(_function_name(node.name, cls), set())
                into.add(_header(node))
                collect(node, into)
            elif isinstance(node, ast.ClassDef) and cls is None:
                top(node.body, node.name)

    top(ast.parse(code).body)
    return found


def dotted(module):
    """The dotted name of ``module``: ``src/equimesh/planar/bounds.py`` -> ``equimesh.planar.bounds``."""
    return ".".join(Path(module).with_suffix("").parts[1:])


def function_of(mangled):
    """The function of a mutant (or of mutmut's mangled name of a function), as ``--functions`` names it.

    ``equimesh.planar.boundary.sides.x_sharp_run__mutmut_3`` -> ``sharp_run``,
    ``xǁPolygonǁarea`` -> ``Polygon.area``.
    """
    return mangled.rsplit("__mutmut_", 1)[0].rpartition(".")[2][2:].replace("ǁ", ".")


def pattern(module, function):
    """mutmut's name pattern of the mutants of ``function`` (``f`` or ``Class.method``) in ``module``."""
    return f"{dotted(module)}.x{'ǁ' if '.' in function else '_'}{function.replace('.', 'ǁ')}__mutmut_*"


def module_mutants(module, code):
    """The mutants mutmut makes of ``code``, the text of ``module`` (a path under ``src/``), in mutmut's order.

    The same names as ``mutmut run`` gives them (mutmut 3.8: its numbering per function, its mangling).
    """
    import libcst as cst
    from mutmut.configuration import config
    from mutmut.mutation.file_mutation import create_mutations, group_by_top_level_node
    from mutmut.mutation.trampoline_templates import mangle_function_name
    from mutmut.utils.file_utils import change_cwd

    with change_cwd(ROOT):
        config()  # mutmut's settings (none but its defaults here) are read from the project's root
    tree, mutations, _, _ = create_mutations(module, code)
    owner = {id(node): None for node in tree.body if isinstance(node, cst.FunctionDef)}  # function -> its class
    for node in tree.body:
        if isinstance(node, cst.ClassDef) and isinstance(node.body, cst.IndentedBlock):
            owner.update((id(m), node.name.value) for m in node.body.body if isinstance(m, cst.FunctionDef))
    parent = {}
    stack = [tree]
    while stack:
        node = stack.pop()
        for child in node.children:
            parent[id(child)] = node
            stack.append(child)

    def statement(node):
        while not isinstance(node, (cst.BaseSmallStatement, cst.BaseCompoundStatement)):
            node = parent[id(node)]
        return node

    def text(node):
        if isinstance(node, cst.BaseCompoundStatement) and "body" in node.__dataclass_fields__:
            suite = cst.SimpleStatementSuite([cst.Expr(cst.Ellipsis())])
            rest = {f: None for f in ("orelse", "finalbody") if f in node.__dataclass_fields__}
            extra = {"decorators": ()} if "decorators" in node.__dataclass_fields__ else {}
            node = node.with_changes(body=suite, **rest, **extra)
        return normalised(tree.code_for_node(node))

    prefix = dotted(module)
    found = []
    for function, group in group_by_top_level_node(mutations).items():
        if id(function) not in owner:  # module-level code and nested classes: mutmut makes no mutant of them
            continue
        name, cls = function.name.value, owner[id(function)]
        mangled = mangle_function_name(name=name, class_name=cls)
        for i, mutation in enumerate(group, start=1):
            before = statement(mutation.original_node)
            if before is mutation.original_node:
                after = mutation.mutated_node
            else:
                after = before.deep_replace(mutation.original_node, mutation.mutated_node)
            original, mutated = text(before), text(after)
            if original == mutated:  # a compound statement changed in its body's structure (a case removed)
                original, mutated = (_whole(ast.parse(tree.code_for_node(n)).body[0]) for n in (before, after))
            found.append(Mutant(f"{prefix}.{mangled}__mutmut_{i}", _function_name(name, cls), original, mutated))
    return found
