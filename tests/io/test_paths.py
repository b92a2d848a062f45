"""Output paths (``io/_paths.py``): each refused before any work when it cannot be written, none an input file, no
two outputs the same file, files compared by what the file system says, not by their spelling."""

import errno
import os
import tempfile

import pytest
from hostile_paths import fifo, name_max, plain_file, unwritable_folder
from refusals import assert_one_line

from equimesh import OutputPathError
from equimesh.io._atomic import atomic_paths, probe_folder
from equimesh.io._paths import check_distinct, check_writable, identity
from equimesh.io._schema import shown_path


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


def path_of_bytes(folder, size):
    """A path of exactly ``size`` bytes under ``folder``, through folders that need not exist."""
    parts, left = [], size - len(os.fsencode(str(folder)))
    while left > 201 + 10:
        parts.append("a" * 200)
        left -= 201
    return folder.joinpath(*parts, "b" * (left - 1))


def test_refusals_name_the_path_and_the_limit(tmp_path):
    """Each refusal is the whole line it should be: the limit exceeded and the path refused."""
    missing = tmp_path / "missing" / "m.obj"
    folder = tmp_path / "folder.obj"
    folder.mkdir()
    pipe = fifo(tmp_path / "pipe.obj")
    long_name = "a" * (name_max(tmp_path) + 1)
    cases = [
        (missing, f"output folder does not exist: {missing.parent}"),
        (folder, f"output {folder} is a folder"),
        (pipe, f"output {pipe} exists and is not a regular file"),
        (
            tmp_path / long_name,
            f"output file name is {len(long_name)} bytes long, more than the {name_max(tmp_path)} this file system "
            f"allows: {shown_path(long_name)}",
        ),
    ]
    for path, message in cases:
        with pytest.raises(OutputPathError) as err:
            check_writable(path)
        assert str(err.value) == message


def test_a_path_of_exactly_path_max_bytes_is_refused_on_its_length(tmp_path):
    """PATH_MAX counts the closing NUL: a path of PATH_MAX bytes is one too long, one byte less is not refused so."""
    path_max = os.pathconf(tmp_path, "PC_PATH_MAX")
    path = path_of_bytes(tmp_path, path_max)
    assert len(os.fsencode(str(path))) == path_max
    with pytest.raises(OutputPathError) as err:
        check_writable(path)
    assert str(err.value) == (
        f"output path is {path_max} bytes long, more than the {path_max - 1} this system allows: {shown_path(path)}"
    )
    with pytest.raises(OutputPathError, match="^output folder does not exist"):
        check_writable(path_of_bytes(tmp_path, path_max - 1))


def test_a_name_whose_temporary_cannot_be_made_is_refused_as_its_write_would_fail(tmp_path):
    """The temporary keeps the target's suffix: a name of NAME_MAX bytes that is nearly all suffix fits, but its
    temporary does not; the path is refused, as writing it would fail."""
    path = tmp_path / ("m." + "a" * (name_max(tmp_path) - 2))
    with pytest.raises(OutputPathError) as err:
        check_writable(path)
    assert str(err.value) == f"cannot write {shown_path(path)}: path too long"
    with pytest.raises(OSError) as write, atomic_paths(path):
        pass
    assert write.value.errno == errno.ENAMETOOLONG


def test_a_folder_that_refuses_files_is_named_with_the_systems_reason(tmp_path):
    folder = unwritable_folder(tmp_path)
    try:
        os.close(tempfile.mkstemp(dir=folder)[0])
    except OSError as exc:
        reason = exc.strerror
    assert reason != "path too long"
    with pytest.raises(OutputPathError) as err:
        check_writable(folder / "m.obj")
    assert str(err.value) == f"cannot write {folder / 'm.obj'}: {reason}"


def no_limit(folder, name):
    return -1


def unknown_limit(folder, name):
    raise ValueError(f"unrecognized configuration name {name}")


@pytest.mark.parametrize("pathconf", [no_limit, unknown_limit])
def test_a_file_system_without_limits_bounds_no_name(tmp_path, monkeypatch, pathconf):
    """Where the system has no limit (pathconf says -1) or cannot be asked, any name is tried: the write decides."""
    monkeypatch.setattr(os, "pathconf", pathconf)
    assert check_writable(tmp_path / "m.obj") is False
    with pytest.raises(OutputPathError, match="^cannot write .*: path too long$"):
        check_writable(tmp_path / ("a" * 300 + ".obj"))


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
    with pytest.raises(OutputPathError) as err:
        check_distinct([(tmp_path / "link.obj", "mesh", False)], [(source, "input")])
    assert str(err.value) == (
        f"the mesh {tmp_path / 'link.obj'} is the input {source}: writing it would destroy the input; choose another "
        "output file"
    )


def test_an_input_named_in_another_case_is_the_output_where_the_file_system_folds_case(tmp_path):
    """Where the output's folder folds case, the input's name is folded too: ``Roof.obj`` is ``roof.obj``."""
    source = tmp_path / "Roof.obj"
    source.write_text("v 0 0 0\n")
    with pytest.raises(OutputPathError, match="would destroy the input"):
        check_distinct([(tmp_path / "roof.obj", "mesh", True)], [(source, "input")])
    check_distinct([(tmp_path / "roof.obj", "mesh", False)], [(source, "input")])


def test_two_outputs_that_are_one_file_are_refused(tmp_path):
    """Two new files under one name, and two names (hard links) of one existing file."""
    (tmp_path / "sub").mkdir()
    a, same = tmp_path / "a.csv", tmp_path / "sub" / ".." / "a.csv"
    with pytest.raises(OutputPathError) as err:
        check_distinct([(a, "member schedule", check_writable(a)), (same, "node schedule", check_writable(same))])
    assert str(err.value) == (
        f"the member schedule {a} and the node schedule {same} are the same file; give each output its own file"
    )
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
