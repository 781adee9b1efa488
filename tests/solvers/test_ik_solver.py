"""The inverse_kinematics question through the pipeline: layouts of the spec, odd cases, goldens."""

from __future__ import annotations

import math

import pytest
from pathlib import Path

from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import solve_problem
from robosolve.render.results_json import results_document

ROOT = Path(__file__).resolve().parents[2]

PLANAR_2R = """
robosolve: 1
name: ik-2r
parameters: {L1: 0.6, L2: 0.5, F: ~}
joints:
  - {name: theta1, type: revolute}
  - {name: theta2, type: revolute, limits: [0, pi]}
frames:
  "1": {parent: "0", pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
questions:
"""


def _solve(questions: str, head: str = PLANAR_2R):
    problem = load_problem_text(head + questions, "test.yaml")
    report = solve_problem(problem)
    return report, results_document(report, {})["answers"]


def test_layout_solutions_selected_closed_form_qdot():
    report, ans = _solve("  - {type: inverse_kinematics, target: {E.x: 0.7, E.y: 0.4}, velocity: {E.x: 0.1, E.y: 0}}\n")
    a = ans["inverse_kinematics"]
    assert "unreachable" not in a and "error" not in a
    sols = a["numeric"]["solutions"]
    assert len(sols) == 1 and list(sols[0]) == ["theta1", "theta2"]    # theta2 < 0 rejected
    assert a["numeric"]["selected"] == sols[0]
    assert set(a["numeric"]["q_dot"]) == {"theta1", "theta2"}
    assert len(a["symbolic"]["closed_form"]) == 2
    md = "\n".join(s.title for s in report.answers[0].steps)
    assert "Every solution" in md
    table = [s for s in report.answers[0].steps if s.table][-1].table
    assert any("rejected" in row[-1] and "lower limit" in row[-1] for row in table[1])

    # values, against the textbook closed form of the planar 2R arm (independent of robosolve):
    # cos t2 = (x^2 + y^2 - L1^2 - L2^2) / (2 L1 L2), t1 = atan2(y, x) - atan2(L2 s2, L1 + L2 c2);
    # theta2 limited to [0, pi] keeps the elbow-down branch t2 > 0
    L1, L2, x, y = 0.6, 0.5, 0.7, 0.4
    t2 = math.acos((x * x + y * y - L1 * L1 - L2 * L2) / (2 * L1 * L2))
    t1 = math.atan2(y, x) - math.atan2(L2 * math.sin(t2), L1 + L2 * math.cos(t2))
    assert math.isclose(sols[0]["theta1"], t1, abs_tol=1e-9)
    assert math.isclose(sols[0]["theta2"], t2, abs_tol=1e-9)
    # velocity IK: q_dot = J^-1 v, J of the same closed form
    j = [[-L1 * math.sin(t1) - L2 * math.sin(t1 + t2), -L2 * math.sin(t1 + t2)],
         [L1 * math.cos(t1) + L2 * math.cos(t1 + t2), L2 * math.cos(t1 + t2)]]
    det = j[0][0] * j[1][1] - j[0][1] * j[1][0]
    qd1 = (j[1][1] * 0.1 - j[0][1] * 0.0) / det
    qd2 = (-j[1][0] * 0.1 + j[0][0] * 0.0) / det
    assert math.isclose(a["numeric"]["q_dot"]["theta1"], qd1, rel_tol=1e-9)
    assert math.isclose(a["numeric"]["q_dot"]["theta2"], qd2, rel_tol=1e-9)


def test_unreachable_is_an_answer():
    report, ans = _solve("  - {type: inverse_kinematics, target: {E.x: 1.31, E.y: 0}}\n")
    a = ans["inverse_kinematics"]
    assert report.exit_status == 0
    assert a["unreachable"] is True and a["numeric"]["solutions"] == []
    assert "1.31 > L1 + L2 = 1.1" in a["reason"]


def test_select_nearest():
    head = PLANAR_2R.replace("limits: [0, pi]", "limits: [-pi, pi]")
    _, ans = _solve("  - {type: inverse_kinematics, target: {E.x: 0.7, E.y: 0.4}, "
                    "select: {theta1: 1, theta2: -1}}\n", head)
    assert ans["inverse_kinematics"]["numeric"]["selected"]["theta2"] < 0


def test_overdetermined_is_explained():
    report, ans = _solve("  - {type: inverse_kinematics, target: {E.x: 0.7, E.y: 0.4, 'theta1 + theta2': 0.5}}\n")
    a = ans["inverse_kinematics"]
    assert "Choose 2 of the 3 equations" in a["error"]
    assert report.exit_status == 1


def test_redundant_family_in_closed_form():
    head = PLANAR_2R
    _, ans = _solve("  - {type: inverse_kinematics, target: {E.x: 0.7}}\n", head)
    a = ans["inverse_kinematics"]
    assert a["numeric"]["solutions"] == []
    assert any("infinitely many" in n for n in a["notes"])
    assert a["symbolic"]["closed_form"]


def test_null_parameter_gives_closed_form_only():
    _, ans = _solve("  - {type: inverse_kinematics, target: {E.x: F, E.y: 0.4}}\n")
    a = ans["inverse_kinematics"]
    assert a["symbolic"]["closed_form"] and a["numeric"] == {}
    assert any("F" in n for n in a["notes"])


