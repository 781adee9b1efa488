"""Actuator laws and forces of time that leave their domain (log, sqrt of a negative number):
an input error with its line when the run starts there (t = 0), else the question's error saying
where the equations stop having a value — never an internal error (`math domain error`)."""

from __future__ import annotations

import pytest
import sympy as sp

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import solve_problem
from robosolve.simulation.forward import RunUndefined, compile_plant, integrate
from robosolve.simulation.joint_control import SimulationTooLong, _Budget

ARM = """\
robosolve: 1
name: arm
parameters: {L: 1, m: 1, g: 9.81}
joints: [{name: q, type: revolute, actuator: C}]
frames:
  "1": {pose: "Rx(q) Ty(L)"}
bodies: [{name: b, frame: "1", mass: m, point: [0, 0, 0]}]
%s
questions:
%s
"""


def messages(text) -> list[str]:
    try:
        load_problem_text(text, "f.yaml")
    except InputError as exc:
        return [str(i) for i in exc.issues]
    return []


def test_an_actuator_law_without_value_at_the_start_is_an_input_error():
    text = ARM % ("", "  - {type: forward_dynamics, actuators: {C: 'log(t - 2)'}, start: {q: 1}, duration: 1}")
    assert messages(text) == [
        "f.yaml:10: questions[0].actuators.C: the law has no value at the start of the run (t = 0, the "
        "`start` state): log(t - 2) is not a real number (it is 0.693147+3.14159i: a square root or logarithm "
        "of a negative number, or acos/asin beyond [-1, 1]?)"]
    # sqrt(q - 1) is 0 at the start q = 1: defined there (where the run goes is the run's to say)
    assert messages(ARM % ("", "  - {type: forward_dynamics, actuators: {C: 'sqrt(q - 1)'}, start: {q: 1}, "
                                "duration: 1}")) == []


def test_a_force_without_value_at_t_0_is_an_input_error():
    text = ARM % ("forces: [{name: P, frame: '1', force: [0, 'log(-1 - t)', 0]}]",
                  "  - {type: forward_dynamics, duration: 1}")
    assert messages(text) == [
        "f.yaml:8: forces[0].force[1]: no value at t = 0, where every run starts: log(-1 - t) is not a real "
        "number (it is 0+3.14159i: a square root or logarithm of a negative number, or acos/asin beyond "
        "[-1, 1]?)"]


def test_a_run_stops_where_its_law_has_no_value():
    """q'' = log(1 - t): defined on [0, 1) only (closed form), so a run of 2 s stops at t = 1."""
    t, q, qd = sp.symbols("t q qd")
    plant = compile_plant(sp.Matrix([[1]]), [0], [0], [sp.log(1 - t)], [q], [qd], t)
    with pytest.raises(RunUndefined, match=r"no value at t = 1 s \(math domain error"):
        integrate(plant, [0.0], [0.0], 2.0)


def test_a_run_that_overflows_says_so():
    """q'' = exp(1000*q) from q = 1: exp(1000) is beyond the floats (about 1.8e308) at once."""
    t, q, qd = sp.symbols("t q qd")
    plant = compile_plant(sp.Matrix([[1]]), [0], [0], [sp.exp(1000 * q)], [q], [qd], t)
    with pytest.raises(RunUndefined, match=r"overflow at t = 0 s \(a value beyond the range"):
        integrate(plant, [1.0], [0.0], 1.0)


def test_a_closed_loop_stops_where_a_force_has_no_value():
    def rhs(t, y):
        import math
        return [math.sqrt(0.5 - t)]
    guarded = _Budget(100, None, lambda why: why).guard(rhs)
    assert guarded(0.0, [0.0]) == [pytest.approx(0.5 ** 0.5)]
    with pytest.raises(SimulationTooLong, match=r"no value at t = 0.75 s"):
        guarded(0.75, [0.0])


def test_joint_torques_along_a_profile_past_a_force_domain_is_an_answer_error():
    text = ARM % ("forces: [{name: P, frame: '1', force: [0, 0, 'log(1/2 - t)']}]",
                  "  - {type: motion_profile, from: {q: 0}, to: {q: 1}, max_acceleration: {q: 1}}\n"
                  "  - {type: joint_torques}")
    report = solve_problem(load_problem_text(text, "f.yaml"))
    error = report.answers[1].error
    assert error is not None and "no value along the profile" in error and "internal" not in error


SLIDER = """\
robosolve: 1
name: slider
parameters: {m: 2}
gravity: [0, 0, 0]
joints: [{name: x, type: prismatic, actuator: F1}]
frames:
  "1": {pose: "Tx(x)"}
bodies: [{name: b, frame: "1", mass: m, point: [0, 0, 0]}]
%s
questions:
  - {type: forward_dynamics, duration: 3%s}
"""


@pytest.mark.parametrize("force, law", [
    ('forces: [{name: P, frame: "1", force: [t, 0, 0], in: "0"}]', ""),
    ("", ", actuators: {F1: t}"),
])
def test_a_force_or_law_that_is_t_itself_is_read_and_followed(force, law):
    """A force component or an actuator law written as `t` alone (0 at the start) was an internal
    error ('int' object has no attribute 'is_Integer'): its value at t = 0 is a plain 0. The slider
    pushed by t from rest: m x'' = t, x(T) = T³/(6m), x'(T) = T²/(2m) (closed form)."""
    problem = load_problem_text(SLIDER % (force, law), "s.yaml")
    answer = solve_problem(problem).answers[0]
    assert answer.error is None
    T, m = 3.0, 2.0
    assert answer.numeric["final"]["x"] == pytest.approx(T**3 / (6 * m), rel=1e-7)
    assert answer.numeric["final_velocity"]["x"] == pytest.approx(T**2 / (2 * m), rel=1e-7)
