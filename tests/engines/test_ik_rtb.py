"""IK against Robotics Toolbox for Python (test-only reference).

- PUMA 560, wrist position and orientation: our 8 solutions equal RTB's `ikine_a`
  for its 8 configurations (left/right, up/down, flip/no-flip).
- Planar 2R and anthropomorphic 3R: every solution checked with RTB's `fkine`,
  and every solution RTB's numeric `ikine_LM` finds from many starts is in our set.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

rtb = pytest.importorskip("roboticstoolbox")

from robosolve.core.transforms import dh_standard  # noqa: E402
from robosolve.ik.engine import IKJoint, solve_ik  # noqa: E402
from robosolve.ik.numeric import wrap_angle  # noqa: E402


def _dh_chain(robot, qs):
    M = sp.eye(4)
    for link, q in zip(robot.links, qs):
        M = M * dh_standard(q + float(link.offset), float(link.d), float(link.a), float(link.alpha))
    return M


def _contains(sols, q, names, tol=1e-7):
    return any(all(abs(wrap_angle(s[n] - float(v))) < tol for n, v in zip(names, q)) for s in sols)


def test_puma560_eight_solutions_match_ikine_a():
    puma = rtb.models.DH.Puma560()
    qs = sp.symbols("q1:7")
    names = [str(q) for q in qs]
    M = _dh_chain(puma, qs)
    q0 = np.array([0.3, -0.5, 0.4, 0.7, -0.9, 1.2])
    T = puma.fkine(q0).A
    eqs = [(M[i, j], float(T[i, j])) for i in range(3) for j in range(4)]
    joints = [IKJoint(q) for q in qs]
    res = solve_ik(eqs, joints, {}, closed_form=False)
    assert res.status == "ok"
    assert len(res.solutions) == 8
    for sol in res.solutions:
        Ts = puma.fkine([sol[n] for n in names]).A
        assert np.max(np.abs(Ts - T)) < 1e-9
    ref = []
    for conf in ("lun", "luf", "ldn", "ldf", "run", "ruf", "rdn", "rdf"):
        s = puma.ikine_a(puma.fkine(q0), config=conf)
        if s.success:
            ref.append(s.q)
    # RTB's 8 configurations are 8 distinct solutions, all in our set
    assert len(ref) == 8
    for q in ref:
        assert _contains(res.solutions, q, names, 1e-6), q


def test_planar2_against_fkine_and_ikine_lm():
    p2 = rtb.models.DH.Planar2()
    qs = sp.symbols("q1 q2")
    M = _dh_chain(p2, qs)
    x, y = 1.2, 0.7
    res = solve_ik([(M[0, 3], x), (M[1, 3], y)], [IKJoint(q) for q in qs], {})
    assert len(res.solutions) == 2 and res.agree
    for sol in res.solutions:
        t = p2.fkine([sol["q1"], sol["q2"]]).t
        assert abs(t[0] - x) < 1e-12 and abs(t[1] - y) < 1e-12
    from spatialmath import SE3

    found = 0
    for k in range(12):
        q0 = [-3 + 0.5 * k, 2.5 - 0.45 * k]
        s = p2.ikine_LM(SE3(x, y, 0), q0=q0, mask=[1, 1, 0, 0, 0, 0], seed=k)
        if s.success:
            found += 1
            # LM stops at its own tolerance (q within ~1e-3): match by nearest
            assert _contains(res.solutions, s.q, ["q1", "q2"], 5e-3), s.q
    assert found > 0


def test_anthropomorphic_dh_four_solutions_against_fkine():
    L1, L2, L3 = 0.5, 0.4, 0.3
    robot = rtb.DHRobot([rtb.RevoluteDH(d=L1, a=0, alpha=math.pi / 2),
                         rtb.RevoluteDH(a=L2), rtb.RevoluteDH(a=L3)])
    qs = sp.symbols("q1:4")
    M = _dh_chain(robot, qs)
    q_true = [0.4, 0.9, -1.3]
    p = robot.fkine(q_true).t
    res = solve_ik([(M[i, 3], float(p[i])) for i in range(3)], [IKJoint(q) for q in qs], {})
    assert len(res.solutions) == 4 and res.agree
    assert _contains(res.solutions, q_true, ["q1", "q2", "q3"], 1e-9)
    for sol in res.solutions:
        assert np.max(np.abs(robot.fkine([sol["q1"], sol["q2"], sol["q3"]]).t - p)) < 1e-9


def test_spherical_wrist_closed_form_from_three_of_six_equations():
    """ZYZ wrist, orientation given by the approach and normal vectors (6 consistent equations)."""
    smb = pytest.importorskip("spatialmath.base")
    from robosolve.core.transforms import rot_y, rot_z

    t4, t5, t6 = sp.symbols("theta4 theta5 theta6")
    R = (rot_z(t4) * rot_y(t5) * rot_z(t6))[:3, :3]
    Rn = smb.eul2r([0.4, 1.1, -0.7])
    eqs = [(R[i, 2], float(Rn[i, 2])) for i in range(3)] + [(R[i, 0], float(Rn[i, 0])) for i in range(3)]
    res = solve_ik(eqs, [IKJoint(t4), IKJoint(t5), IKJoint(t6)], {})
    assert res.closed_form is not None and res.closed_form_subset is not None and res.agree
    assert len(res.solutions) == 2
    names = ["theta4", "theta5", "theta6"]
    for flip in (False, True):
        assert _contains(res.solutions, smb.tr2eul(Rn, flip=flip), names, 1e-9)


@pytest.mark.slow
def test_puma560_through_the_solver_position_and_tool_vectors():
    """A PUMA 560 problem file: E, A = E + z6, N = E + x6 as 9 consistent equations -> 8 solutions."""
    from robosolve.load.loader import load_problem_text
    from robosolve.run.pipeline import solve_problem

    puma = rtb.models.DH.Puma560()
    q0 = [0.3, -0.5, 0.4, 0.7, -0.9, 1.2]
    T = puma.fkine(q0).A
    E, A, N = T[:3, 3], T[:3, 3] + T[:3, 2], T[:3, 3] + T[:3, 0]
    rows = "\n".join(
        f"    - {{theta: q{i + 1}, d: {float(L.d)!r}, a: {float(L.a)!r}, alpha: {float(L.alpha)!r}}}"
        for i, L in enumerate(puma.links))
    target = ", ".join(f"{p}.{a}: {float(v[k])!r}" for p, v in (("E", E), ("A", A), ("N", N))
                       for k, a in enumerate("xyz"))
    text = f"""robosolve: 1
name: puma-ik
joints:
{chr(10).join(f"  - {{name: q{i}, type: revolute}}" for i in range(1, 7))}
dh:
  convention: standard
  rows:
{rows}
points:
  E: {{frame: "6", at: [0, 0, 0]}}
  A: {{frame: "6", at: [0, 0, 1]}}
  N: {{frame: "6", at: [1, 0, 0]}}
questions:
  - {{type: inverse_kinematics, target: {{{target}}}}}
"""
    report = solve_problem(load_problem_text(text, "puma.yaml"))
    ans = report.answers[0]
    assert ans.error is None
    sols = ans.numeric["solutions"]
    assert len(sols) == 8
    names = [f"q{i}" for i in range(1, 7)]
    for conf in ("lun", "luf", "ldn", "ldf", "run", "ruf", "rdn", "rdf"):
        s = puma.ikine_a(puma.fkine(q0), config=conf)
        assert _contains(sols, s.q, names, 1e-6), conf
