"""Provenance of every result: git commit, date, platform, library versions, parameters.

Each script that writes a file under ``results/`` or ``paper_figs/`` writes a
``<name>.provenance.json`` beside it with :func:`write_provenance`, so that a
number can always be traced to the code and the inputs that produced it.
"""

import datetime
import importlib.metadata
import json
import platform
import subprocess
import sys
from pathlib import Path

from ._atomic import atomic_write_text

#: Output folders: changes there do not make the code "dirty" (a
#: ``make reproduce`` run rewrites them while later experiments still run).
OUTPUT_DIRS = ("results", "paper_figs")

#: Distributions whose versions are recorded.
LIBRARIES = ("equimesh", "numpy", "scipy", "shapely", "triangle", "pandas", "matplotlib")


def _git(*args, cwd):
    try:
        out = subprocess.run(["git", *args], cwd=cwd, capture_output=True, text=True, timeout=10, check=True)
    except (OSError, subprocess.SubprocessError):
        return None
    return out.stdout.strip()


def git_state(cwd=None):
    """``{"commit": sha or None, "dirty": bool or None}`` of the repository holding ``cwd``.

    ``cwd`` defaults to the folder of this source file, so that the commit of
    the code that ran is recorded wherever the script is started from.
    ``dirty`` says whether anything but the outputs (:data:`OUTPUT_DIRS`)
    differs from the commit.  Outside a git checkout (an installed wheel, no
    ``git``) both are None.
    """
    cwd = Path(__file__).resolve().parent if cwd is None else Path(cwd)
    commit = _git("rev-parse", "HEAD", cwd=cwd)
    if not commit:
        return {"commit": None, "dirty": None}
    top = _git("rev-parse", "--show-toplevel", cwd=cwd)
    outputs = [f":(exclude,top){name}" for name in OUTPUT_DIRS]
    status = _git("-C", top, "status", "--porcelain", "--", ".", *outputs, cwd=cwd) if top else None
    return {"commit": commit, "dirty": None if status is None else bool(status)}


def library_versions(names=LIBRARIES):
    """Installed version of each distribution in ``names`` (None if not installed)."""
    versions = {}
    for name in names:
        try:
            versions[name] = importlib.metadata.version(name)
        except importlib.metadata.PackageNotFoundError:
            versions[name] = None
    return versions


def provenance(parameters):
    """The provenance record of a result computed with ``parameters`` (a JSON-able dict)."""
    return {
        "git": git_state(),
        "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
        "python": platform.python_version(),
        "implementation": sys.implementation.name,
        "platform": platform.platform(),
        "versions": library_versions(),
        "parameters": dict(parameters),
    }


def provenance_path(result_path):
    """``results/x.csv`` -> ``results/x.provenance.json`` (the file beside a result)."""
    result_path = Path(result_path)
    return result_path.with_name(f"{result_path.stem}.provenance.json")


def write_provenance(path, parameters):
    """Write :func:`provenance` of ``parameters`` as JSON to ``path``, atomically; returns the record.

    ``path`` is the JSON file itself; use :func:`provenance_path` to derive it
    from the result it describes.
    """
    record = provenance(parameters)
    atomic_write_text(path, json.dumps(record, indent=2, sort_keys=True, default=str) + "\n")
    return record


def provenance_markdown(record):
    """The "Provenance" section of a Markdown report, as a list of lines (commit, date, parameters, versions)."""
    git = record["git"]
    commit = git["commit"] or "unknown (not a git checkout)"
    dirty = " (uncommitted changes)" if git["dirty"] else ""
    versions = ", ".join(f"{k} {v}" for k, v in record["versions"].items())
    return [
        "## Provenance",
        "",
        f"- commit: `{commit}`{dirty}",
        f"- date (UTC): {record['date']}",
        f"- parameters: `{json.dumps(record['parameters'], sort_keys=True)}`",
        f"- Python {record['python']} on {record['platform']}",
        f"- libraries: {versions}",
    ]
