"""Inputs that ended in a traceback or an `internal error` (issue 22) get a clear message at their
line, or an answer: the default point's name taken, a very long student id, a variants table
that is not UTF-8 or starts with a byte-order mark, a chain whose point does not move, a number
of 5000 digits."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from robosolve.cli import app
from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text

runner = CliRunner()

ONE = """\
robosolve: 1
name: one
parameters: {L: 1}
joints: [{name: q, type: revolute}]
frames:
  "1": {pose: "Rz(q) Tx(L)"}
questions:
  - {type: position, at: {q: 0}}
"""


def issues(text):
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "p.yaml")
    return [str(i) for i in exc.value.issues]


@pytest.mark.parametrize("text, where", [
    (ONE.replace("{L: 1}", "{L: 1, E: 2}").replace("Tx(L)", "Tx(L*E)"), "p.yaml:3: parameters.E: "),
    (ONE.replace("name: q,", "name: E,").replace("Rz(q)", "Rz(E)").replace("{q: 0}", "{E: 0}"),
     "p.yaml:4: joints[0].name: "),
    (ONE.replace("type: revolute}", "type: revolute, actuator: E}"), "p.yaml:4: joints[0].actuator: "),
])
def test_the_default_points_name_is_refused_once_where_it_is_declared(text, where):
    assert issues(text) == [where + "'E' is the name of the end point (by default the origin of the "
                            "last frame, used by every question without `point`; E.x is its x): "
                            "choose another name, such as E_1 or Ey"]


def test_a_5000_digit_integer_is_too_long_at_its_line():
    found = issues(ONE.replace("{L: 1}", "{L: " + "1" * 5000 + "}"))
    assert found == ["p.yaml:3: parameters.L: number too long (5000 digits; at most 4300)"]


def test_ik_of_a_point_that_does_not_move(write_problem, tmp_path):
    src = write_problem("""\
        robosolve: 1
        name: still
        joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
        frames: {"1": {pose: "Rz(q1)"}, "2": {pose: "Rz(q2)"}}
        questions:
          - {type: inverse_kinematics, id: here, target: {E.x: 0, E.y: 0}}
          - {type: inverse_kinematics, id: there, target: {E.x: 1, E.y: 0}}
        """)
    out = tmp_path / "o"
    result = runner.invoke(app, ["solve", str(src), "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert "internal error" not in result.output
    answers = json.loads((out / "results.json").read_text())["answers"]
    here, there = answers["here"], answers["there"]
    assert here["numeric"]["selected"] == {"q1": 0.0, "q2": 0.0}
    assert any("does not depend on them" in n and "every configuration" in n for n in here["notes"])
    assert there["unreachable"] is True and there["reason"] == "E.x is 0 whatever the joints, but the target asks 1"


def _variants_folder(tmp_path, table: bytes):
    for v in ("1", "2"):
        (tmp_path / f"exam-{v}").mkdir()
        (tmp_path / f"exam-{v}" / "problem.yaml").write_text("robosolve: 1\n")
    (tmp_path / "variants.csv").write_bytes(table)
    return tmp_path


def test_variants_table_with_a_byte_order_mark_is_read(tmp_path):
    from robosolve.grading.grade import read_variants

    folder = _variants_folder(tmp_path, "\ufeffvariant,student,seed\n1,alice,0\n2,bob,0\n".encode("utf-8"))
    assert read_variants(folder).match("bob", None).problem == folder / "exam-2" / "problem.yaml"


def test_variants_table_not_utf8_is_reported_at_its_line(tmp_path):
    from robosolve.grading.grade import UsageError, read_variants

    folder = _variants_folder(tmp_path, b"variant,student,seed\n1,alice,0\n2,b\xe9b,0\n")
    with pytest.raises(UsageError) as exc:
        read_variants(folder)
    assert str(exc.value) == (f"{folder / 'variants.csv'}:3: the variants table is not UTF-8 text: "
                              "byte 0xe9 at column 4 (save it as UTF-8)")


def test_a_300_character_student_id_gets_a_short_safe_file_name():
    from robosolve.variants.naming import MAX_NAME, safe_name

    long_id, other = "s" * 300, "s" * 299 + "t"
    name = safe_name(long_id)
    assert len(name) == MAX_NAME and name.startswith("s" * 50) and name != safe_name(other)
    assert safe_name("Jo Smith") == "jo-smith"           # short ids unchanged


def test_grade_with_a_300_character_student_id(tmp_path):
    from tests._grading import TWO_R, dedent

    (tmp_path / "p.yaml").write_text(dedent(TWO_R), encoding="utf-8")
    sub = tmp_path / "a.yaml"
    sub.write_text(f"robosolve-answers: 1\nproblem: p.yaml\nstudent: {'x' * 300}\n"
                   "answers:\n  jacobian: {det: \"L1*L2*sin(q2)\"}\n", encoding="utf-8")
    out = tmp_path / "grades"
    result = runner.invoke(app, ["grade", str(sub), "--out", str(out)])
    assert "Traceback" not in result.output and "File name too long" not in result.output
    records = [p.name for p in out.glob("*.json")]
    assert len(records) == 1 and len(records[0]) < 80, records


def test_empty_student_id_stands_for_the_file_name(tmp_path):
    """papers.md: a template's `student: ""` (no roster) is valid; the file's name stands."""
    from robosolve.grading.answers import read_answers_text

    sub = read_answers_text('robosolve-answers: 1\nstudent: ""\nanswers: {q: {T: 1}}\n', "a.yaml")
    assert [str(i) for i in sub.issues] == [] and sub.student == "a"


def test_grade_says_which_blank_student_ids_took_the_file_name(tmp_path):
    """`student: ""` or `~` (a template's blank) is graded under the file's name, and `grade`
    says so at the line, in the user's words, never "expected the student's id, got a string"."""
    from tests.conftest import MINI

    (tmp_path / "p.yaml").write_text(MINI, encoding="utf-8")
    body = "robosolve-answers: 1\nproblem: p.yaml\nstudent: {}\nanswers:\n  position:\n    position: [1, 0, 0]\n"
    for name, value in (("alice", '""'), ("bob", "~"), ("carl", '"  "'), ("dan", "s42")):
        (tmp_path / f"{name}.yaml").write_text(body.format(value), encoding="utf-8")
    result = runner.invoke(app, ["grade", *(str(tmp_path / f"{n}.yaml") for n in ("alice", "bob", "carl", "dan")),
                                 "--out", str(tmp_path / "g"), "--jobs", "1"])
    assert result.exit_code == 0, result.output
    for name in ("alice", "bob", "carl"):
        assert (f"{tmp_path / name}.yaml:3: student: empty; graded under the file's name, '{name}'"
                in result.output), result.output
    assert "dan.yaml:3" not in result.output and "got a string" not in result.output
    assert sorted(p.stem for p in (tmp_path / "g").glob("*.json")) == ["alice", "bob", "carl", "s42"]


def test_a_student_id_of_the_wrong_kind_says_what_an_id_is():
    from robosolve.grading.answers import read_answers_text

    sub = read_answers_text('robosolve-answers: 1\nstudent: [a]\nanswers: {q: {T: 1}}\n', "a.yaml")
    assert [str(i) for i in sub.issues] == [
        'a.yaml:2: student: expected the student\'s id (a name or a number, such as s123456 or "Jo Smith"), '
        "got a list"]


def test_a_yaml_tag_in_a_problem_file_is_one_line_at_its_path():
    found = issues(ONE.replace("{L: 1}", "{L: !custom 1}"))
    assert found == ["p.yaml:3: parameters.L: invalid value '1': the YAML tag '!custom' is not one robosolve "
                     "reads (write the value without it)"]
