"""The diagnoses of the robot's conventions (grading.md "Diagnosis"): dh_convention,
rows_swapped, end_effector_frame, quaternion_order. Every given value is written here from
closed forms of the planar 2R arm (or scipy for the quaternion), not from robosolve."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tests._grading import grade_text, key, reference_of

L1, L2 = 0.5, 0.4
Q1, Q2, D1, D2 = math.pi / 6, math.pi / 3, 1.0, -0.5

ARM = f"""
robosolve: 1
name: arm
parameters: {{L1: 1/2, L2: 2/5}}
joints:
  - {{name: q1, type: revolute}}
  - {{name: q2, type: revolute}}
frames:
  "1": {{parent: "0", pose: "Rz(q1) Tx(L1)"}}
  "2": {{pose: "Rz(q2) Tx(L2)"}}
questions:
  - {{type: jacobian, geometric: true, at: {{q1: pi/6, q2: pi/3}}, grade: [J]}}
  - {{type: velocity_acceleration, at: {{q1: pi/6, q2: pi/3, q1_dot: 1, q2_dot: -1/2, q1_ddot: 0, q2_ddot: 0}}}}
  - type: orientation
    matrix: [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
"""
DH = """
robosolve: 1
name: arm-dh
parameters: {L1: 1/2, L2: 2/5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
dh:
  convention: standard
  rows:
    - {theta: q1, d: 0, a: L1, alpha: 0}
    - {theta: q2, d: 0, a: L2, alpha: 0}
questions:
  - {type: position, at: {q1: pi/6, q2: pi/3}}
"""


@pytest.fixture(scope="module")
def ref():
    return reference_of(ARM)


def ans(qid, k, value) -> str:
    return f"robosolve-answers: 1\nanswers:\n  {qid}: {{{k}: {value}}}\n"


def lst(a) -> str:
    return repr(np.round(np.asarray(a, dtype=float), 6).tolist())


def geometric_J(q1=Q1, q2=Q2):
    s1, c1, s12, c12 = math.sin(q1), math.cos(q1), math.sin(q1 + q2), math.cos(q1 + q2)
    return np.array([[-L1 * s1 - L2 * s12, -L2 * s12], [L1 * c1 + L2 * c12, L2 * c12], [0, 0],
                     [0, 0], [0, 0], [1, 1]])


def test_rows_swapped(ref):
    name = "J"
    J = geometric_J()
    right = grade_text(ref, ans("jacobian", name, lst(J)))
    assert key(right, "jacobian", name).verdict == "correct"
    swapped = grade_text(ref, ans("jacobian", name, lst(np.vstack([J[3:], J[:3]]))))
    r = key(swapped, "jacobian", name)
    assert (r.verdict, r.diagnosis) == ("incorrect", "rows_swapped")
    # in frame 2 instead of frame 0: blockdiag(Rᵀ, Rᵀ)·J, R = Rz(q1 + q2)
    Rt = Rotation.from_euler("z", Q1 + Q2).as_matrix().T
    r = key(grade_text(ref, ans("jacobian", name, lst(np.block([[Rt, np.zeros((3, 3))],
                                                                  [np.zeros((3, 3)), Rt]]) @ J))),
            "jacobian", name)
    assert (r.verdict, r.diagnosis) == ("incorrect", "end_effector_frame")


def test_velocity_in_end_effector_frame(ref):
    v0 = geometric_J()[:3] @ np.array([D1, D2])
    assert key(grade_text(ref, ans("velocity_acceleration", "velocity", lst(v0))),
               "velocity_acceleration", "velocity").verdict == "correct"
    v2 = Rotation.from_euler("z", Q1 + Q2).as_matrix().T @ v0
    r = key(grade_text(ref, ans("velocity_acceleration", "velocity", lst(v2))), "velocity_acceleration", "velocity")
    assert (r.verdict, r.diagnosis) == ("incorrect", "end_effector_frame")
    assert "expressed in frame 2" in r.feedback


def test_quaternion_order(ref):
    xyzw = Rotation.from_matrix([[0, -1, 0], [1, 0, 0], [0, 0, 1]]).as_quat()     # scipy: scalar last
    wxyz = np.roll(xyzw, 1)
    assert key(grade_text(ref, ans("orientation", "quaternion", lst(wxyz))), "orientation", "quaternion").verdict \
        == "correct"
    r = key(grade_text(ref, ans("orientation", "quaternion", lst(xyzw))), "orientation", "quaternion")
    assert (r.verdict, r.diagnosis) == ("incorrect", "quaternion_order")
    assert "(x, y, z, w)" in r.feedback


def test_dh_convention():
    ref = reference_of(DH)
    # standard rows: M = Rz(q1)Tx(L1)Rz(q2)Tx(L2); read as modified: Tx(L1)Rz(q1)Tx(L2)Rz(q2)
    c1, s1, c12, s12 = math.cos(Q1), math.sin(Q1), math.cos(Q1 + Q2), math.sin(Q1 + Q2)
    right = [L1 * c1 + L2 * c12, L1 * s1 + L2 * s12, 0]
    assert key(grade_text(ref, ans("position", "position", lst(right))), "position", "position").verdict == "correct"
    other = [L1 + L2 * c1, L2 * s1, 0]
    r = key(grade_text(ref, ans("position", "position", lst(other))), "position", "position")
    assert (r.verdict, r.diagnosis) == ("incorrect", "dh_convention")
    M_other = ('[["cos(q1 + q2)", "-sin(q1 + q2)", 0, "L1 + L2*cos(q1)"], ["sin(q1 + q2)", "cos(q1 + q2)", 0, '
               '"L2*sin(q1)"], [0, 0, 1, 0], [0, 0, 0, 1]]')
    r = key(grade_text(ref, ans("position", "M", M_other)), "position", "M")
    assert (r.verdict, r.diagnosis, r.compared) == ("incorrect", "dh_convention", "symbolic")


# -- IK solutions judged by the pose they reach ---------------------------------------
IK = """
robosolve: 1
name: ik
parameters: {L1: 1/2, L2: 2/5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: inverse_kinematics, target: {E.x: 0.6, E.y: 0.3}}
"""


def ik_branches(x=0.6, y=0.3):
    """The two branches by the law of cosines."""
    c2 = (x * x + y * y - L1 * L1 - L2 * L2) / (2 * L1 * L2)
    out = []
    for q2 in (math.acos(c2), -math.acos(c2)):
        q1 = math.atan2(y, x) - math.atan2(L2 * math.sin(q2), L1 + L2 * math.cos(q2))
        out.append({"q1": q1, "q2": q2})
    return out


def sols(elements) -> str:
    return "[" + ", ".join("{" + ", ".join(f"{k}: {v:.6f}" for k, v in e.items()) + "}" for e in elements) + "]"


@pytest.fixture(scope="module")
def ik_ref():
    return reference_of(IK)


def test_ik_solutions_by_the_pose_they_reach(ik_ref):
    a, b = ik_branches()
    turned = {"q1": b["q1"] + 2 * math.pi, "q2": b["q2"] - 2 * math.pi}
    r = key(grade_text(ik_ref, ans("inverse_kinematics", "solutions", sols([turned, a]))),
            "inverse_kinematics", "solutions")
    assert r.verdict == "correct"
    # every branch is still needed
    r = key(grade_text(ik_ref, ans("inverse_kinematics", "solutions", sols([a]))), "inverse_kinematics", "solutions")
    assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set")
    # the same branch twice is not two branches
    twice = {"q1": a["q1"] + 2 * math.pi, "q2": a["q2"]}
    r = key(grade_text(ik_ref, ans("inverse_kinematics", "solutions", sols([a, twice]))),
            "inverse_kinematics", "solutions")
    assert r.verdict == "incorrect"
    # a configuration that does not reach the target
    wrong = {"q1": a["q1"], "q2": -a["q2"]}
    r = key(grade_text(ik_ref, ans("inverse_kinematics", "solutions", sols([wrong, b]))),
            "inverse_kinematics", "solutions")
    assert r.verdict == "incorrect"


def test_reach_accepts_a_solution_robosolve_wrote_differently(ik_ref):
    """A valid solution whose numbers differ from the reference's beyond the comparison's
    tolerance on angles, but which reaches the target: right."""
    from robosolve.grading.compare import Tolerance
    from robosolve.grading.reach import set_reaches

    q = ik_ref.questions[0]
    a, b = ik_branches()
    tol = Tolerance(0.005, 1e-6)
    assert set_reaches(q.reach, [{k: np.array([v]) for k, v in e.items()} for e in (a, b)], 2, {"q1", "q2"}, tol)
    # the reach test itself: 0.05 rad off does not reach the target
    off = {"q1": a["q1"] + 0.05, "q2": a["q2"]}
    assert not set_reaches(q.reach, [{k: np.array([v]) for k, v in e.items()} for e in (off, b)], 2,
                           {"q1", "q2"}, tol)
