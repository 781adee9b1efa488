"""task_trajectory on robots it was not written for (planar 3R, SCARA, anthropomorphic 3R): the
joint path against Robotics Toolbox's numeric IK per sample (`ikine_LM`), the rates against RTB's
Jacobian and finite differences."""

from __future__ import annotations

import math

import numpy as np
import pytest

from robosolve.load.loader import load_problem_text
from robosolve.model import RobotModel
from robosolve.motion import task_path as tp
from robosolve.solvers import task_trajectory as tt
from robosolve.run.pipeline import solve_context

HEAD = "robosolve: 1\nname: r\nparameters: {}\n"

PLANAR_3R = HEAD + """joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: q3, type: revolute}]
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(0.5)"}
  "2": {pose: "Rz(q2) Tx(0.4)"}
  "3": {pose: "Rz(q3) Tx(0.3)"}
questions:
  - {type: task_trajectory, coordinates: [E.x, E.y, "q1 + q2 + q3"], from: {E.x: 0.8, E.y: 0.2, "q1 + q2 + q3": 0.3},
     to: {E.x: 0.4, E.y: 0.6, "q1 + q2 + q3": 1.2}, duration: 2, shape: quintic}
"""
PLANAR_3R_WIDE = HEAD + PLANAR_3R.split("questions:")[0].split("parameters: {}\n")[1] + """questions:
  - {type: task_trajectory, coordinates: [E.x, E.y], from: {E.x: 0.8, E.y: 0.2}, to: {E.x: 0.4, E.y: 0.6},
     max_velocity: 0.5, max_acceleration: 2, start: {q1: 0.2, q2: -0.3, q3: 0.4}}
"""
SCARA = HEAD + """joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: d3, type: prismatic}]
frames:
  "1": {parent: "0", pose: "Tz(1) Rz(q1) Tx(0.5)"}
  "2": {pose: "Rz(q2) Tx(0.4)"}
  "3": {pose: "Tz(d3)"}
questions:
  - type: task_trajectory
    from: {E.x: 0.6, E.y: 0.3, E.z: 0.8}
    to: {E.x: 0.2, E.y: 0.6, E.z: 0.9}
    path: {circle: {center: [0.4, 0.45, 0.85], normal: [0.3, 0.4, 0]}}
    max_velocity: 0.4
    max_acceleration: 1.5
"""
ANTHRO = HEAD + """joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: q3, type: revolute}]
dh:
  convention: standard
  rows:
    - {theta: q1, d: 0.4, a: 0, alpha: pi/2}
    - {theta: q2, d: 0, a: 0.5, alpha: 0}
    - {theta: q3, d: 0, a: 0.4, alpha: 0}
questions:
  - {type: task_trajectory, from: {E.x: 0.5, E.y: 0.1, E.z: 0.6}, to: {E.x: 0.2, E.y: 0.5, E.z: 0.3},
     max_velocity: 0.5, max_acceleration: 2}
"""


def _rtb(name):
    import roboticstoolbox as rtb

    if name == "planar3r":
        return rtb.DHRobot([rtb.RevoluteDH(a=0.5), rtb.RevoluteDH(a=0.4), rtb.RevoluteDH(a=0.3)])
    if name == "scara":
        E = rtb.ET
        return rtb.ERobot(E.tz(1) * E.Rz() * E.tx(0.5) * E.Rz() * E.tx(0.4) * E.tz(qlim=[-2, 2]))
    return rtb.DHRobot([rtb.RevoluteDH(d=0.4, alpha=math.pi / 2), rtb.RevoluteDH(a=0.5), rtb.RevoluteDH(a=0.4)])


def _convert(text):
    problem = load_problem_text(text, "r.yaml")
    ctx = solve_context(problem, RobotModel(problem))
    q = problem.questions[0]
    coords, arm, path, timing, q_from, _res, _subs, outside = tt.setup(q, ctx)
    assert outside is None
    conv = tp.follow(arm, path, timing, q_from, samples=101)
    assert conv.failure is None
    return arm, path, timing, conv


