"""Command-line values the problem file would refuse are refused on the command line too, and
what a command leaves out it says (issue 22)."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from robosolve.cli import app
from tests._grading import dedent
from tests.workflows.test_grading_grade import ALICE, PROBLEM

runner = CliRunner()


@pytest.mark.parametrize("command", ["check", "grade"])
@pytest.mark.parametrize("flag,value", [("--rtol", "-1"), ("--rtol", "nan"), ("--atol", "-1"),
                                        ("--atol", "inf"), ("--rtol", "-inf")])
def test_bad_tolerances_are_usage_errors(tmp_path, command, flag, value):
    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    (tmp_path / "subs").mkdir()
    sub = tmp_path / "subs" / "alice.yaml"
    sub.write_text(dedent(ALICE), encoding="utf-8")
    args = [command, str(sub), flag, value] + (["--out", str(tmp_path / "o")] if command == "grade" else [])
    r = runner.invoke(app, args)
    assert r.exit_code == 2, r.output
    assert "expected a number >= 0" in r.output and flag in r.output
    assert not (tmp_path / "o").exists()


def test_good_tolerances_pass_the_option_check():
    from robosolve.cli.common import _tolerance

    assert _tolerance(None) is None and _tolerance(0.0) == 0.0 and _tolerance(0.01) == 0.01


def test_a_dangling_link_in_a_submissions_folder_is_said(tmp_path):
    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "alice.yaml").write_text(dedent(ALICE), encoding="utf-8")
    (subs / "bob.yaml").symlink_to(tmp_path / "gone" / "bob.yaml")
    r = runner.invoke(app, ["grade", str(subs), "--out", str(tmp_path / "o"), "--jobs", "1"])
    assert r.exit_code == 0, r.output
    assert f"{subs / 'bob.yaml'}: skipped: a symbolic link to" in r.output
    assert "does not exist" in r.output


def test_only_dangling_links_is_a_usage_error_that_names_them(tmp_path):
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "bob.yaml").symlink_to(tmp_path / "gone.yaml")
    r = runner.invoke(app, ["grade", str(subs), "--out", str(tmp_path / "o")])
    assert r.exit_code == 2
    assert "bob.yaml: skipped" in r.output and "no answers files found" in r.output


def test_a_folder_of_student_folders_says_where_the_answers_are(tmp_path):
    """An LMS's download (one folder per student) is not searched below the folder given: the
    message names the folders that hold answers files and how to give them; nothing is written."""
    subs = tmp_path / "subs"
    for who in ("lee_102", "smith_101"):
        (subs / who).mkdir(parents=True)
        (subs / who / "answers.yaml").write_text(dedent(ALICE), encoding="utf-8")
    r = runner.invoke(app, ["grade", str(subs), "--out", str(tmp_path / "o")])
    assert r.exit_code == 2
    words = " ".join(r.output.split())
    assert "no answers files found" in words and "2 of those hold answers files" in words
    assert str(subs / "lee_102") in words and f"robosolve grade {subs / '*'}" in words
    assert not (tmp_path / "o").exists()


def test_upper_case_suffixes_are_answers_files(tmp_path):
    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "ALICE.YAML").write_text(dedent(ALICE), encoding="utf-8")
    r = runner.invoke(app, ["grade", str(subs), "--out", str(tmp_path / "o"), "--jobs", "1"])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "o" / "summary.csv").read_text().count("\n") == 2


def test_missing_extras_are_said_at_once_with_both_install_forms(monkeypatch, tmp_path):
    import importlib.util

    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name in ("latex2mathml", "nbformat") else real(name, *a))
    (tmp_path / "p.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    r = runner.invoke(app, ["solve", str(tmp_path / "p.yaml"), "--format", "md,html,ipynb",
                            "--out", str(tmp_path / "o")])
    assert r.exit_code == 2
    lines = [ln for ln in r.output.splitlines() if ln.strip()]
    assert len(lines) == 1, r.output                               # one message, not one per extra
    assert "latex2mathml" in lines[0] and "nbformat" in lines[0]
    assert "pip install 'robosolve[html,notebook]'" in lines[0] and "pip install '.[html,notebook]'" in lines[0]
    assert not (tmp_path / "o").exists()


def test_one_is_singular_in_what_the_commands_say(tmp_path):
    """'ok (1 question)', 'paper of 1 question', '1 variant of': the plural of one (issue 22)."""
    from tests.conftest import MINI

    p = tmp_path / "p.yaml"
    p.write_text(MINI + "variants:\n  parameters:\n    L: {choices: [1, 2]}\n", encoding="utf-8")
    r = runner.invoke(app, ["validate", str(p)])
    assert r.exit_code == 0 and f"{p}: ok (1 question)\n" in r.output, r.output
    r = runner.invoke(app, ["paper", str(p), "--out", str(tmp_path / "paper")])
    assert r.exit_code == 0 and "paper of 1 question ->" in r.output, r.output
    r = runner.invoke(app, ["variants", str(p), "--count", "1", "--no-solve", "--out", str(tmp_path / "v")])
    assert r.exit_code == 0 and "1 variant of mini" in r.output, r.output


@pytest.mark.parametrize("special", ["/dev/zero", "fifo"])
def test_batch_of_a_device_or_a_pipe_says_it_is_not_a_regular_file(tmp_path, special):
    import os

    if special == "fifo":
        special = str(tmp_path / "pipe.yaml")
        os.mkfifo(special)
    r = runner.invoke(app, ["batch", special, "--out", str(tmp_path / "o")])
    assert r.exit_code == 2
    assert "not a regular file" in r.output and "no problem files found" not in r.output
    assert not (tmp_path / "o").exists()


def test_batch_of_a_folder_without_problems_says_none_found(tmp_path):
    r = runner.invoke(app, ["batch", str(tmp_path), "--out", str(tmp_path / "o")])
    assert r.exit_code == 2 and "no problem files found" in r.output


def test_a_defect_is_one_line_saying_where_never_a_traceback():
    """The last resort of every command (a `require` that divided by zero once ended `variants`
    with a Python traceback): one line naming the exception and robosolve's file and line."""
    import re
    import subprocess
    import sys

    code = ("import robosolve.cli.common as c\n"
            "def app():\n"
            "    raise TypeError('Cannot convert complex to float')\n"
            "c.app = app\n"
            "c.main()\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert r.returncode == 1
    assert "Traceback" not in r.stderr
    assert re.match(r"internal error \(TypeError: Cannot convert complex to float, at robosolve/[\w/]+\.py:\d+\): "
                    r"this is a bug in robosolve", r.stderr), r.stderr
    assert r.stderr.count("\n") == 1


@pytest.mark.parametrize("command", [["solve", "{d}/arn.yaml"], ["check", "{d}/a.yaml", "--problem", "{d}/arn.yaml"]])
def test_a_missing_problem_file_gets_a_did_you_mean(tmp_path, command):
    """A misspelt file name: the YAML files beside it are the candidates, compared without the
    suffix (every one ends in .yaml: 'zzzzz.yaml' means none of them)."""
    (tmp_path / "arm.yaml").write_text(dedent(PROBLEM), encoding="utf-8")
    (tmp_path / "a.yaml").write_text("robosolve-answers: 1\nanswers: {}\n", encoding="utf-8")
    r = runner.invoke(app, [c.format(d=tmp_path) for c in command])
    assert r.exit_code == 2
    assert f"(did you mean '{tmp_path / 'arm.yaml'}'?)" in " ".join(r.output.split()), r.output
    far = runner.invoke(app, ["solve", str(tmp_path / "zzzzz.yaml")])
    assert far.exit_code == 2 and "did you mean" not in far.output
