"""The docs name what the repository holds, and the code cites the docs by what they hold.

What must hold:

* every module of ``src/equimesh`` has its row in docs/architecture.md, and every module architecture.md names
  (paths relative to ``src/equimesh``) exists;
* every Python file a doc names in a code span (docs/*.md, README.md) exists, and so does the ``name`` of
  ``path.py::name`` in it (a test function for a test file); a bare ``::name`` belongs to the last file named before
  it in the same paragraph;
* every citation of docs/decisions.md in the code, ``(docs/decisions.md, "Heading")``, names one of its headings,
  and no code cites an entry by a number (entries have none).

The checks read the tree as it is, so a module added or renamed fails the first check until architecture.md says
where it goes.
"""

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "src" / "equimesh"
DOCS = [*sorted((ROOT / "docs").glob("*.md")), ROOT / "README.md"]
ARCHITECTURE = ROOT / "docs" / "architecture.md"
DECISIONS = ROOT / "docs" / "decisions.md"

#: Top folders: a path that starts with one is relative to the repository root, any other to ``src/equimesh``.
TOP = ("src/", "tests/", "experiments/", "benchmarks/", "tools/")
#: A code span naming a Python file, ``path.py`` or ``path.py::name``, or a bare ``::name`` continuing the last one.
NAMED = re.compile(r"`((?:[\w.-]+/)*[\w.-]+\.py)?(?:::([\w.]+))?`")
#: The citation of a decisions entry in code: ``decisions.md, "Heading"`` (or ``"A" and "B"``).
CITATION = re.compile(r'decisions\.md(?:,\s*("[^"]+"(?:\s*(?:,|and)\s*"[^"]+")*))?')
CODE = ("src", "tests", "experiments", "benchmarks", "tools")
#: A citation by number ("item 52", "decisions 6-7"), from when the entries were numbered.
BY_NUMBER = re.compile(r"\b(?:items?|decisions?) \d+")


def python_files():
    """Every Python file of the repository's code folders, as paths relative to the root."""
    return sorted(
        p.relative_to(ROOT).as_posix()
        for top in CODE
        if (ROOT / top).is_dir()
        for p in (ROOT / top).rglob("*.py")
        if "__pycache__" not in p.parts
    )


def package_modules():
    return sorted(p.relative_to(PACKAGE).as_posix() for p in PACKAGE.rglob("*.py") if "__pycache__" not in p.parts)


def named(text):
    """``(path, name)`` for every Python file a doc names (``name`` None when none is given)."""
    found = []
    for paragraph in re.split(r"\n\s*\n", text):
        last = None
        for path, name in NAMED.findall(paragraph):
            if path:
                last = path
            elif name and last:
                path = last
            if path:
                found.append((path, name or None))
    return found


def resolve(path):
    """The files a doc's ``path`` may mean: from the root, from the package, or any file ending in it."""
    if path.startswith(TOP):
        return [path] if (ROOT / path).is_file() else []
    if (PACKAGE / path).is_file():
        return [(PACKAGE / path).relative_to(ROOT).as_posix()]
    return [f for f in python_files() if f.endswith("/" + path)]


def defines(path, name):
    """True when ``path`` defines every component of the dotted ``name`` (def, class or assignment)."""
    text = (ROOT / path).read_text()
    return all(
        re.search(rf"^\s*(?:def|class)\s+{re.escape(part)}\b|^\s*{re.escape(part)}\s*[:=]", text, re.M)
        for part in name.split(".")
    )


def headings():
    return {line.lstrip("#").strip() for line in DECISIONS.read_text().splitlines() if line.startswith(("## ", "### "))}


def test_every_module_of_the_package_is_in_architecture():
    listed = {p.removeprefix("src/equimesh/") for p, _ in named(ARCHITECTURE.read_text())}
    missing = [m for m in package_modules() if m not in listed]
    assert not missing, f"docs/architecture.md has no row for {missing}"


