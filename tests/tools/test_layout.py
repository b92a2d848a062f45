"""The shape of the package: one idea per module, no private name crossing a module's border.

* A module holds one idea: at most :data:`MAX_MODULE_LINES` lines.  The
  largest modules (the compiled insertion engine, the pipeline, Step 2's
  sides) stay under it; a module that grows past it holds two ideas and is
  split, as the polygon module of 1,188 lines was split into validation,
  argument checks and the four modules of Step 2.
* A name with a leading underscore is private to its module: no module
  imports one from another module of the package (a helper that two modules
  share is public inside the package, or lives in the base modules).  A
  private *module* may be imported by the package that holds it (meshio's
  ``io/_obj.py`` style: ``from . import _bezier``).
"""

import ast

import pytest
from repository import ROOT

SRC = ROOT / "src" / "equimesh"
MODULES = sorted(SRC.rglob("*.py"))

#: Lines of the largest module this package allows (docstrings and comments included).
MAX_MODULE_LINES = 500


def _module(path):
    parts = list(path.relative_to(SRC.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(SRC)))
def test_a_module_is_one_idea(path):
    lines = len(path.read_text().splitlines())
    assert lines <= MAX_MODULE_LINES, f"{path.relative_to(ROOT)} has {lines} lines: split it by idea"


def private_imports(text, package, modules):
    """The ``from X import _name`` lines of a module's ``text`` (in ``package``) that take a private name, not a
    private module of ``modules``, from a module of equimesh."""
    crossing = []
    for node in ast.walk(ast.parse(text)):
        if not isinstance(node, ast.ImportFrom):
            continue
        base = package.split(".")
        source = (
            ".".join(base[: len(base) - node.level + 1] + ([node.module] if node.module else []))
            if node.level
            else node.module
        )
        if not source or not source.startswith("equimesh"):
            continue
        for alias in node.names:
            if alias.name.startswith("_") and f"{source}.{alias.name}" not in modules:
                crossing.append(f"line {node.lineno}: from {source} import {alias.name}")
    return crossing


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(SRC)))
def test_no_private_name_crosses_a_module(path):
    package = _module(path) if path.name == "__init__.py" else _module(path).rpartition(".")[0]
    crossing = private_imports(path.read_text(), package, {_module(p) for p in MODULES})
    assert not crossing, f"{path.relative_to(ROOT)} imports private names: {crossing}"


def test_a_private_name_imported_is_found_and_a_private_module_is_not():
    modules = {"equimesh.io", "equimesh.io._bezier", "equimesh.surface.flatten"}
    text = "from ..flatten import _start, flatten\nfrom equimesh.io import _bezier\nfrom numpy import _core\n"
    assert private_imports(text, "equimesh.surface.charts", modules) == [
        "line 1: from equimesh.surface.flatten import _start"
    ]


def test_the_checks_see_the_package():
    """The two checks read every module (a wrong root would make them pass on nothing)."""
    assert len(MODULES) > 60 and any(p.name == "pipeline.py" for p in MODULES)