@pytest.mark.parametrize("text, robot, mask", [
    (PLANAR_3R, "planar3r", [1, 1, 0, 0, 0, 1]),
    (SCARA, "scara", [1, 1, 1, 0, 0, 0]),
    (ANTHRO, "anthro", [1, 1, 1, 0, 0, 0]),
], ids=["planar-3r", "scara-half-circle", "anthropomorphic-3r"])
def test_joint_path_matches_rtb_ikine_lm_per_sample(text, robot, mask):
    from spatialmath import SE3

    arm, path, timing, conv = _convert(text)
    r = _rtb(robot)
    for k in range(0, conv.t.size, 10):
        x = conv.x[:, k]
        T = SE3(x[0], x[1], 0) * SE3.Rz(x[2]) if robot == "planar3r" else SE3(*x)
        sol = r.ikine_LM(T, q0=conv.q[:, k] + 0.03, mask=mask, tol=1e-13, ilimit=200, slimit=20)
        assert sol.success and np.allclose(sol.q, conv.q[:, k], atol=1e-6), (k, sol.q, conv.q[:, k])
        # rates: RTB's Jacobian rows of the task coordinates times q_dot give x_dot
        Jr = r.jacob0(conv.q[:, k])[[i for i, m in enumerate(mask) if m]]
        assert np.allclose(Jr @ conv.qd[:, k], conv.xd[:, k], atol=1e-9)
    # finite differences of the converted path, inside the middle segment
    seg = len(timing.breaks) // 2 - 1 if len(timing.breaks) > 2 else 0
    t0 = 0.5 * (timing.breaks[seg] + timing.breaks[seg + 1])
    h = 1e-4
    st = [tp.state_at(arm, path, timing, conv, t, seg) for t in (t0 - h, t0, t0 + h)]
    assert np.allclose((st[2][0] - st[0][0]) / (2 * h), st[1][1], atol=1e-6)
    assert np.allclose((st[2][1] - st[0][1]) / (2 * h), st[1][2], atol=1e-5)


def test_fewer_coordinates_than_joints_gives_minimum_norm_rates():
    arm, path, timing, conv = _convert(PLANAR_3R_WIDE)
    r = _rtb("planar3r")
    for k in range(0, conv.t.size, 10):
        J = r.jacob0(conv.q[:, k])[:2]
        assert np.allclose(r.fkine(conv.q[:, k]).t[:2], conv.x[:, k], atol=1e-10)
        assert np.allclose(conv.qd[:, k], np.linalg.pinv(J) @ conv.xd[:, k], atol=1e-9)


