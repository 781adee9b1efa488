"""Odd input is refused cleanly where it is read (FILE:LINE, exit 2), never a traceback, a hang
or a silent wrong answer (issue: never touch a user's files, never crash, never hang).

Each case was a defect: a traceback, an "internal error", all-null numbers with exit 0, or a
run that did not end. The reference is the rule of problem-format.md §4 itself.
"""

import subprocess
import sys

import pytest
from typer.testing import CliRunner

from conftest import ROOT
from robosolve.cli import app

runner = CliRunner()

ARM = """\
robosolve: 1
name: t
parameters: {L: 1, a: 0, k: 2, m: 3, g: 9.81}
joints: [{name: q, type: revolute}]
frames:
  "1": {pose: "Rz(q) Tx(L)"}
"""

DYN = ARM + """\
bodies:
  - {name: link, frame: "1", mass: MASS, point: [0, 0, 0]}
questions:
  - {type: motion_profile, from: {q: 0}, to: {q: 1}, max_acceleration: {q: ACC}}
  - {type: p_control, gains: {q: 100}, DURATION}
"""


def validate(write_problem, text):
    src = write_problem(text)
    result = runner.invoke(app, ["validate", str(src)])
    assert "Traceback" not in result.output
    return result, src


@pytest.mark.parametrize("at, line, message", [
    ("{q: acos(2)}", 8, "acos(2) is not a real number"),
    ("{q: log(0)}", 8, "log(0) is undefined"),
    ("{q: 1/a}", 8, "1/a is undefined"),
    ("{q: sqrt(-1)}", 8, "is not a real number"),
    ("{q: '((9**999)**999)**999'}", 8, "too large"),
    ("{q: 'exp(exp(exp(exp(100))))'}", 8, "too large"),
    ("{q: 1e400}", 8, "too large for a floating-point number"),
])
def test_bad_at_values_are_input_errors_with_their_line(write_problem, at, line, message):
    result, src = validate(write_problem, ARM + f"questions:\n  - {{type: position, at: {at}}}\n")
    assert result.exit_code == 2
    assert f"{src}:{line}: questions[0].at.q: " in result.output
    assert message in result.output
    assert len(result.output) < 600  # no 1000-digit numbers printed


def test_at_value_uses_the_parameter_it_overrides(write_problem):
    result, _ = validate(write_problem, ARM + "questions:\n  - {type: position, at: {a: 2, q: 1/a}}\n")
    assert result.exit_code == 0, result.output