def test_continuum_at_the_base():
    head = PLANAR_2R.replace("L1: 0.6, L2: 0.5", "L1: 0.5, L2: 0.5").replace("limits: [0, pi]", "limits: [-pi, pi]")
    _, ans = _solve("  - {type: inverse_kinematics, target: {E.x: 0, E.y: 0}}\n", head)
    a = ans["inverse_kinematics"]
    assert len(a["numeric"]["solutions"]) == 1
    assert abs(abs(a["numeric"]["solutions"][0]["theta2"]) - math.pi) < 1e-9
    assert any("theta1 can take any value" in n for n in a["notes"])

# The golden outputs of problems/ik-*.yaml are checked by tests/cli/test_cli.py (robosolve batch --check).


def test_equation_without_joints():
    _, ans = _solve("  - {type: inverse_kinematics, id: z0, target: {E.x: 0.7, E.y: 0.4, E.z: 0}}\n"
                    "  - {type: inverse_kinematics, id: z1, target: {E.x: 0.7, E.y: 0.4, E.z: 1}}\n")
    assert len(ans["z0"]["numeric"]["solutions"]) == 1 and any("E.z holds" in n for n in ans["z0"]["notes"])
    assert ans["z1"]["unreachable"] is True and ans["z1"]["reason"].startswith("E.z is 0 whatever the joints")


# joints 3 to 6 with parallel axes (α = 0): a planar 4R for a 3-dof planar task, a curve of solutions
PARALLEL_4R_ARM = """robosolve: 1
name: rand6-32-9
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
  - {name: q3, type: revolute}
  - {name: q4, type: revolute}
  - {name: q5, type: revolute}
  - {name: q6, type: revolute}
dh:
  convention: standard
  rows:
    - {theta: 'q1', d: '-0.2938595152767076', a: 0.08400136931478663, alpha: 0.0}
    - {theta: 'q2', d: '0.0', a: 0.10904040540509663, alpha: -1.5707963267948966}
    - {theta: 'q3', d: '0.0', a: 0.2905874517252588, alpha: 0.0}
    - {theta: 'q4', d: '0.07953496067565125', a: 0.16339922202752422, alpha: 0.0}
    - {theta: 'q5', d: '0.0', a: 0.3461061921780233, alpha: 0.0}
    - {theta: 'q6', d: '0.0', a: 0.09771383277748674, alpha: 0.0}
questions:
"""


def test_a_continuum_where_several_joints_move_together():
    """On a curve of solutions the joints that move change together: the note does not say they
    each take any value (found by the pose-IK probe, bench/ikprobe, on a random 6R arm)."""
    _, ans = _solve('  - {type: inverse_kinematics, target: {position: [0.21565129889392934, -0.10218063765613887, -0.6096644259428934], zyz: [1.0704950002832516, 1.5707963267948966, 3.0940031042816227]}}\n', PARALLEL_4R_ARM)
    a = ans["inverse_kinematics"]
    notes = [n for n in a["notes"] if "continuum" in n]
    assert notes and "can take any value" not in notes[0]
    assert "q3, q4, q5 and q6 change together" in notes[0]


NULL_POSE = """robosolve: 1
name: null-pose
parameters: {{L1: 0.5, L2: {l2}, X: ~}}
joints: [{{name: q1, type: revolute}}, {{name: q2, type: revolute}}, {{name: q3, type: revolute}}]
frames:
  "1": {{parent: "0", pose: "Rz(q1) Tx(L1)"}}
  "2": {{pose: "Rz(q2) Tx(L2)"}}
  "3": {{pose: "Rz(q3) Tx(0.1)"}}
questions:
  - {{type: inverse_kinematics, target: {{position: [{x}, 0.1, 0], rpy: [0, 0, 0.3]}}}}
"""


def test_a_pose_target_with_a_null_parameter_is_answered_with_a_note():
    """Spec (null parameters): the numeric key omitted with a note naming the parameter — a pose
    target with X: ~ (or a null length of the chain) was an error (exit 1). With X given in `at`,
    the solutions reach the target: the planar 3R's wrist point by the law of cosines."""
    for l2, x, null in (("0.4", "X", "X"), ("~", "0.6", "L2")):
        answer = solve_problem(load_problem_text(NULL_POSE.format(l2=l2, x=x), "p.yaml")).answers[0]
        assert answer.error is None and "solutions" not in answer.numeric
        assert answer.notes == [f"numeric solutions omitted: it needs the null parameter {null}"]
    text = NULL_POSE.format(l2="0.4", x="X").replace("rpy: [0, 0, 0.3]}}", "rpy: [0, 0, 0.3]}, at: {X: 0.6}}")
    answer = solve_problem(load_problem_text(text, "p.yaml")).answers[0]
    wx, wy = 0.6 - 0.1 * math.cos(0.3), 0.1 - 0.1 * math.sin(0.3)       # the wrist point
    c2 = (wx ** 2 + wy ** 2 - 0.25 - 0.16) / (2 * 0.5 * 0.4)
    assert sorted(abs(s["q2"]) for s in answer.numeric["solutions"]) == [
        pytest.approx(math.acos(c2), abs=1e-9)] * 2
