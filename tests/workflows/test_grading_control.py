"""Answers to the closed-loop control questions (`p_control`): the errors are mappings joint ->
value (joint laws) or task coordinate -> value (task laws, `max_task_error`), and a student may
write them as a vector in the order the paper lists them (papers.md "What students may write"),
as for every other per-joint answer.

The reference errors are computed here with scipy from the closed loop itself: a Cartesian PP
robot (E = (d1, d2), J = I, no gravity along its axes), so M = diag(m1 + m2, m2) and each
coordinate is the linear loop Mᵢ·ëᵢ + Kdᵢ·ėᵢ + Kpᵢ·eᵢ = Mᵢ·ẍ_d,ᵢ, e = x_d − x, with x_d the line
(0, 0) -> (0.3, 0.4) (length 0.5) timed trapezoidally at 0.5 m/s, 2 m/s² (T = 1.25 s).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from tests._grading import grade_text, key, reference_of

PP = """
robosolve: 1
name: pp
parameters: {m1: 3, m2: 1, g: 9.81}
joints:
  - {name: d1, type: prismatic, limits: [-1, 1]}
  - {name: d2, type: prismatic, limits: [-1, 1]}
frames:
  "1": {parent: "0", pose: "Tx(d1)"}
  "2": {pose: "Ty(d2)"}
bodies:
  - {name: carriage, frame: "1", mass: m1, point: [0, 0, 0]}
  - {name: slide, frame: "2", mass: m2, point: [0, 0, 0]}
questions:
  - {type: task_trajectory, id: line, coordinates: [E.x, E.y], from: {E.x: 0, E.y: 0},
     to: {E.x: 0.3, E.y: 0.4}, max_velocity: 0.5, max_acceleration: 2}
  - {type: p_control, id: task, trajectory: line, law: task_pd_gravity,
     gains: {E.x: 400, E.y: 900}, gains_d: {E.x: 40, E.y: 30}, grade: [max_error, final_error, max_task_error]}
  - {type: p_control, id: joint, trajectory: line, law: pd_gravity,
     gains: {d1: 400, d2: 900}, gains_d: {d1: 40, d2: 30}}
grading: {entries: proportional}      # (verdicts do not depend on it; one problem solved for every test)
"""


def _errors():
    """(max |e|, e(T)) of each coordinate, integrated by scipy."""
    T, ta, a, direction = 1.25, 0.25, 2.0, np.array([0.6, 0.8])

    def s_ddot(t):
        return a if t < ta else (-a if t > T - ta else 0.0)

    out = []
    for mass, kp, kd, u in zip((4.0, 1.0), (400.0, 900.0), (40.0, 30.0), direction):
        sol = solve_ivp(lambda t, y: [y[1], u * s_ddot(t) - (kd * y[1] + kp * y[0]) / mass],
                        (0, T), [0.0, 0.0], rtol=1e-10, atol=1e-13, max_step=1e-3, dense_output=True)
        e = sol.sol(np.linspace(0, T, 5001))[0]
        out.append((np.abs(e).max(), e[-1]))
    return out


@pytest.fixture(scope="module")
def ref():
    return reference_of(PP)


@pytest.fixture(scope="module")
def errors():
    return _errors()


def _answers(question, body):
    return f"robosolve-answers: 1\nstudent: s1\nanswers:\n  {question}:\n" + "".join(
        f"    {k}: {v}\n" for k, v in body.items())


def test_control_errors_as_mappings_are_right(ref, errors):
    (mx, fx), (my, fy) = errors
    text = _answers("task", {"max_error": f"{{E.x: {mx:.4g}, E.y: {my:.4g}}}",
                             "final_error": f"{{E.x: {fx:.4g}, E.y: {fy:.4g}}}",
                             "max_task_error": f"{{E.x: {mx:.4g}, E.y: {my:.4g}}}"})
    result = grade_text(ref, text)
    assert [key(result, "task", k).verdict for k in ("max_error", "final_error", "max_task_error")] == ["correct"] * 3


@pytest.mark.parametrize("written", ["[{x}, {y}]", '"[{x} {y}]"', '"[{x}; {y}]"'])
def test_control_errors_as_vectors_in_the_papers_order_are_right(ref, errors, written):
    (mx, fx), (my, fy) = errors
    vec = lambda x, y: written.format(x=f"{x:.4g}", y=f"{y:.4g}")   # noqa: E731
    task = grade_text(ref, _answers("task", {"max_error": vec(mx, my), "final_error": vec(fx, fy),
                                             "max_task_error": vec(mx, my)}))
    assert [key(task, "task", k).verdict for k in ("max_error", "final_error", "max_task_error")] == ["correct"] * 3
    # the joint law: the joint errors of this robot are its coordinates' errors
    joint = grade_text(ref, _answers("joint", {"max_error": vec(mx, my), "final_error": vec(fx, fy)}))
    assert [key(joint, "joint", k).verdict for k in ("max_error", "final_error")] == ["correct"] * 2


def test_control_errors_as_a_vector_in_the_wrong_order_are_wrong(ref, errors):
    (mx, _), (my, _) = errors
    result = grade_text(ref, _answers("task", {"max_error": f"[{my:.4g}, {mx:.4g}]"}))
    assert key(result, "task", "max_error").verdict == "incorrect"


def test_control_errors_as_a_vector_of_another_length_are_a_wrong_shape(ref, errors):
    (mx, _), _ = errors
    result = grade_text(ref, _answers("task", {"max_error": f"[{mx:.4g}, {mx:.4g}, 0]"}))
    assert key(result, "task", "max_error").verdict == "invalid"
    assert key(result, "task", "max_error").diagnosis == "wrong_shape"


def test_entries_proportional_credits_each_right_error_of_a_control_question(ref, errors):
    """`entries: proportional` gives a per-coordinate or per-joint error the share of its entries
    that are right, as it does a per-joint Fq (grading.md)."""
    from fractions import Fraction

    (mx, fx), (my, fy) = errors
    task = grade_text(ref, _answers("task", {
        "max_error": f"{{E.x: {mx:.4g}, E.y: {2 * my:.4g}}}", "final_error": f"{{E.x: {fx:.4g}, E.y: {fy:.4g}}}",
        "max_task_error": f"{{E.x: {2 * mx:.4g}, E.y: {my:.4g}}}"}))
    assert key(task, "task", "max_error").credit == Fraction(1, 2)
    assert key(task, "task", "max_task_error").credit == Fraction(1, 2)
    question = next(q for q in task.questions if q.id == "task")
    assert question.score == Fraction(1, 3) * (Fraction(1, 2) + 1 + Fraction(1, 2))
    joint = grade_text(ref, _answers("joint", {"max_error": f"[{mx:.4g}, 1]",
                                                            "final_error": f"[{fx:.4g}, {fy:.4g}]"}))
    assert key(joint, "joint", "max_error").credit == Fraction(1, 2)