@pytest.mark.parametrize("params, message", [
    ("{k: 'exp(exp(exp(exp(100))))'}", "too large"),
    ("{k: '((9**999)**999)**999'}", "too large"),
    ("{k: '9**100', k2: 'k**9'}", "exact number of 96 digits"),   # k itself: 96 digits (MAX_EXACT_DIGITS)
    ("{k: '9**30', k2: 'k**30'}", "too large"),        # through a parameter
    ("{k: 'exp(100)', k2: 'exp(exp(k))'}", "too large"),
])
def test_huge_numbers_refused_before_evaluation(write_problem, params, message):
    # each of these used to run for minutes (big-integer or mpmath work a time limit cannot stop)
    src = write_problem(ARM.replace("parameters: {L: 1, a: 0, k: 2, m: 3, g: 9.81}",
                                    f"parameters: {params}".replace("}", ", L: 1}", 1))
                        + "questions:\n  - {type: position}\n")
    proc = subprocess.run([sys.executable, "-m", "robosolve", "validate", str(src)], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert message in proc.stderr and "parameters.k" in proc.stderr
    assert "set_int_max_str_digits" not in proc.stderr and len(proc.stderr) < 600


@pytest.mark.parametrize("mass, acc, duration, where, message", [
    ("-2", "1", "", "bodies[0].mass", "a mass cannot be negative"),
    ("-m", "1", "", "bodies[0].mass", "a mass cannot be negative"),
    ("m", "a", "", "questions[0].max_acceleration.q", "must be positive"),
    ("m", "1", "duration: 0", "questions[1].duration", "must be positive"),
    ("m", "1", "duration: -k", "questions[1].duration", "must be positive"),
])
def test_physical_values_checked_where_they_are_read(write_problem, mass, acc, duration, where, message):
    text = DYN.replace("MASS", mass).replace("ACC", acc).replace(", DURATION", f", {duration}" if duration else "")
    result, src = validate(write_problem, text)
    assert result.exit_code == 2
    assert f": {where}: {message}" in result.output, result.output
    assert result.output.startswith(f"{src}:")


def test_pose_and_matrix_values_checked(write_problem):
    text = ARM.replace('"Rz(q) Tx(L)"', '"Rz(q) Tx(sqrt(a - 1))"') + "questions:\n  - {type: position}\n"
    result, src = validate(write_problem, text)
    assert result.exit_code == 2 and f"{src}:6: frames.1.pose: Tx(sqrt(a - 1)): " in result.output
    text = ARM.replace('"1": {pose: "Rz(q) Tx(L)"}',
                       '"1": {pose: "Rz(q)"}\n  "2": {matrix: [[1, 0, 0, sqrt(-1)], [0, 1, 0, 0], [0, 0, 1, 0], '
                       '[0, 0, 0, 1]]}') + "questions:\n  - {type: position}\n"
    result, src = validate(write_problem, text)
    assert result.exit_code == 2 and "frames.2.matrix[0][3]: sqrt(-1) is not a real number" in result.output


def test_name_must_match_entirely(write_problem):
    result, src = validate(write_problem, ARM.replace("name: t", 'name: "ok\\n"') + "questions:\n  - {type: position}\n")
    assert result.exit_code == 2 and f"{src}:2: name: invalid value" in result.output


@pytest.mark.parametrize("text, hint", [("30deg", "deg(30)"), ("2L", "2*L")])
def test_parse_hints(write_problem, text, hint):
    result, _ = validate(write_problem, ARM + f"questions:\n  - {{type: position, at: {{q: {text}}}}}\n")
    assert result.exit_code == 2 and hint in result.output


# -- internal errors become answers or clear input errors ---------------------------------------

def solve_json(write_problem, tmp_path, text):
    import json

    src = write_problem(text)
    out = tmp_path / "o"
    result = runner.invoke(app, ["solve", str(src), "--out", str(out)])
    assert "internal error" not in result.output and "Traceback" not in result.output, result.output
    return result, json.loads((out / "results.json").read_text())["answers"] if out.exists() else None


def test_ik_with_zero_length_link_is_an_answer(write_problem, tmp_path):
    text = """\
robosolve: 1
name: fam
parameters: {L1: 0, L2: 1}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute, limits: [2, 3]}]
frames:
  "1": {pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: inverse_kinematics, target: {E.x: 1, E.y: 0}}
"""
    result, answers = solve_json(write_problem, tmp_path, text)
    assert result.exit_code == 0, result.output
    ik = answers["inverse_kinematics"]
    # E = (cos(q1 + q2), sin(q1 + q2)): reached for q1 + q2 = 0, q2 free in [2, 3] -> q1 = -q2
    assert ik.get("unreachable") is True and "continuum" in ik["reason"]


def test_jacobian_with_a_null_dh_alpha_is_answered(write_problem, tmp_path):
    text = """\
robosolve: 1
name: dhnull
parameters: {L1: 1, al: ~}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
dh:
  rows:
    - {theta: q1, d: 0, a: L1, alpha: al}
    - {theta: q2, d: 0, a: L1, alpha: 0}
questions:
  - {type: jacobian}
"""
    result, answers = solve_json(write_problem, tmp_path, text)
    assert result.exit_code == 0, result.output
    sym = answers["jacobian"]["symbolic"]
    assert "J" in sym
    # a symbolic twist al: det(JᵀJ) = L1⁴ (1 + c2)(1 - c2 cos 2al), zero for generic al only at
    # q2 = π (1/cos 2al is beyond ±1); a search that cannot finish says so in a note instead
    if "singularities" in sym:
        assert sym["singularities"] == [{"q2": "pi"}]
    else:
        assert any("symbolically" in n for n in answers["jacobian"]["notes"])


@pytest.mark.parametrize("matrix", ["[[k, 0, 0], [0, 1, 0], [0, 0, 1]]", "[[1, 0, 0], [0, 1, 0], [0, 0, 2]]"])
def test_orientation_of_a_non_rotation_is_an_input_error(write_problem, matrix):
    text = f"robosolve: 1\nname: o\nparameters: {{k: ~}}\nquestions:\n  - {{type: orientation, matrix: {matrix}}}\n"
    result, src = validate(write_problem, text)
    assert result.exit_code == 2 and f"{src}:5: questions[0].matrix: not a rotation" in result.output


# -- one mistake, one message; hints -------------------------------------------------------------

def test_one_mistake_one_message(write_problem):
    text = ARM.replace('"1": {pose: "Rz(q) Tx(L)"}', '"1": {pose: "Rz(q) Tx(LL)"}\n  "2": {parent: "1", pose: "Tx(L)"}') + """\
points:
  Q: {frame: "1", at: [0, 0, zz]}
bodies:
  - {name: link, frame: "1", mas: 1, point: [0, 0, 0]}
questions:
  - {type: position, frame: "1"}
  - {type: position, point: Q, id: p2}
  - {type: jacobian, coordinates: [Q.x, Q.y]}
"""
    result, src = validate(write_problem, text)
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 3, result.output        # LL, zz, mas: nothing else
    assert "unknown name 'LL'" in lines[0] and "unknown name 'zz'" in lines[1]
    assert "unknown key 'mas' (did you mean 'mass'?)" in lines[2]
    assert "missing required key" not in result.output and "unknown frame" not in result.output


def test_tab_hint_and_cannot_read_without_line(write_problem, tmp_path):
    src = write_problem("robosolve: 1\nname: tab\nparameters:\n\tL: 1\n")
    result = runner.invoke(app, ["validate", str(src), str(tmp_path / "missing.yaml")])
    assert result.exit_code == 2
    assert f"{src}:4: YAML syntax error" in result.output and "indent with spaces" in result.output
    assert f"{tmp_path / 'missing.yaml'}: cannot read the file" in result.output
    assert f"{tmp_path / 'missing.yaml'}:1:" not in result.output


def test_batch_messages_printed_once_and_unwrapped(tmp_path):
    long_name = "a_parameter_with_a_very_long_name_" * 3
    (tmp_path / "bad.yaml").write_text(ARM.replace("Tx(L)", f"Tx({long_name})")
                                       + "questions:\n  - {type: position}\n")
    proc = subprocess.run([sys.executable, "-m", "robosolve", "batch", str(tmp_path), "--out", str(tmp_path / "o"),
                           "--jobs", "1"], cwd=ROOT, capture_output=True, text=True, timeout=300,
                          env={"COLUMNS": "60", "PATH": "/usr/bin:/bin", "PYTHONPATH": str(ROOT)})
    assert proc.returncode == 2
    hits = [ln for ln in proc.stderr.splitlines() if ln.startswith(f"{tmp_path / 'bad.yaml'}:6: frames.1.pose:")]
    assert len(hits) == 1 and long_name in hits[0], proc.stderr


def test_every_body_without_mass_under_p_control_is_an_input_error(write_problem):
    result, src = validate(write_problem, DYN.replace("MASS", "0").replace("ACC", "1").replace(", DURATION", ""))
    assert result.exit_code == 2 and "mass matrix M(q) is singular" in result.output


# -- budgets: counted, so the same everywhere; safety nets that cannot be swallowed ------------

def test_symbolic_step_over_the_node_budget_is_skipped_deterministically():
    import sympy as sp

    from robosolve.solvers.task_space import limited
    from robosolve.solvers.base import Budgets

    class Ctx:
        budgets = Budgets(symbolic_nodes=50)

        def time_limit(self, seconds):
            raise AssertionError("over the count: the clock is not even started")

    q = sp.symbols("q1:9")
    big = sp.Matrix([[sp.cos(a + b) * sp.sin(a) for a in q] for b in q])   # far more than 50 nodes
    called = []
    out, why = limited(Ctx(), 30, lambda m: called.append(m), big)
    assert out is None and not called and "expression nodes, above the budget of 50" in why


def test_question_budget_cannot_be_swallowed(write_problem, monkeypatch):
    """A solver that catches SymbolicTimeout without looking at its token still ends: the
    per-question safety net is raised again until the question is over."""
    import robosolve.solvers.position as position
    from robosolve.errors import SymbolicTimeout
    from robosolve.load.loader import load_problem
    from robosolve.run.pipeline import solve_problem
    from robosolve.solvers.base import Budgets

    def stubborn(question, ctx):
        try:
            while True:
                sum(i * i for i in range(10_000))
        except SymbolicTimeout:
            pass              # swallowed, as a careless fallback would
        while True:           # more work: only the repeated expiry stops it
            sum(i * i for i in range(10_000))

    monkeypatch.setattr(position, "solve", stubborn)
    problem = load_problem(write_problem(ARM + "questions:\n  - {type: position}\n  - {type: dof, bodies: 2, joints_1dof: 1}\n"))
    report = solve_problem(problem, Budgets(question_seconds=0.3))
    assert "exceeded its budget" in report.answers[0].error
    assert report.answers[1].error is None        # the next question is still answered


def test_a_swallowed_expiry_is_raised_again():
    """An expiry that lands where Python ignores it (a finaliser run by the garbage
    collector, an `except Exception` inside sympy) must not let the block run on unlimited:
    the limit raises again until the block ends (this let a 1 µs limit derive a whole
    model once, and the numeric-only route was not taken)."""
    import time

    from robosolve.core.timing import time_limit
    from robosolve.errors import SymbolicTimeout

    swallowed = []
    with pytest.raises(SymbolicTimeout):
        with time_limit(0.01):
            end = time.process_time() + 3.0
            while time.process_time() < end:
                try:
                    while time.process_time() < end and not swallowed:
                        pass
                    if swallowed:
                        while time.process_time() < end:
                            pass
                except SymbolicTimeout:
                    if swallowed:
                        raise
                    swallowed.append(1)   # the first expiry is lost, as in a finaliser
    assert swallowed
