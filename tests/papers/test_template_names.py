"""The answers template writes a student's id in UTF-8 as it is (students read the file: it said
`student: "Jos\\u00e9 \\u00c1lvarez"`), escaping only what YAML cannot hold in quotes; PyYAML
(an independent reader) and robosolve's reader read back the id exactly, and `grade` matches
each template to its roster row."""

from __future__ import annotations

import csv
import re

import pytest
import yaml
from typer.testing import CliRunner

from robosolve.cli import app
from robosolve.grading.answers import read_answers_text
from robosolve.load.loader import load_problem_text
from robosolve.papers.template import render_template

runner = CliRunner()

ARM = """\
robosolve: 1
name: arm
parameters: {L1: 1/2, L2: 2/5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: position, id: pos, at: {q1: pi/6, q2: pi/3}}
"""

READABLE = ["José Álvarez", "Jo \"Bob\" O'Brien", "Smith: John", "- Lee", "# Kim", "李小龍", "Zoë #2: a\\b",
            "yes", "123", "[x]", "{a: 1}", "&anchor *alias !tag", "% % ` @"]
UNREADABLE = ["tab\there", "two\nlines", "nel\x85x", "sep\u2028x", "\ufeffbom", "del\x7f", "bell\x07"]


def _student_line(text: str) -> str:
    return next(line for line in text.splitlines() if line.startswith("student: "))


@pytest.mark.parametrize("name", READABLE + UNREADABLE)
def test_the_student_id_reads_back_exactly(name):
    problem = load_problem_text(ARM, "arm.yaml")
    text = render_template(problem, "arm.yaml", name)
    assert yaml.safe_load(text)["student"] == name
    assert read_answers_text(text, "answers.yaml").student == name.strip()
    line = _student_line(text)
    if name in READABLE:
        assert name.replace("\\", "\\\\").replace('"', '\\"') in line
        assert not re.search(r"\\u[0-9a-f]{4}", line)


def test_a_roster_of_such_names_is_graded_one_template_each(tmp_path):
    names = ["José Álvarez", "Jo \"Bob\" O'Brien", "Smith: John", "- Lee", "# Kim"]
    (tmp_path / "arm.yaml").write_text(ARM + "variants:\n  parameters:\n    L1: {choices: [0.3, 0.5, 0.7, 0.9, 1.1]}\n",
                                       encoding="utf-8")
    with open(tmp_path / "roster.csv", "w", newline="", encoding="utf-8") as f:
        csv.writer(f).writerows([["student"]] + [[n] for n in names])
    r = runner.invoke(app, ["variants", str(tmp_path / "arm.yaml"), "--roster", str(tmp_path / "roster.csv"),
                            "--out", str(tmp_path / "ex"), "--no-solve"])
    assert r.exit_code == 0, r.output
    subs = tmp_path / "subs"
    subs.mkdir()
    for i, template in enumerate(sorted((tmp_path / "ex").glob("*/answers.yaml"))):
        text = template.read_text(encoding="utf-8")
        assert "\\u" not in _student_line(text)
        # no `problem:` line: the submission is matched through the roster by its student id
        (subs / f"s{i}.yaml").write_text("".join(line for line in text.splitlines(keepends=True)
                                                 if not line.startswith("problem:")), encoding="utf-8")
    r = runner.invoke(app, ["grade", str(subs), "--variants", str(tmp_path / "ex"), "--out", str(tmp_path / "g"),
                            "-j", "1"])
    assert r.exit_code == 0, r.output           # graded (every key missing), no input error
    with open(tmp_path / "g" / "grades.csv", encoding="utf-8") as f:
        assert sorted({row["student"] for row in csv.DictReader(f)}) == sorted(names)
