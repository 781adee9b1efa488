"""A path the system cannot look up (a name longer than it allows, a loop of symbolic links),
given on the command line or as an answers file's `problem:`, is a usage error in words at
once: exit 2, nothing written, never `OSError: File name too long` (issue 22)."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from robosolve.cli import app
from tests.conftest import MINI

runner = CliRunner()
LONG = "x" * 300

ANSWERS = """\
robosolve-answers: 1
problem: {problem}
student: s1
answers:
  position:
    position: [1, 0, 0]
"""


def _files(tmp_path, problem="p.yaml"):
    (tmp_path / "p.yaml").write_text(MINI, encoding="utf-8")
    (tmp_path / "a.yaml").write_text(ANSWERS.format(problem=problem), encoding="utf-8")
    return str(tmp_path / "p.yaml"), str(tmp_path / "a.yaml")


def _commands(p, a, bad):
    return {
        "solve --out": ["solve", p, "--out", bad],
        "solve file": ["solve", bad + ".yaml"],
        "validate": ["validate", bad + ".yaml"],
        "batch --out": ["batch", p, "--out", bad],
        "batch source": ["batch", bad, "--out", "o"],
        "batch --check": ["batch", p, "--check", bad],
        "paper --out": ["paper", p, "--out", bad],
        "variants --out": ["variants", p, "--count", "1", "--out", bad],
        "variants --roster": ["variants", p, "--roster", bad + ".csv", "--out", "o"],
        "check --json": ["check", a, "--json", bad + ".json"],
        "check --problem": ["check", a, "--problem", bad + ".yaml"],
        "grade --out": ["grade", a, "--problem", p, "--out", bad],
        "grade submission": ["grade", bad + ".yaml", "--out", "o"],
        "grade --variants": ["grade", a, "--variants", bad, "--out", "o"],
    }


@pytest.mark.parametrize("case", list(_commands("p", "a", "b")))
def test_a_name_too_long_for_the_system_is_a_usage_error(tmp_path, monkeypatch, case):
    monkeypatch.chdir(tmp_path)
    p, a = _files(tmp_path)
    before = sorted(x.name for x in tmp_path.iterdir())
    r = runner.invoke(app, _commands(p, a, LONG)[case])
    assert r.exit_code == 2, r.output
    assert r.exception is None or isinstance(r.exception, SystemExit), repr(r.exception)
    words = " ".join(r.output.replace("│", " ").split())
    assert any(f"has {n} characters" in words for n in (300, 304, 305)), words
    assert "the system allows at most 255" in words
    assert sorted(x.name for x in tmp_path.iterdir()) == before


def test_a_loop_of_links_is_said(tmp_path):
    (tmp_path / "l1").symlink_to(tmp_path / "l2")
    (tmp_path / "l2").symlink_to(tmp_path / "l1")
    r = runner.invoke(app, ["solve", str(tmp_path / "l1")])
    assert r.exit_code == 2
    assert "loop of symbolic links" in " ".join(r.output.replace("│", " ").split())


@pytest.mark.parametrize("command", ["check", "grade"])
def test_an_answers_problem_too_long_is_said_at_its_line(tmp_path, command):
    _, a = _files(tmp_path, problem=LONG + ".yaml")
    args = ["check", a] if command == "check" else ["grade", a, "--out", str(tmp_path / "o")]
    r = runner.invoke(app, args)
    assert r.exception is None or isinstance(r.exception, SystemExit), repr(r.exception)
    assert r.exit_code == (2 if command == "check" else 1), r.output
    words = " ".join(r.output.replace("│", " ").split())
    # rich folds a long line wherever the terminal ends (a longer tmp path moves the fold), so
    # the place is looked for with the whitespace taken out
    assert f"{a}:2:problem:" in "".join(words.split()), words
    assert "has 305 characters" in words


def test_an_answers_problem_with_a_nul_is_said_at_its_line(tmp_path):
    _, a = _files(tmp_path, problem='"a\\0b"')
    r = runner.invoke(app, ["check", a])
    assert r.exit_code == 2, r.output
    assert f"{a}:2: problem: 'a\\0b': a path cannot hold a NUL character" in r.output
