"""p_control along a work-space trajectory against an independent integration: pinocchio `aba`
(the plant), `crba`/`rnea` (M, c, g in the laws), the 2R arm's own closed-form IK and Jacobian,
scipy `solve_ivp`."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from robosolve.motion import task_path as tp
from support.robots import ARM2R_LC, ARM2R_VALUES, arm2r_pin

V, LC = ARM2R_VALUES, ARM2R_LC
PROBLEM = f"""robosolve: 1
name: arm2r-work-space
parameters: {{L1: {V['L1']}, L2: {V['L2']}, g: {V['g']}}}
joints: [{{name: q1, type: revolute}}, {{name: q2, type: revolute}}]
frames:
  "1": {{parent: "0", pose: "Rz(q1) Tx(L1)"}}
  "2": {{pose: "Rz(q2) Tx(L2)"}}
gravity: [0, -g, 0]
bodies:
  - {{name: b1, frame: "1", mass: {V['m1']}, com: [{LC['lc1'] - V['L1']}, 0, 0], inertia: [[0, 0, 0], [0, 0, 0], [0, 0, {V['I1']}]]}}
  - {{name: b2, frame: "2", mass: {V['m2']}, com: [{LC['lc2'] - V['L2']}, 0, 0], inertia: [[0, 0, 0], [0, 0, 0], [0, 0, {V['I2']}]]}}
questions:
  - {{type: task_trajectory, id: line, coordinates: [E.x, E.y], from: {{E.x: 0.7, E.y: 0.1}},
     to: {{E.x: 0.2, E.y: 0.6}}, max_velocity: 0.6, max_acceleration: 3}}
  - {{type: p_control, id: ct, trajectory: line, law: task_computed_torque,
     gains: {{E.x: 400, E.y: 400}}, gains_d: {{E.x: 30, E.y: 30}}, start: {{q1: -0.2, q2: 1.35}}}}
  - {{type: p_control, id: ideal, trajectory: line, law: pd_gravity,
     gains: {{q1: 600, q2: 600}}, gains_d: {{q1: 40, q2: 40}}}}
"""
L1, L2 = V["L1"], V["L2"]
PATH, TIMING = tp.line([0.7, 0.1], [0.2, 0.6]), tp.trapezoidal(math.hypot(0.5, 0.5), 0.6, 3.0)


def fk(q):
    return np.array([L1 * math.cos(q[0]) + L2 * math.cos(q[0] + q[1]), L1 * math.sin(q[0]) + L2 * math.sin(q[0] + q[1])])


def jac(q):
    s1, c1, s12, c12 = math.sin(q[0]), math.cos(q[0]), math.sin(q[0] + q[1]), math.cos(q[0] + q[1])
    return np.array([[-L1 * s1 - L2 * s12, -L2 * s12], [L1 * c1 + L2 * c12, L2 * c12]])


def jdot_qdot(q, qd):
    a, b = qd[0], qd[0] + qd[1]
    return -np.array([L1 * math.cos(q[0]) * a * a + L2 * math.cos(q[0] + q[1]) * b * b,
                      L1 * math.sin(q[0]) * a * a + L2 * math.sin(q[0] + q[1]) * b * b])


def ik(x, elbow):
    c2 = (x @ x - L1 ** 2 - L2 ** 2) / (2 * L1 * L2)
    q2 = elbow * math.acos(c2)
    q1 = math.atan2(x[1], x[0]) - math.atan2(L2 * math.sin(q2), L1 + L2 * math.cos(q2))
    return np.array([q1, q2])


def reference(t):
    _s, x, xd, xdd = tp.task_state(PATH, TIMING, t)
    q = ik(x, 1.0)
    qd = np.linalg.solve(jac(q), xd)
    return x, xd, xdd, q, qd, np.linalg.solve(jac(q), xdd - jdot_qdot(q, qd))


def _simulate(law, q0):
    import pinocchio as pin
    from scipy.integrate import solve_ivp

    model = arm2r_pin()
    data = model.createData()

    def rhs(t, y):
        q, qd = y[:2], y[2:]
        x, xd, xdd, qr, qdr, qddr = reference(t)
        gq = pin.rnea(model, data, q, np.zeros(2), np.zeros(2))
        if law == "ct":
            M = pin.crba(model, data, q)
            M = np.triu(M) + np.triu(M, 1).T
            nle = pin.rnea(model, data, q, qd, np.zeros(2))
            e, ed = x - fk(q), xd - jac(q) @ qd
            tau = M @ np.linalg.solve(jac(q), xdd + 30 * ed + 400 * e - jdot_qdot(q, qd)) + nle
        else:
            tau = 600 * (qr - q) + 40 * (qdr - qd) + gq
        return np.concatenate([qd, pin.aba(model, data, q, qd, tau)])

    ts = np.union1d(np.linspace(0, TIMING.T, 4001), TIMING.breaks)
    sol = solve_ivp(rhs, (0, TIMING.T), np.concatenate([q0, [0, 0]]), t_eval=ts, rtol=1e-11, atol=1e-12,
                    method="DOP853", max_step=0.005)
    refs = [reference(t) for t in ts]
    task_err = np.array([r[0] - fk(sol.y[:2, k]) for k, r in enumerate(refs)]).T
    joint_err = np.array([r[3] - sol.y[:2, k] for k, r in enumerate(refs)]).T
    return task_err, joint_err


def _answers(tmp_path, keep):
    """The problem's trajectory and its control question `keep` (ct or ideal), solved."""
    head, rest = PROBLEM.split("  - {type: p_control, id: ct")
    ct, ideal = ("  - {type: p_control, id: ct" + rest).split("  - {type: p_control, id: ideal")
    text = head + (ct if keep == "ct" else "  - {type: p_control, id: ideal" + ideal)
    (tmp_path / "p.yaml").write_text(text)
    r = subprocess.run([sys.executable, "-m", "robosolve", "solve", str(tmp_path / "p.yaml"), "--out",
                        str(tmp_path / "out")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return json.loads((tmp_path / "out" / "results.json").read_text())["answers"]


@pytest.mark.slow
def test_task_computed_torque_matches_pinocchio(tmp_path):
    answers = _answers(tmp_path, "ct")
    task_err, _ = _simulate("ct", np.array([-0.2, 1.35]))
    got = answers["ct"]["numeric"]
    for i, c in enumerate(("E.x", "E.y")):
        assert got["max_error"][c] == pytest.approx(np.max(np.abs(task_err[i])), rel=1e-4)
        assert got["final_error"][c] == pytest.approx(task_err[i, -1], rel=1e-3, abs=1e-8)
        assert got["max_task_error"][c] == got["max_error"][c]


def test_ideal_scheme_matches_pinocchio_with_a_closed_form_reference(tmp_path):
    answers = _answers(tmp_path, "ideal")
    start = answers["line"]["numeric"]["start"]
    q0 = np.array([start["q1"], start["q2"]])
    assert np.allclose(q0, ik(np.array([0.7, 0.1]), 1.0), atol=1e-10)     # the branch followed
    task_err, joint_err = _simulate("ideal", q0)
    got = answers["ideal"]["numeric"]
    for i, j in enumerate(("q1", "q2")):
        assert got["max_error"][j] == pytest.approx(np.max(np.abs(joint_err[i])), rel=1e-4)
        assert got["final_error"][j] == pytest.approx(joint_err[i, -1], rel=1e-3, abs=1e-8)
    for i, c in enumerate(("E.x", "E.y")):
        assert got["max_task_error"][c] == pytest.approx(np.max(np.abs(task_err[i])), rel=1e-3)
