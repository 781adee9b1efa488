"""The golden check's words: a golden folder whose problem is gone is named, and one problem is
one problem (issue 22)."""

from __future__ import annotations

from typer.testing import CliRunner

from conftest import MINI
from robosolve.cli import app

runner = CliRunner()


def test_a_golden_folder_whose_problem_was_removed_is_flagged(tmp_path):
    src = tmp_path / "src"
    src.mkdir()
    (src / "a.yaml").write_text(MINI)
    (src / "b.yaml").write_text(MINI.replace("name: mini", "name: mini2"))
    golden = tmp_path / "golden"
    r = runner.invoke(app, ["batch", str(src), "--check", str(golden), "--update", "--jobs", "1"])
    assert r.exit_code == 0 and "updated (2 problems)" in r.output
    (src / "b.yaml").unlink()
    r = runner.invoke(app, ["batch", str(src), "--check", str(golden), "--jobs", "1"])
    assert f"{golden / 'mini2'}: no problem file checked has the name 'mini2'" in r.output
    assert "golden check: 1 problem identical" in r.output
    assert f"{golden / 'mini'}:" not in r.output                                  # the kept one is fine
