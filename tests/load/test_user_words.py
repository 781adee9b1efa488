"""Messages in the user's words, not sympy's (issue 22): abs(...) not Abs(...), a complex value
called complex, no "declare g" when g is declared, an empty student id called empty."""

from __future__ import annotations

import json

import pytest
import sympy as sp
from typer.testing import CliRunner

from robosolve.cli import app
from robosolve.core.plain import plain
from robosolve.errors import InputError
from robosolve.grading.grader import show
from robosolve.load.loader import load_problem_text

runner = CliRunner()

DYN = """\
robosolve: 1
name: b
parameters: {L: 1, m: 2, %s}
joints: [{name: q, type: revolute}]
frames:
  "1": {pose: "Rz(q) Tx(L)"}
bodies:
  - {name: link, frame: "1", mass: m, point: [0, 0, 0]}
%s
questions:
  - {type: equations_of_motion}
"""


def messages(text):
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "p.yaml")
    return [str(i) for i in exc.value.issues]


def test_abs_printed_as_written():
    L1, L2 = sp.symbols("L1 L2")
    assert plain(sp.Abs(L1 - L2)) == "abs(L1 - L2)"
    assert show(sp.Abs(L1) * L2) == "L2*abs(L1)"


def test_ik_reason_uses_abs(write_problem, tmp_path):
    src = write_problem("""\
        robosolve: 1
        name: absr
        parameters: {L1: 1/2, L2: 2/5}
        joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
        frames:
          "1": {pose: "Rz(q1) Tx(L1)"}
          "2": {pose: "Rz(q2) Tx(L2)"}
        questions:
          - {type: inverse_kinematics, target: {E.x: 0.01, E.y: 0}}
        """)
    out = tmp_path / "o"
    assert runner.invoke(app, ["solve", str(src), "--out", str(out)]).exit_code == 0
    reason = json.loads((out / "results.json").read_text())["answers"]["inverse_kinematics"]["reason"]
    assert "< abs(L1 - L2) = 0.1" in reason and "Abs" not in reason


@pytest.mark.parametrize("value, message", [
    ("a: sqrt(-1)", "p.yaml:3: parameters.a: 'sqrt(-1)' is not a real number (it is complex, 0+1i: a square "
     "root or logarithm of a negative number, or acos/asin beyond [-1, 1]?)"),
])
def test_a_complex_parameter_is_called_complex(value, message):
    assert messages(DYN % ("g: 9.81, " + value, "")) == [message]


@pytest.mark.parametrize("params, gravity, message", [
    ("g: abc", "", "p.yaml:3: parameters.g: unknown parameter 'abc' in 'abc'"),
    ("g: 9.81", "gravity: [0, -g]", "p.yaml:9: gravity: expected a list of 3 numbers or expressions, got 2 items"),
])
def test_no_declare_g_when_g_or_gravity_is_given(params, gravity, message):
    assert messages(DYN % (params, gravity)) == [message]


def test_declare_g_still_said_when_it_is_missing():
    [m] = messages(DYN % ("a: 1", ""))
    assert "declare g in parameters" in m


@pytest.mark.parametrize("value, use", [
    ("a: sqrt(-1)", "Tx(L*a)"),             # used through an expression
    ("a: sqrt(-1)", "Tx(a)"),               # used as it is
    ("a: 1e400", "Tx(a)"),                  # too large
    ("a: log(0)", "Tx(a)"),                 # not finite
])
def test_a_refused_parameter_is_one_message_not_one_more_per_use(value, use):
    """One mistake, one message: the parameter's line, not again at every frame that uses it."""
    found = messages(DYN.replace("Rz(q) Tx(L)", "Rz(q) " + use) % ("g: 9.81, " + value, ""))
    assert len(found) == 1 and found[0].startswith("p.yaml:3: parameters.a: "), found


def test_an_unreachable_numeric_search_finds_no_solution_in_words():
    """Not "finds 0 distinct solutions, each checked with the direct kinematics"."""
    from robosolve.run.pipeline import render_files, solve_problem

    problem = load_problem_text(
        "robosolve: 1\nname: z\njoints: [{name: q1, type: revolute}, {name: q2, type: revolute}]\n"
        'frames: {"1": {pose: "Rz(q1)"}, "2": {pose: "Rz(q2)"}}\n'
        "questions:\n  - {type: inverse_kinematics, target: {E.x: 1, E.y: 0}}\n", "z.yaml")
    report = render_files(solve_problem(problem), ("md",))["report.md"].decode()
    assert "refined to machine precision finds no solution." in report
    assert "finds 0 distinct" not in report
