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


def test_a_golden_folder_that_does_not_exist_is_a_usage_error(tmp_path):
    """A mistyped --check path was 'differences found' (exit 1, every file 'missing in the golden
    folder'): it is a usage error (exit 2) that says to add --update to make one; a file is not a
    golden folder. Nothing is written."""
    (tmp_path / "a.yaml").write_text(MINI)
    r = runner.invoke(app, ["batch", str(tmp_path / "a.yaml"), "--check", str(tmp_path / "gold"), "--jobs", "1"])
    assert r.exit_code == 2 and "no such golden folder (to make one, add --update)" in r.output
    assert not (tmp_path / "gold").exists()
    r = runner.invoke(app, ["batch", str(tmp_path / "a.yaml"), "--check", str(tmp_path / "a.yaml"), "--jobs", "1"])
    assert r.exit_code == 2 and "not a folder" in r.output


def test_a_boolean_that_becomes_a_number_is_a_difference():
    """JSON's true and 1 are different values (`unreachable: true` is not the number 1), but
    Python's True == 1 made the key-by-key comparison call them equal."""
    from robosolve.run.batch import compare_json

    assert compare_json({"unreachable": True}, {"unreachable": 1}) == ["$.unreachable: True -> 1"]
    assert compare_json([0], [False]) == ["$[0]: 0 -> False"]
    assert compare_json({"x": 1.0}, {"x": 1}) == []                       # numbers stay numbers
    assert compare_json([True, False], [True, False]) == []


def test_a_golden_folder_of_a_file_that_cannot_be_read_is_not_called_removed(tmp_path):
    """A YAML syntax error hides the file's `name`: its golden folder was reported as if its problem
    had been removed or renamed, with the advice to delete it. It names the unreadable file instead."""
    src = tmp_path / "src"
    src.mkdir()
    (src / "a.yaml").write_text(MINI)
    golden = tmp_path / "golden"
    r = runner.invoke(app, ["batch", str(src), "--check", str(golden), "--update", "--jobs", "1"])
    assert r.exit_code == 0
    (src / "a.yaml").write_text(MINI + "oops: [\n")
    r = runner.invoke(app, ["batch", str(src), "--check", str(golden), "--jobs", "1"])
    assert r.exit_code == 2 and "YAML syntax error" in r.output
    assert "delete the folder" not in r.output
    assert f"{golden / 'mini'}: not checked: {src / 'a.yaml'} could not be read" in r.output


def test_out_with_check_is_a_usage_error_not_ignored(tmp_path):
    """`--check` compares in memory: an `--out` beside it was silently ignored (exit 0, no folder
    written where the user asked). It is a usage error, and nothing is written."""
    (tmp_path / "a.yaml").write_text(MINI)
    golden, out = tmp_path / "golden", tmp_path / "out"
    r = runner.invoke(app, ["batch", str(tmp_path / "a.yaml"), "--check", str(golden), "--update", "--jobs", "1"])
    assert r.exit_code == 0
    for extra in ([], ["--update"]):
        r = runner.invoke(app, ["batch", str(tmp_path / "a.yaml"), "--check", str(golden), "--out", str(out),
                                "--jobs", "1", *extra])
        assert r.exit_code == 2 and "--out and --check do not go together" in r.output
        assert not out.exists()


def test_a_corrupt_golden_file_is_a_difference_not_an_internal_error(tmp_path):
    """A golden results.json that is not JSON (a bad merge, a hand edit) or a report.md that is not
    UTF-8 stopped the check with 'internal error'; each is a difference that names the file."""
    (tmp_path / "a.yaml").write_text(MINI)
    golden = tmp_path / "golden"
    r = runner.invoke(app, ["batch", str(tmp_path / "a.yaml"), "--check", str(golden), "--update", "--jobs", "1"])
    assert r.exit_code == 0
    (golden / "mini" / "results.json").write_text('{"answers": ')
    (golden / "mini" / "report.md").write_bytes(b"\xff\xfe not utf-8")
    r = runner.invoke(app, ["batch", str(tmp_path / "a.yaml"), "--check", str(golden), "--jobs", "1"])
    assert "internal error" not in r.output and r.exit_code == 1
    assert f"{golden / 'mini' / 'results.json'}: unreadable golden file (not JSON:" in r.output
    assert f"{golden / 'mini' / 'report.md'}: unreadable golden file (not UTF-8 text" in r.output
    assert "golden check: differences found" in r.output
