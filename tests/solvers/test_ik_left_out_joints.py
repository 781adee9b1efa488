"""A point target that a joint does not move: the unknowns are the joints that move it.

A planar 3R arm asked where W (fixed in frame 2) goes: theta3 moves nothing in the target, so
the answer is the 2R inverse kinematics in theta1, theta2 (it used to be `solutions: []` with a
note about 1 free parameter). References: the textbook closed form of the 2R arm (law of
cosines) and its Jacobian, in numpy; the DH table multiplied out in numpy for the spatial arm.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from robosolve.load.loader import load_problem_text
from robosolve.papers.keys import placeholder
from robosolve.papers.paper import Say, statement
from robosolve.render.chain_names import symbol_latex
from robosolve.render.markdown import Tex
from robosolve.questions.registry import QUESTION_TYPES
from robosolve.render.results_json import results_document
from robosolve.run.pipeline import solve_problem
from tests._grading import dedent, grade_text, key, reference_of

L1, L2, X, Y = 0.5, 0.4, 0.6, 0.3

THREE_R_W = """
robosolve: 1
name: w-in-frame-2
parameters: {L1: 0.5, L2: 0.4, L3: 0.1}
joints:
  - {name: theta1, type: revolute}
  - {name: theta2, type: revolute}
  - {name: theta3, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
  "3": {pose: "Rz(theta3) Tx(L3)"}
points:
  W: {frame: "2"}
questions:
  - {type: inverse_kinematics, id: ik, target: {W.x: 0.6, W.y: 0.3}, velocity: {W.x: 0.05, W.y: 0.01}}
  - {type: inverse_kinematics, id: near, target: {W.x: 0.6, W.y: 0.3}, select: {theta1: 1, theta2: -1, theta3: 2}}
"""


def two_r(x=X, y=Y):
    """Both elbow solutions of the planar 2R arm (law of cosines), sorted as robosolve sorts."""
    c2 = (x * x + y * y - L1 * L1 - L2 * L2) / (2 * L1 * L2)
    out = []
    for q2 in (math.acos(c2), -math.acos(c2)):
        out.append((math.atan2(y, x) - math.atan2(L2 * math.sin(q2), L1 + L2 * math.cos(q2)), q2))
    return sorted(out)


def jacobian_2r(q1, q2):
    """∂(x, y)/∂(q1, q2) of the planar 2R arm."""
    return np.array([[-L1 * math.sin(q1) - L2 * math.sin(q1 + q2), -L2 * math.sin(q1 + q2)],
                     [L1 * math.cos(q1) + L2 * math.cos(q1 + q2), L2 * math.cos(q1 + q2)]])


def _answers(text):
    report = solve_problem(load_problem_text(dedent(text), "p.yaml"))
    return results_document(report, {})["answers"]


def test_a_joint_that_does_not_move_the_point_is_left_out():
    ans = _answers(THREE_R_W)
    ik, near = ans["ik"], ans["near"]
    want = two_r()
    sols = ik["numeric"]["solutions"]
    assert "unreachable" not in ik
    assert [list(s) for s in sols] == [["theta1", "theta2"]] * 2
    assert np.allclose([(s["theta1"], s["theta2"]) for s in sols], want, atol=1e-9)
    assert ik["numeric"]["selected"] == sols[0]
    assert any("theta3 does not move the target" in n for n in ik["notes"])
    assert all(set(b) == {"theta1", "theta2"} for b in ik["symbolic"]["closed_form"])
    # q_dot = J⁻¹ v with the 2R Jacobian at the selected solution
    J = jacobian_2r(*want[0])
    assert list(ik["numeric"]["q_dot"]) == ["theta1", "theta2"]
    assert np.allclose(list(ik["numeric"]["q_dot"].values()), np.linalg.solve(J, [0.05, 0.01]), atol=1e-9)
    # `select` with a configuration: nearest in theta1, theta2 (theta3 = 2 is ignored)
    nearest = min(want, key=lambda s: math.hypot(s[0] - 1, s[1] + 1))
    assert np.allclose(list(near["numeric"]["selected"].values()), nearest, atol=1e-9)


def test_the_paper_asks_for_the_moving_joints_and_grades_them():
    problem = load_problem_text(dedent(THREE_R_W), "p.yaml")
    q = next(q for q in problem.questions if q.id == "ik")
    ik_type = QUESTION_TYPES["inverse_kinematics"]
    assert placeholder(ik_type.key("selected"), q, problem) == {"theta1": None, "theta2": None}
    assert placeholder(ik_type.key("q_dot"), q, problem) == {"theta1": None, "theta2": None}
    say = Say(problem, Tex(symbol_latex(problem)))
    stated = statement(q, say)
    assert "Find every configuration ($\\theta_{1}$, $\\theta_{2}$) within" in stated
    assert "values ($\\theta_{1}$, $\\theta_{2}$; smallest first)" in stated
    assert "$\\theta_{3}$ does not move the target: it is in no solution." in stated
    ref = reference_of(THREE_R_W)
    (a1, b1), (a2, b2) = two_r()
    q_dot = np.linalg.solve(jacobian_2r(a1, b1), [0.05, 0.01])
    res = grade_text(ref, f"""
        robosolve-answers: 1
        student: s1
        answers:
          ik:
            solutions: [{{theta1: {a2}, theta2: {b2}}}, {{theta1: {a1}, theta2: {b1}}}]
            q_dot: {{theta1: {q_dot[0]}, theta2: {q_dot[1]}}}
        """)
    assert key(res, "ik", "solutions").verdict == "correct"
    assert key(res, "ik", "q_dot").verdict == "correct"


def test_the_notebook_recomputes_in_the_moving_joints_only():
    """robosolve's own notebook cell (a structure check, not a reference): its Newton search
    and its Jacobian are in theta1, theta2, as the answer's solutions are."""
    from robosolve.questions.inverse_kinematics import notebook_cell

    problem = load_problem_text(dedent(THREE_R_W), "p.yaml")
    q = next(q for q in problem.questions if q.id == "ik")
    report = solve_problem(problem)
    cell = notebook_cell(q, report.answers[0], problem)
    assert "newton_solutions(residual, [robot.joints[i] for i in [0, 1]], limits, [True, True])" in cell
    assert "rates_of.jacobian([robot.joints[i] for i in [0, 1]])" in cell


def test_a_prismatic_joint_that_does_not_move_the_target_coordinates():
    """d3 slides W along z: the target W.x, W.y is the 2R arm's, d3 in no solution."""
    ans = _answers("""
        robosolve: 1
        name: rrp-xy
        parameters: {L1: 0.5, L2: 0.4}
        joints:
          - {name: theta1, type: revolute}
          - {name: theta2, type: revolute}
          - {name: d3, type: prismatic, limits: [0, 0.3]}
        frames:
          "1": {parent: "0", pose: "Rz(theta1) Tx(L1)"}
          "2": {pose: "Rz(theta2) Tx(L2)"}
          "3": {pose: "Tz(d3)"}
        points:
          W: {frame: "3"}
        questions:
          - {type: inverse_kinematics, id: ik, target: {W.x: 0.6, W.y: 0.3}}
        """)["ik"]
    sols = ans["numeric"]["solutions"]
    assert np.allclose([(s["theta1"], s["theta2"]) for s in sols], two_r(), atol=1e-9)
    assert all(list(s) == ["theta1", "theta2"] for s in sols)
    assert any("d3 does not move the target" in n for n in ans["notes"])


@pytest.mark.parametrize("right", ["pi/2", "1.5707963267949"])
def test_the_wrist_joints_do_not_move_the_wrist_centre(right):
    """An anthropomorphic arm with a spherical wrist (standard DH), W the wrist centre written in
    frame 6: q4, q5, q6 do not move it, and every solution in q1, q2, q3 puts it at the target
    (checked with the DH table multiplied out in numpy); q_dot against its Jacobian by central
    differences. With the right angles written as decimals, cos(1.5707963267949) ≈ 1e-16 is no
    dependence on q4, q5 (it gave no q_dot)."""
    a2, a3, d6 = 0.4, 0.35, 0.1
    ans = _answers((f"""
        robosolve: 1
        name: wrist-centre
        parameters: {{a2: {a2}, a3: {a3}, d6: {d6}}}
        joints:
          - {{name: q1, type: revolute}}
          - {{name: q2, type: revolute}}
          - {{name: q3, type: revolute}}
          - {{name: q4, type: revolute}}
          - {{name: q5, type: revolute}}
          - {{name: q6, type: revolute}}
        frames:
          "1": {{parent: "0", dh: {{theta: q1, d: 0, a: 0, alpha: pi/2}}}}
          "2": {{dh: {{theta: q2, d: 0, a: a2, alpha: 0}}}}
          "3": {{dh: {{theta: q3 + pi/2, d: 0, a: 0, alpha: pi/2}}}}
          "4": {{dh: {{theta: q4, d: a3, a: 0, alpha: -pi/2}}}}
          "5": {{dh: {{theta: q5, d: 0, a: 0, alpha: pi/2}}}}
          "6": {{dh: {{theta: q6, d: d6, a: 0, alpha: 0}}}}
        points:
          W: {{frame: "6", at: [0, 0, -d6]}}
        questions:
          - {{type: inverse_kinematics, id: ik, target: {{W.x: 0.3, W.y: 0.2, W.z: 0.25}},
             velocity: {{W.x: 0.1, W.y: -0.05, W.z: 0.02}}}}
        """).replace("pi/2", right))["ik"]
    rows = [(0, 0, np.pi / 2), (0, a2, 0), (0, 0, np.pi / 2), (a3, 0, -np.pi / 2), (0, 0, np.pi / 2), (d6, 0, 0)]

    def wrist(qs):
        T = np.eye(4)
        for (d, a, alpha), th in zip(rows, np.add(qs, [0, 0, np.pi / 2, 0, 0, 0])):
            ct, st, ca, sa = np.cos(th), np.sin(th), np.cos(alpha), np.sin(alpha)
            T = T @ np.array([[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],
                              [0, sa, ca, d], [0, 0, 0, 1]])
        return (T @ [0, 0, -d6, 1])[:3]

    q0 = np.array([0.1, -0.4, 0.2, -1.9, 0.3, 1.5])
    moving = [f"q{i + 1}" for i in range(6) if not np.allclose(wrist(q0 + 0.3 * np.eye(6)[i]), wrist(q0))]
    assert moving == ["q1", "q2", "q3"]
    sols = ans["numeric"]["solutions"]
    assert len(sols) == 4 and all(list(s) == moving for s in sols)
    for s in sols:
        qs = [s["q1"], s["q2"], s["q3"], 0.7, -0.2, 1.1]    # any wrist: W does not move
        assert np.allclose(wrist(qs), [0.3, 0.2, 0.25], atol=1e-9)
    assert any("q4, q5, q6 do not move the target" in n for n in ans["notes"])
    sel = [ans["numeric"]["selected"][n] for n in moving] + [0.7, -0.2, 1.1]
    J = np.column_stack([(wrist(sel + 1e-6 * e) - wrist(sel - 1e-6 * e)) / 2e-6 for e in np.eye(6)[:3]])
    assert list(ans["numeric"]["q_dot"]) == moving
    assert np.allclose(list(ans["numeric"]["q_dot"].values()), np.linalg.solve(J, [0.1, -0.05, 0.02]), atol=1e-6)


def test_more_or_fewer_equations_than_the_moving_joints():
    """Counted against theta1, theta2 (theta3 moves nothing in W): three consistent equations
    give the one 2R solution whose theta1 + theta2 is the one asked; inconsistent ones stay a
    question error; one equation for two moving joints stays a continuum."""
    (a1, b1), (a2, b2) = two_r()
    ans = _answers(THREE_R_W.split("questions:")[0] + f"""questions:
  - {{type: inverse_kinematics, id: cons, target: {{W.x: 0.6, W.y: 0.3, "theta1 + theta2": {a2 + b2!r}}}}}
  - {{type: inverse_kinematics, id: bad, target: {{W.x: 0.6, W.y: 0.3, "theta1 + theta2": 0.5}}}}
  - {{type: inverse_kinematics, id: one, target: {{W.x: 0.6}}}}
""")
    sols = ans["cons"]["numeric"]["solutions"]
    assert len(sols) == 1 and np.allclose(list(sols[0].values()), (a2, b2), atol=1e-9)
    assert ans["bad"]["error"].startswith("3 equations for 2 unknown joints: no configuration satisfies")
    assert ans["bad"]["error"].endswith("(theta3 does not move the target.)")
    assert ans["one"]["numeric"]["solutions"] == []
    assert any(n.startswith("1 equation for 2 unknown joints: infinitely many solutions") for n in ans["one"]["notes"])


def test_a_value_for_the_joint_in_no_solution_is_ignored_in_every_key():
    """theta3 given anyway (it moves nothing in W) is ignored alike in `solutions`, `selected`
    and `q_dot`, right values graded right and wrong ones wrong; a name that is no joint of the
    robot stays invalid. References: the 2R closed form and its Jacobian (numpy)."""
    ref = reference_of(THREE_R_W)
    (a1, b1), (a2, b2) = two_r()
    q_dot = np.linalg.solve(jacobian_2r(a1, b1), [0.05, 0.01])

    def graded(b_sel, extra="theta3"):
        return grade_text(ref, f"""
            robosolve-answers: 1
            student: s1
            answers:
              ik:
                solutions: [{{theta1: {a2}, theta2: {b2}, theta3: 0.7}}, {{theta1: {a1}, theta2: {b1}, theta3: 0}}]
                selected: {{theta1: {a1}, theta2: {b_sel}, {extra}: 0.7}}
                q_dot: {{theta1: {q_dot[0]}, theta2: {q_dot[1]}, {extra}: 1}}
            """)

    res = graded(b1)
    assert [key(res, "ik", k).verdict for k in ("solutions", "selected", "q_dot")] == ["correct"] * 3
    assert key(graded(b1 + 0.3), "ik", "selected").verdict == "incorrect"
    bad = key(graded(b1, extra="thetaX"), "ik", "selected")
    assert bad.verdict == "invalid"
    assert "'thetaX'" in bad.feedback and "did you mean 'theta" in bad.feedback
    bad = grade_text(ref, """
        robosolve-answers: 1
        student: s1
        answers:
          ik:
            solutions: [{theta1: 1, theta2: 2, thetaX: 0.7}]
        """)
    assert key(bad, "ik", "solutions").verdict == "invalid"


def test_vectors_of_the_asked_joints_are_read_in_their_order():
    """`selected: [a, b]` and solutions as vectors on the 3R whose target theta3 does not move are
    the asked joints' values, {theta1: a, theta2: b} (they were read against all three joints and
    graded invalid); three values still map to every joint, theta3 ignored. References: the 2R
    closed form and its Jacobian (numpy)."""
    ref = reference_of(THREE_R_W)
    (a1, b1), (a2, b2) = two_r()
    q_dot = np.linalg.solve(jacobian_2r(a1, b1), [0.05, 0.01])
    res = grade_text(ref, f"""
        robosolve-answers: 1
        student: s1
        answers:
          ik:
            solutions: [[{a2}, {b2}], [{a1}, {b1}, 0.3]]
            selected: [{a1}, {b1}]
            q_dot: "[{q_dot[0]}, {q_dot[1]}]"
        """)
    assert [key(res, "ik", k).verdict for k in ("solutions", "selected", "q_dot")] == ["correct"] * 3
    wrong = grade_text(ref, f"""
        robosolve-answers: 1
        student: s1
        answers:
          ik:
            selected: [{b1}, {a1}]
        """)
    assert key(wrong, "ik", "selected").verdict == "incorrect"