def _line_rates(t, a, b, v, acc):
    """x_dot_d(t) on the line a -> b, trapezoidal speed (closed form, independent of the engine)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    L = float(np.linalg.norm(b - a))
    ta, T = v / acc, L / v + v / acc
    speed = acc * t if t <= ta else (v if t <= T - ta else acc * (T - t))
    return speed * (b - a) / L


def test_fewer_coordinates_than_joints_follow_the_integrated_minimum_norm_motion():
    # x(q) = x_d(t) leaves a family of configurations: the motion is the integral of the
    # minimum-norm rates q' = J+ x'_d (scipy DOP853 at rtol 1e-12 on RTB's Jacobian), and its
    # acceleration the derivative of those rates (null-space part included).  Newton's steps from
    # sample to sample drifted ~1e-4 rad along the family; q'' = J+ (x'' - J' q') alone missed the
    # null-space part (7 % of the largest acceleration on a quintic).
    from scipy.integrate import solve_ivp

    arm, path, timing, conv = _convert(PLANAR_3R_WIDE)
    r = _rtb("planar3r")

    def rates(t, q):
        return np.linalg.pinv(r.jacob0(q)[:2]) @ _line_rates(t, [0.8, 0.2], [0.4, 0.6], 0.5, 2.0)

    ref = solve_ivp(rates, (0.0, timing.T), conv.q[:, 0], method="DOP853", rtol=1e-12, atol=1e-13,
                    dense_output=True)
    assert timing.T == pytest.approx(math.hypot(0.4, 0.4) / 0.5 + 0.25, rel=1e-14)
    for k in range(conv.t.size):
        assert np.allclose(conv.q[:, k], ref.sol(conv.t[k]), atol=1e-9), conv.t[k]
    h = 1e-5
    for k in range(3, conv.t.size - 3, 7):
        t = conv.t[k]
        if any(abs(t - b) < 3 * h for b in timing.breaks):
            continue
        fd = (rates(t + h, ref.sol(t + h)) - rates(t - h, ref.sol(t - h))) / (2 * h)
        assert np.allclose(conv.qdd[:, k], fd, atol=1e-6), t


WIDE_STARTS = {
    # the probe's start: Newton's steps (capped at 0.5 rad) landed 1e-2 rad from the nearest solution
    "planar-3r-given": (PLANAR_3R_WIDE.replace("from: {E.x: 0.8, E.y: 0.2}, to: {E.x: 0.4, E.y: 0.6}",
                                               "from: {E.x: 0.8, E.y: 0.3}, to: {E.x: 0.5, E.y: 0.6}")
                        .replace("start: {q1: 0.2, q2: -0.3, q3: 0.4}", "start: {q1: 0.1, q2: 0.6, q3: 0.5}"),
                        "planar3r", [0, 1], [0.8, 0.3], [0.1, 0.6, 0.5]),
    "planar-3r-far": (PLANAR_3R_WIDE.replace("start: {q1: 0.2, q2: -0.3, q3: 0.4}",
                                             "start: {q1: -1.0, q2: 2.0, q3: -0.5}"),
                      "planar3r", [0, 1], [0.8, 0.2], [-1.0, 2.0, -0.5]),
    "planar-3r-default": (PLANAR_3R_WIDE.replace(", start: {q1: 0.2, q2: -0.3, q3: 0.4}", ""),
                          "planar3r", [0, 1], [0.8, 0.2], [0.0, 0.0, 0.0]),
    "anthropomorphic-x-z": (ANTHRO.replace("from: {E.x: 0.5, E.y: 0.1, E.z: 0.6}, to: {E.x: 0.2, E.y: 0.5, E.z: 0.3}",
                                           "coordinates: [E.x, E.z], from: {E.x: 0.5, E.z: 0.6}, to: {E.x: 0.2, E.z: 0.3}")
                            .replace("max_acceleration: 2}", "max_acceleration: 2, start: {q1: 0.4, q2: 0.3, q3: 1.2}}"),
                            "anthro", [0, 2], [0.5, 0.6], [0.4, 0.3, 1.2]),
}


@pytest.mark.parametrize("key", list(WIDE_STARTS))
def test_a_wide_j_starts_at_the_solution_of_from_nearest_start(key):
    """Fewer coordinates than joints: `from` has a family of solutions, and the reported start is
    the one nearest `start` (q = 0 when none is given). Independent: scipy's SLSQP minimising
    |q − start|² subject to RTB's forward kinematics at `from`, from 16 random starts about
    `start`, the nearest of its answers."""
    from scipy.optimize import minimize

    from robosolve.run.pipeline import solve_problem

    text, robot, rows, target, given = WIDE_STARTS[key]
    answer = solve_problem(load_problem_text(text, "r.yaml")).answers[0]
    got = np.array(list(answer.numeric["start"].values()))
    r, q0, target = _rtb(robot), np.array(given), np.array(target)
    found = []
    for x0 in q0 + np.random.default_rng(5).uniform(-1.5, 1.5, (16, q0.size)):
        ref = minimize(lambda q: (q - q0) @ (q - q0), x0, jac=lambda q: 2 * (q - q0), method="SLSQP",
                       constraints=[{"type": "eq", "fun": lambda q: r.fkine(q).t[rows] - target,
                                     "jac": lambda q: r.jacob0(q)[rows]}], options={"ftol": 1e-15, "maxiter": 500})
        if ref.success and np.allclose(r.fkine(ref.x).t[rows], target, atol=1e-12):
            found.append(ref.x)
    nearest = min(found, key=lambda q: float(np.linalg.norm(q - q0)))
    assert got == pytest.approx(nearest, abs=1e-7)
    assert np.allclose(r.fkine(got).t[rows], target, atol=1e-12)