def test_every_module_architecture_names_exists():
    paths = {p for p, _ in named(ARCHITECTURE.read_text())}
    gone = sorted(p for p in paths if not (ROOT / p if p.startswith(TOP) else PACKAGE / p).is_file())
    assert not gone, f"docs/architecture.md names modules that do not exist: {gone}"


@pytest.mark.parametrize("doc", DOCS, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_file_and_name_a_doc_names_exists(doc):
    wrong = []
    for path, name in named(doc.read_text()):
        files = resolve(path)
        if not files:
            wrong.append(f"{path}: no such file")
        elif name and not any(defines(f, name) for f in files):
            wrong.append(f"{path}::{name}: not defined there")
    assert not wrong, f"{doc.name} names what does not exist: {sorted(set(wrong))}"


def test_decisions_headings_are_unique():
    lines = [line for line in DECISIONS.read_text().splitlines() if line.startswith(("## ", "### "))]
    assert len(lines) == len({line.lstrip("#").strip() for line in lines})


def citing_files():
    return [p for p in python_files() if not p.startswith("tests/tools/") and "decisions.md" in (ROOT / p).read_text()]


@pytest.mark.parametrize("path", citing_files())
def test_code_cites_decisions_by_an_existing_heading(path):
    # Comments and docstrings wrap: join the lines, dropping the comment markers, so a citation reads as one line.
    text = re.sub(r"\s*\n\s*(?:#:?\s*)?", " ", (ROOT / path).read_text())
    known, wrong = headings(), []
    for match in CITATION.finditer(text):
        cited = re.findall(r'"([^"]+)"', match.group(1) or "")
        if not cited:
            wrong.append(f"no heading after: {text[match.start() : match.end() + 40]!r}")
        wrong.extend(f"unknown heading {h!r}" for h in cited if h not in known)
    assert not wrong, f"{path} cites docs/decisions.md wrongly: {wrong}"


def test_no_code_cites_an_entry_by_number():
    wrong = [
        f"{path}:{n}: {line.strip()}"
        for path in python_files()
        if not path.startswith("tests/tools/")
        for n, line in enumerate((ROOT / path).read_text().splitlines(), 1)
        if BY_NUMBER.search(line)
    ]
    assert not wrong, "cite docs/decisions.md by heading, not by number:\n" + "\n".join(wrong)


def test_the_readme_comparison_rows_are_rows_of_the_generated_table():
    """Every row of the README's comparison says what ``results/compare_peers.md`` (written by
    ``experiments/compare_peers.py``) says for that surface and method: no number in the README that the script did
    not write."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("## Against other meshers", 1)[1].split("\n## ", 1)[0]
    generated = (ROOT / "results" / "compare_peers.md").read_text(encoding="utf-8")
    header = next(line for line in generated.splitlines() if line.startswith("| surface | method |"))
    columns = [c.strip() for c in header.strip("|").split("|")]
    table = {}
    for line in generated.splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if line.startswith("| ") and len(cells) == len(columns) and cells[0] != "surface":
            table[cells[0], cells[1]] = dict(zip(columns, cells))
    rows = [line for line in section.splitlines() if line.startswith("| ") and not line.startswith("| surface")]
    assert rows
    for line in rows:
        surface, method, within, within5, band, classes, top10, angles = (c.strip() for c in line.strip("|").split("|"))
        row = table[surface, method]
        assert (within, within5, band, classes, top10, angles) == (
            f"{row['within 0.5 %']} %",
            f"{row['within 5 %']} %",
            f"{row['in [l, 2l]']} %",
            row["classes 0.5 %"],
            f"{row['top 10']} %",
            f"{row['min angle']}-{row['max angle']}",
        ), line


def test_the_readme_lists_every_output_format():
    """The README's output table is the one the registry makes (``equimesh.io.output_table``)."""
    from equimesh.io import output_table

    assert output_table() in (ROOT / "README.md").read_text(encoding="utf-8")
