"""The closed form of a pose's inverse kinematics has no spurious branch (Robotics Toolbox's
`fkine` as the reference forward kinematics).

Each branch, evaluated in order (each joint's formula with the joints found before it), either
reaches the pose or leaves its domain (an acos of more than 1, a division by zero); every solution
is some branch's value; and the wrist gives two branches per branch of the arm (the sign of the
middle angle's sine), each a solution: a joint whose sine and cosine are both fixed by the
equations is one atan2, not ±acos or asin, π − asin (two values of which one is right).
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

rtb = pytest.importorskip("roboticstoolbox")

from robosolve.core.angles import wrap_angle  # noqa: E402
from robosolve.core.transforms import dh_standard  # noqa: E402
from robosolve.ik.engine import IKJoint  # noqa: E402
from robosolve.ik.pose import solve_pose  # noqa: E402

NAMES = [f"q{i}" for i in range(1, 7)]


def _kuka():
    """problems/kuka-kr.yaml's DH table (standard)."""
    rows = [(0.675, 0.26, -np.pi / 2), (0, 0.68, 0), (0, 0.035, -np.pi / 2), (0.67, 0, np.pi / 2),
            (0, 0, -np.pi / 2), (0.158, 0, 0)]
    return rtb.DHRobot([rtb.RevoluteDH(d=d, a=a, alpha=al) for d, a, al in rows])


ROBOTS = {"kuka": _kuka, "puma": lambda: rtb.models.DH.Puma560(), "ur5": lambda: rtb.models.DH.UR5()}


def _solve(robot, q0):
    qs = sp.symbols("q1:7")
    F = [dh_standard(q + float(L.offset), float(L.d), float(L.a), float(L.alpha)) for L, q in zip(robot.links, qs)]
    T = robot.fkine(q0).A
    return solve_pose(F, [IKJoint(q) for q in qs], T[:3, :3], T[:3, 3]), T


def _branch_values(branch, T):
    """The branch's joint values, each formula evaluated with the earlier joints; None when one
    leaves its domain (complex, zoo, nan)."""
    vals = {sp.Symbol(f"r{i + 1}{j + 1}"): T[i, j] for i in range(3) for j in range(3)}
    vals.update(dict(zip(sp.symbols("px py pz"), T[:3, 3])))
    known = {str(s) for s in vals}
    q = {}
    while len(q) < 6:
        ready = [n for n in NAMES if n not in q and {str(x) for x in branch[n].free_symbols} <= known | set(q)]
        assert ready, "a branch's formulas depend on one another in a cycle"
        for n in ready:
            v = complex(sp.N(branch[n].xreplace({**vals, **{sp.Symbol(k): x for k, x in q.items()}})))
            if not np.isfinite(v) or abs(v.imag) > 1e-9:
                return None
            q[n] = v.real
    return q


@pytest.mark.parametrize("robot", sorted(ROBOTS))
def test_every_closed_form_branch_reaches_the_pose_or_leaves_its_domain(robot):
    arm = ROBOTS[robot]()
    res, T = _solve(arm, [0.3, -0.5, 0.4, 0.7, -0.9, 1.2])
    assert res.closed_form and len(res.all_solutions) == 8, res.notes
    reached = []
    for branch in res.closed_form:
        q = _branch_values(branch, T)
        if q is None:
            continue
        miss = np.max(np.abs(arm.fkine([q[n] for n in NAMES]).A - T))
        assert miss < 1e-8, (branch, miss)
        reached.append(q)
    for s in res.all_solutions:
        assert any(all(abs(wrap_angle(s[n] - q[n])) < 1e-6 for n in NAMES) for q in reached), s
    # two wrist branches per branch of the arm (the UR way: q5, q6 per branch of q1)
    arm_joints, wrist_joints = (["q1"], ["q5", "q6"]) if robot == "ur5" else (NAMES[:3], NAMES[3:])
    wrist = {}
    for branch in res.closed_form:
        key = tuple(str(branch[n]) for n in arm_joints)
        wrist.setdefault(key, set()).add(tuple(str(branch[n]) for n in wrist_joints))
    assert {len(v) for v in wrist.values()} == {2}


