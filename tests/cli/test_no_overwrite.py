"""No command writes over, or replaces a folder holding, a file it reads (issue 22).

Each case is a real command line on real files; the check is the file system afterwards:
exit 2, the message names the clash, every byte of the inputs is still there.
"""

from __future__ import annotations

from pathlib import Path

from typer.testing import CliRunner

from robosolve.cli import app
from robosolve.run.outputs import MARK
from tests._grading import dedent
from tests.workflows.test_grading_grade import ALICE, PROBLEM

runner = CliRunner()


def snapshot(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): (None if p.is_dir() else p.read_bytes())
            for p in sorted(folder.rglob("*"))}


def _variants_folder(root: Path) -> Path:
    """A folder as `robosolve variants` writes it: marked, variants.csv, one problem each."""
    v = root / "V"
    (v / "two-r-grade-1").mkdir(parents=True)
    (v / "two-r-grade-1" / "problem.yaml").write_text(dedent(PROBLEM).replace("two-r-grade", "two-r-grade-1"))
    (v / "variants.csv").write_text("variant,student,seed,L2\n1,alice,0,2/5\n")
    (v / MARK).write_bytes(b"")
    return v


def _answers(root: Path, problem_ref: str = "../p.yaml") -> Path:
    subs = root / "subs"
    subs.mkdir(exist_ok=True)
    f = subs / "alice.yaml"
    f.write_text(dedent(ALICE).replace("../p.yaml", problem_ref), encoding="utf-8")
    return f


def test_grade_refuses_out_equal_to_the_variants_folder(tmp_path):
    v = _variants_folder(tmp_path)
    sub = _answers(tmp_path)
    before = snapshot(tmp_path)
    r = runner.invoke(app, ["grade", str(sub), "--variants", str(v), "--out", str(v)])
    assert r.exit_code == 2, r.output
    assert "which robosolve reads" in r.output and "Traceback" not in r.output
    assert snapshot(tmp_path) == before


def test_grade_refuses_out_inside_or_holding_the_variants_folder(tmp_path):
    v = _variants_folder(tmp_path)
    sub = _answers(tmp_path)
    before = snapshot(tmp_path)
    for out in (v / "grades", tmp_path):
        (tmp_path / MARK).write_bytes(b"")            # the parent is robosolve's too: still refused
        r = runner.invoke(app, ["grade", str(sub), "--variants", str(v), "--out", str(out)])
        (tmp_path / MARK).unlink()
        assert r.exit_code == 2, r.output
        assert snapshot(tmp_path) == before


def test_grade_refuses_a_folder_holding_a_problem_named_by_a_submission(tmp_path):
    probs = tmp_path / "probs"
    probs.mkdir()
    (probs / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    (probs / MARK).write_bytes(b"")                   # an earlier robosolve output folder
    sub = _answers(tmp_path, "../probs/p.yaml")
    before = snapshot(tmp_path)
    r = runner.invoke(app, ["grade", str(sub), "--out", str(probs)])
    assert r.exit_code == 2, r.output
    assert "p.yaml" in r.output
    assert snapshot(tmp_path) == before


def test_check_json_refuses_the_answers_file_the_problem_and_a_folder(tmp_path):
    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    sub = _answers(tmp_path)
    before = snapshot(tmp_path)
    for target in (sub, tmp_path / "p.yaml", tmp_path / "subs" / ".." / "p.yaml"):
        r = runner.invoke(app, ["check", str(sub), "--json", str(target)])
        assert r.exit_code == 2, r.output
        assert "a file robosolve reads" in r.output
        assert snapshot(tmp_path) == before
    r = runner.invoke(app, ["check", str(sub), "--json", str(tmp_path / "subs")])
    assert r.exit_code == 2 and "is a folder" in r.output and "IsADirectoryError" not in r.output
    assert snapshot(tmp_path) == before


def test_check_json_refuses_a_hard_link_to_an_input(tmp_path):
    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    sub = _answers(tmp_path)
    (tmp_path / "link.yaml").hardlink_to(sub)
    before = snapshot(tmp_path)
    r = runner.invoke(app, ["check", str(sub), "--json", str(tmp_path / "link.yaml")])
    assert r.exit_code == 2, r.output
    assert snapshot(tmp_path) == before


def test_check_json_never_replaces_a_device_or_a_pipe(tmp_path):
    """`--json /dev/null` (or a FIFO) would be replaced by a regular file by the atomic write:
    as root, the system's /dev/null itself. Refused, the special file left as it was."""
    import os
    import stat

    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    sub = _answers(tmp_path)
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    targets = [fifo]
    if os.geteuid() == 0:                     # a device node of our own (never the system's)
        os.mknod(tmp_path / "null", stat.S_IFCHR | 0o666, os.makedev(1, 3))
        targets.append(tmp_path / "null")
    for target in targets:
        kind = stat.S_IFMT(os.lstat(target).st_mode)
        r = runner.invoke(app, ["check", str(sub), "--json", str(target)])
        assert r.exit_code == 2, r.output
        assert "is a device, pipe or socket" in r.output and "'-' for standard output" in r.output
        assert stat.S_IFMT(os.lstat(target).st_mode) == kind


def test_check_json_writes_a_new_file_atomically(tmp_path):
    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    sub = _answers(tmp_path)
    r = runner.invoke(app, ["check", str(sub), "--json", str(tmp_path / "rec" / "alice.json")])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "rec" / "alice.json").read_text().startswith("{")
    assert sorted(p.name for p in (tmp_path / "rec").iterdir()) == ["alice.json"]   # no temporary left


def test_solve_in_the_working_folder_never_overwrites_its_input(tmp_path, monkeypatch):
    """`--out .` is written in place: an input named like an output (results.json) is refused."""
    from robosolve.run.outputs import OutputFolderError, write_output_folder

    monkeypatch.chdir(tmp_path)
    (tmp_path / "results.json").write_text("mine")
    (tmp_path / MARK).write_bytes(b"")
    try:
        write_output_folder(Path("."), {"results.json": b"{}"}, inputs=[tmp_path / "results.json"])
    except OutputFolderError as exc:
        assert "a file robosolve reads" in str(exc)
    else:
        raise AssertionError("wrote over an input")
    assert (tmp_path / "results.json").read_text() == "mine"
