"""The repository speaks of the project alone: no word of how the work on it was organised.

Code, tests and docs say what holds, why, and where it is tested; who asked for a change, in which tracker item or
working session, on which machine's temporary paths, is history, and the history is git's. Every tracked text file
of the folders and files in :data:`SCANNED` is read, and each line is searched for the words of :data:`WORDS` once the
legitimate technical phrases of :data:`ALLOWED` are taken out of it.
"""

import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCANNED = ("src", "tests", "docs", "experiments", "benchmarks", "tools", "README.md", "Makefile", "pyproject.toml")

#: What a word means here, and the pattern that finds it (case-insensitive).
WORDS = {
    "a tracker's issue": r"\bissues?\b",
    "a brief": r"\bbriefs?\b",
    "a working session": r"\bsessions?\b",
    "an agent": r"\b(?:sub-?)?agents?\b",
    "a scratch area": r"\bscratch\b",
    "a temporary driver or path": r"/tmp\b",
    "a deadline": r"\bdeadlines?\b",
    "a person's role": r"\bthe lead\b|\b(?:module|solver|code)'s owner\b",
    "a ticket": r"\btickets?\b",
}

#: Technical phrases that contain one of the words, taken out of a line before it is searched.
ALLOWED = (
    # hypothesis's `deadline` setting, the time limit of one example, switched off in every profile.
    r"\bdeadline=None\b",
    r"\bNo deadline in either\b",
    # pytest's session: the fixture scope and the hook run once per test session.
    r'\bscope="session"',
    r"\bpytest_session\w*\(session\)",
    r"\bsession\.config\b",
    # "recomputed from scratch": re-triangulating without reusing the previous triangulation.
    r"\bfrom scratch\b",
    # mutation testing's working copy of src/ and tests/ under .mutation/ (tools/mutation).
    r"\bscratch (?:copy|copies|folder)\b",
    # plain English: "in brief", said of a summary.
    r"\bin brief\b",
)


def tracked_text_files():
    """The tracked files of :data:`SCANNED` that read as UTF-8 text, but this one (its patterns hold the words)."""
    try:
        listed = subprocess.run(
            ["git", "-C", str(ROOT), "ls-files", "-z", "--", *SCANNED], check=True, capture_output=True, text=True
        ).stdout
    except (OSError, subprocess.CalledProcessError):
        return []
    files = []
    for name in filter(None, listed.split("\0")):
        path = ROOT / name
        if not path.is_file() or path.resolve() == Path(__file__).resolve():
            continue
        try:
            path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue
        files.append(name)
    return files


def offences(text):
    """``(line number, meaning, line)`` for every process word of ``text``, allowed phrases taken out."""
    found = []
    for n, line in enumerate(text.splitlines(), 1):
        plain = re.sub("|".join(ALLOWED), " ", line, flags=re.IGNORECASE)
        found.extend((n, meaning, line.strip()) for meaning, word in WORDS.items() if re.search(word, plain, re.I))
    return found


def test_the_scan_sees_the_repository():
    files = tracked_text_files()
    if not files:
        pytest.skip("not a git checkout: nothing tracked to scan")
    assert "README.md" in files and any(f.startswith("src/equimesh/") for f in files)


def test_allowed_phrases_pass_and_the_words_do_not():
    assert offences('    deadline=None,\n@pytest.fixture(scope="session")\nrecomputed from scratch') == []
    assert [meaning for _, meaning, _ in offences("the issue's argument\nmeasured by a /tmp driver")] == [
        "a tracker's issue",
        "a temporary driver or path",
    ]


@pytest.mark.parametrize("name", tracked_text_files())
def test_no_word_of_how_the_work_was_organised(name):
    found = offences((ROOT / name).read_text(encoding="utf-8"))
    assert not found, f"{name}:\n" + "\n".join(f"  {n}: {meaning}: {line}" for n, meaning, line in found)