def test_an_over_determined_point_target_uses_every_equation_one_branch_per_solution():
    """A 2R arm with its position and orientation (3 consistent equations, 2 joints): q1 from
    both position equations once q1 + q2 = φ is used, one atan2; a single branch, the solution
    (checked against the arm's position and angle, numpy)."""
    from robosolve.ik.engine import solve_ik

    q1, q2, x, y, phi = sp.symbols("q1 q2 x y phi")
    eqs = [(sp.cos(q1) + 2 * sp.cos(q1 + q2), x), (sp.sin(q1) + 2 * sp.sin(q1 + q2), y), (q1 + q2, phi)]
    a, b = 0.4, 0.9
    vals = {x: np.cos(a) + 2 * np.cos(a + b), y: np.sin(a) + 2 * np.sin(a + b), phi: a + b}
    res = solve_ik(eqs, [IKJoint(q1), IKJoint(q2)], vals, target_symbols=[x, y, phi])
    assert res.status == "ok" and res.closed_form_subset == [0, 1, 2]
    assert len(res.closed_form_branches) == 1
    br = res.closed_form_branches[0]
    v1 = float(br[q1].subs(vals))
    v2 = float(br[q2].subs({**vals, q1: v1}))
    assert abs(np.cos(v1) + 2 * np.cos(v1 + v2) - vals[x]) < 1e-12
    assert abs(np.sin(v1) + 2 * np.sin(v1 + v2) - vals[y]) < 1e-12 and abs(v1 + v2 - (a + b)) < 1e-12


def _custom_wrist(kind):
    """An anthropomorphic arm (standard DH) with a wrist of three rotations about the frame's
    axes: z-y-z (Euler) or z-y-x (roll-pitch-yaw)."""
    qs = sp.symbols("q1:7")
    c, s = sp.cos, sp.sin
    rot = {"z": lambda t: sp.Matrix([[c(t), -s(t), 0, 0], [s(t), c(t), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]),
           "y": lambda t: sp.Matrix([[c(t), 0, s(t), 0], [0, 1, 0, 0], [-s(t), 0, c(t), 0], [0, 0, 0, 1]]),
           "x": lambda t: sp.Matrix([[1, 0, 0, 0], [0, c(t), -s(t), 0], [0, s(t), c(t), 0], [0, 0, 0, 1]])}
    shift = sp.eye(4)
    shift[2, 3] = sp.Rational(2, 5)
    F = [dh_standard(qs[0], 0.5, 0, -sp.pi / 2), dh_standard(qs[1], 0, 0.4, 0),
         dh_standard(qs[2], 0, 0.05, -sp.pi / 2)] + [shift * rot[kind[0]](qs[3]), rot[kind[1]](qs[4]),
                                                    rot[kind[2]](qs[5]) * shift]
    M = sp.lambdify(qs, F[0] * F[1] * F[2] * F[3] * F[4] * F[5], "numpy")
    return F, [IKJoint(q) for q in qs], lambda q: np.array(M(*q), dtype=float)


@pytest.mark.parametrize("kind, middle, aligned_at", [("zyz", "sine", 0.0), ("zyx", "cosine", np.pi / 2)])
def test_the_wrist_step_names_the_middle_angle_function_whose_sign_gives_the_branches(kind, middle, aligned_at):
    """ZYZ: the first and last axes align where the middle angle is 0 (branches by the sign of its
    sine); roll-pitch-yaw: where it is ±π/2 (its cosine). The alignment is checked here on the
    arm's forward kinematics (numpy), and every branch reaches the pose."""
    F, joints, fk = _custom_wrist(kind)
    q0 = [0.3, -0.5, 0.4, 0.7, -0.9, 1.2]
    T = fk(q0)

    def axis(q, k, h=1e-6):
        d = list(q)
        d[k] += h
        W = (fk(d)[:3, :3] - fk(q)[:3, :3]) / h @ fk(q)[:3, :3].T
        return np.array([W[2, 1], W[0, 2], W[1, 0]])

    at = [0.3, -0.5, 0.4, 0.7, aligned_at, 1.2]
    assert np.linalg.norm(np.cross(axis(at, 3), axis(at, 5))) < 1e-5
    res = solve_pose(F, joints, T[:3, :3], T[:3, 3])
    step = next(s for s in res.steps if s.title == "Kinematic decoupling: the wrist")
    assert f"the sign of the middle angle's {middle}." in step.text and f"angle's {middle} vanishes" in step.text
    for branch in res.closed_form:
        q = _branch_values(branch, T)
        assert q is None or np.max(np.abs(fk([q[n] for n in NAMES]) - T)) < 1e-8
    assert len(res.closed_form) == 8


def test_a_turn_and_a_lift_give_one_branch_atan2_of_the_target():
    """x = 0.5 cos q1, y = 0.5 sin q1, z = d2 + 0.2: q1 = atan2(y, x) (the common 1/0.5 divided
    out), one branch, the angle of the point (math.atan2)."""
    from robosolve.ik.engine import solve_ik

    q1, d2, x, y, z = sp.symbols("q1 d2 x y z")
    eqs = [(0.5 * sp.cos(q1), x), (0.5 * sp.sin(q1), y), (d2 + 0.2, z)]
    res = solve_ik(eqs, [IKJoint(q1), IKJoint(d2, False, None)], {x: -0.3, y: 0.4, z: 1.0}, target_symbols=[x, y, z])
    assert [str(b[q1]) for b in res.closed_form_branches] == ["atan2(y, x)"]
    assert abs(res.all_solutions[0]["q1"] - np.arctan2(0.4, -0.3)) < 1e-12
