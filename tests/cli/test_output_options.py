"""The command line's outputs: every format of the registry by -o's extension, --nodes and --dxf-labels beside the
member schedule, and a format whose extra is missing refused in one line before any work."""

import sys

import pandas as pd
import pytest
from repository import SURFACES

from equimesh._cli import main
from equimesh.io import OUTPUT_FORMATS
from equimesh.surface import pipeline

SADDLE = SURFACES / "saddle.json"
RUN = ["mesh", str(SADDLE), "--length", "6", "--grid", "8", "8"]


def test_help_lists_every_format(capsys):
    with pytest.raises(SystemExit):
        main(["mesh", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    for fmt in OUTPUT_FORMATS:
        assert fmt.extension in text and fmt.name in text
        if fmt.extra:
            assert f"extra [{fmt.extra}]" in text


def test_a_run_writes_mesh_members_and_nodes_and_names_them(tmp_path, capsys):
    pytest.importorskip("ezdxf", reason="ezdxf (the optional extra [dxf]) is not installed")
    out = [tmp_path / "roof.dxf", tmp_path / "roof.csv", tmp_path / "roof.classes.csv", tmp_path / "nodes.csv"]
    code = main([*RUN, "-o", str(out[0]), "--members", str(out[1]), "--nodes", str(out[3]), "--dxf-labels"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert sorted(tmp_path.iterdir()) == sorted(out)
    assert f"wrote {', '.join(map(str, out))}: " in captured.err
    members, nodes = pd.read_csv(out[1]), pd.read_csv(out[3])
    assert nodes["valence"].sum() == 2 * len(members)
    assert "TEXT" in out[0].read_text()


@pytest.mark.parametrize("fmt", [f for f in OUTPUT_FORMATS if f.extra], ids=lambda f: f.extension)
def test_a_format_without_its_extra_is_refused_before_meshing(fmt, tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, fmt.module, None)
    monkeypatch.setattr(pipeline, "mesh_surface", lambda *a, **k: pytest.fail("mesh_surface must not run"))
    target = str(tmp_path / f"m{fmt.extension}")
    outputs = ["-o", target] if fmt.slot == "mesh" else ["-o", str(tmp_path / "m.obj"), f"--{fmt.slot}", target]
    code = main([*RUN, *outputs, "--members", str(tmp_path / "m.csv")])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and f"pip install 'equimesh[{fmt.extra}]'" in err, err
    assert list(tmp_path.iterdir()) == []
