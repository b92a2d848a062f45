"""Output paths (``io/_paths.py``): each refused before any work when it cannot be written, none an input file, no
two outputs the same file, files compared by what the file system says, not by their spelling."""

import os

import pytest
from hostile_paths import fifo, name_max, plain_file, unwritable_folder
from refusals import assert_one_line

from equimesh import OutputPathError
from equimesh.io._atomic import atomic_paths, probe_folder
from equimesh.io._paths import check_distinct, check_writable, identity


@pytest.mark.parametrize(
    "make, fragment",
    [
        (lambda d: d / "missing" / "m.obj", "output folder does not exist"),
        (lambda d: plain_file(d) / "m.obj", "output folder is not a folder"),
        (lambda d: (d / "m.obj").mkdir() or d / "m.obj", "is a folder"),
        (lambda d: fifo(d / "m.obj"), "exists and is not a regular file"),
        (lambda d: d / ("a" * (name_max(d) - 3) + ".obj"), "bytes long, more than the"),
        (lambda d: d.joinpath(*["a" * 200] * 30, "m.obj"), "output path is"),
        (lambda d: unwritable_folder(d) / "m.obj", "cannot write"),
    ],
)
def test_unwritable_outputs_are_refused(make, fragment, tmp_path):
    """A refused output path is one line; nothing, not even a temporary file, is left behind."""
    path = make(tmp_path)
    made = sorted(tmp_path.rglob("*"))
    with pytest.raises(OutputPathError) as err:
        check_writable(path)
    assert fragment in str(err.value)
    assert_one_line(str(err.value))
    assert sorted(tmp_path.rglob("*")) == made


def test_longest_allowed_name_is_written(tmp_path):
    """A name of exactly NAME_MAX bytes is accepted and written: the temporary name does not grow with it."""
    path = tmp_path / ("a" * (name_max(tmp_path) - 4) + ".csv")
    check_writable(path)
    with atomic_paths(path) as (tmp,):
        assert len(tmp.name) < 30
        tmp.write_text("x")
    assert path.read_text() == "x"


def spellings(path):
    """Other paths to the existing file ``path``: ``./``, ``..``, a symbolic link, a hard link, an absolute path."""
    folder = path.parent
    (folder / "sub").mkdir(exist_ok=True)
    os.symlink(path, folder / "link.obj")
    os.link(path, folder / "hard.obj")
    cwd = os.getcwd()
    os.chdir(folder)
    try:
        relative = [os.path.join(".", path.name), os.path.join("sub", "..", path.name)]
    finally:
        os.chdir(cwd)
    return [folder / r for r in relative] + [folder / "link.obj", folder / "hard.obj", path.resolve()]


def test_an_output_that_is_an_input_is_refused_however_spelled(tmp_path):
    source = tmp_path / "roof.obj"
    source.write_text("v 0 0 0\n")
    for spelled in spellings(source):
        with pytest.raises(OutputPathError, match="would destroy the input") as err:
            check_distinct([(spelled, "mesh", check_writable(spelled))], [(source, "input")])
        assert_one_line(str(err.value))
    other = tmp_path / "other.obj"
    check_distinct([(other, "mesh", check_writable(other))], [(source, "input")])


def test_two_outputs_that_are_one_file_are_refused(tmp_path):
    """Two new files under one name, and two names (hard links) of one existing file."""
    (tmp_path / "sub").mkdir()
    a, same = tmp_path / "a.csv", tmp_path / "sub" / ".." / "a.csv"
    with pytest.raises(OutputPathError, match="member schedule .* and the node schedule .* are the same file"):
        check_distinct([(a, "member schedule", check_writable(a)), (same, "node schedule", check_writable(same))])
    a.write_text("old")
    b, c = tmp_path / "b.csv", tmp_path / "c.csv"
    os.link(a, b)
    with pytest.raises(OutputPathError, match="same file"):
        check_distinct([(a, "mesh", False), (b, "node schedule", False)])
    check_distinct([(a, "mesh", False), (c, "node schedule", False)])


def test_names_of_new_files_fold_where_the_file_system_folds_case(tmp_path):
    """Two names differing in case only are one file where the folder folds case, two files elsewhere."""
    folds = probe_folder(tmp_path, ".csv")
    lower, upper = tmp_path / "a.csv", tmp_path / "A.csv"
    assert bool(identity(lower, folds) & identity(upper, folds)) == folds
    assert identity(lower, True) & identity(upper, True) and not identity(lower, False) & identity(upper, False)
    with pytest.raises(OutputPathError, match="same file"):
        check_distinct([(lower, "member schedule", True), (upper, "node schedule", True)])
