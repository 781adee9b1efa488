"""Forward dynamics (robosolve.simulation.forward) against independent references.

robosolve's side: the problem's own equations of motion (robosolve's dynamics engine, from a
problem file), compiled by ``compile_plant`` and integrated by ``integrate`` (DOP853).
Reference side: a pinocchio model built here joint by joint from the same data, ``aba`` for
the accelerations, integrated by a different scipy method (LSODA) at rtol 1e-12.  Arms: the
course's one-link arm (1R, with its follower force), a planar 2R in a vertical plane and an
RP arm; laws: free, constant, time-varying and state feedback.
"""

import math

import numpy as np
import pytest
import sympy as sp

from robosolve.core.symbols import TIME
from robosolve.load.loader import load_problem_text
from robosolve.model import RobotModel
from robosolve.dynamics.bridge import dynamics_for
from robosolve.simulation.forward import RunTooLong, compile_plant, integrate

pin = pytest.importorskip("pinocchio")

T_SYM = TIME   # the loader's time symbol

ONE_LINK = """
robosolve: 1
name: one-link
parameters: {L: 1, m1: 2, m2: 1, g: 9.81, F: 3}
joints: [{name: theta, type: revolute, actuator: C}]
frames: {"1": {parent: "0", pose: "Rx(theta) Ty(L)"}}
bodies:
  - {name: link, frame: "1", mass: m1, rod: {from: [0, -L, 0], to: [0, 0, 0]}}
  - {name: payload, frame: "1", mass: m2, point: [0, 0, 0]}
forces: [%s]
questions: [{type: equations_of_motion}]
"""
FOLLOWER = '{name: F, frame: "1", at: [0, -L/3, 0], force: [0, 0, -F]}'

TWO_R = """
robosolve: 1
name: two-r
parameters: {L1: 0.5, L2: 0.4, m1: 3, m2: 2, I1: 0.06, I2: 0.03, g: 9.81}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
gravity: [0, -g, 0]
bodies:
  - {name: b1, frame: "1", mass: m1, com: [-0.25, 0, 0], inertia: [[0, 0, 0], [0, 0, 0], [0, 0, I1]]}
  - {name: b2, frame: "2", mass: m2, com: [-0.2, 0, 0], inertia: [[0, 0, 0], [0, 0, 0], [0, 0, I2]]}
questions: [{type: equations_of_motion}]
"""

RP = """
robosolve: 1
name: rp
parameters: {m1: 2, m2: 1.5, I1: 0.05, I2: 0.02, g: 9.81}
joints: [{name: q1, type: revolute}, {name: d, type: prismatic}]
frames:
  "1": {parent: "0", pose: "Rz(q1)"}
  "2": {pose: "Tx(d)"}
gravity: [0, -g, 0]
bodies:
  - {name: b1, frame: "1", mass: m1, com: [0.3, 0, 0], inertia: [[0, 0, 0], [0, 0, 0], [0, 0, I1]]}
  - {name: b2, frame: "2", mass: m2, com: [0, 0, 0], inertia: [[0, 0, 0], [0, 0, 0], [0, 0, I2]]}
questions: [{type: equations_of_motion}]
"""


# ---------------------------------------------------------------- pinocchio references
def pin_one_link(follower: bool):
    L, m1, m2, g, F = 1.0, 2.0, 1.0, 9.81, 3.0
    model = pin.Model()
    j = model.addJoint(0, pin.JointModelRX(), pin.SE3.Identity(), "theta")
    rod = pin.Inertia(m1, np.array([0, L / 2, 0]), np.diag([m1 * L ** 2 / 12, 0, m1 * L ** 2 / 12]))
    tip = pin.Inertia(m2, np.array([0, L, 0]), np.zeros((3, 3)))
    model.appendBodyToJoint(j, rod, pin.SE3.Identity())
    model.appendBodyToJoint(j, tip, pin.SE3.Identity())
    model.gravity.linear = np.array([0, 0, -g])
    fext = None
    if follower:     # (0, 0, -F) in the link's frame at 2L/3 from the joint: turns with the link
        p, f = np.array([0, 2 * L / 3, 0]), np.array([0, 0, -F])
        fext = [pin.Force.Zero(), pin.Force(f, np.cross(p, f))]
    return model, fext


def pin_two_r():
    model = pin.Model()
    j1 = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "q1")
    model.appendBodyToJoint(j1, pin.Inertia(3.0, np.array([0.25, 0, 0]), np.diag([0, 0, 0.06])), pin.SE3.Identity())
    j2 = model.addJoint(j1, pin.JointModelRZ(), pin.SE3(np.eye(3), np.array([0.5, 0, 0])), "q2")
    model.appendBodyToJoint(j2, pin.Inertia(2.0, np.array([0.2, 0, 0]), np.diag([0, 0, 0.03])), pin.SE3.Identity())
    model.gravity.linear = np.array([0, -9.81, 0])
    return model, None


def pin_rp():
    model = pin.Model()
    j1 = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "q1")
    model.appendBodyToJoint(j1, pin.Inertia(2.0, np.array([0.3, 0, 0]), np.diag([0, 0, 0.05])), pin.SE3.Identity())
    j2 = model.addJoint(j1, pin.JointModelPX(), pin.SE3.Identity(), "d")
    model.appendBodyToJoint(j2, pin.Inertia(1.5, np.zeros(3), np.diag([0, 0, 0.02])), pin.SE3.Identity())
    model.gravity.linear = np.array([0, -9.81, 0])
    return model, None


def reference(pin_model, law, q0, qd0, duration):
    """pinocchio aba + LSODA at rtol 1e-12: final state and extremes (dense sampling, refined)."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import minimize_scalar

    model, fext = pin_model
    data = model.createData()
    n = model.nq

    def f(t, y):
        q, v = y[:n], y[n:]
        tau = np.asarray(law(t, q, v), dtype=float)
        a = pin.aba(model, data, q, v, tau) if fext is None else pin.aba(model, data, q, v, tau, fext)
        return np.concatenate([v, a])

    sol = solve_ivp(f, (0, duration), np.concatenate([q0, qd0]), method="LSODA", rtol=1e-12,
                    atol=1e-13, dense_output=True)
    assert sol.success
    ts = np.linspace(0, duration, 20001)
    ys = sol.sol(ts)
    out = {"final": sol.y[:n, -1], "final_velocity": sol.y[n:, -1], "max": [], "min": []}
    for i in range(n):
        for key, sign in (("max", 1), ("min", -1)):
            k = int(np.argmax(sign * ys[i]))
            best = sign * ys[i, k]
            if 0 < k < ts.size - 1:
                r = minimize_scalar(lambda s: -sign * sol.sol(s)[i], bounds=(ts[k - 1], ts[k + 1]),
                                    method="bounded", options={"xatol": 1e-13})
                best = max(best, -r.fun)
            out[key].append(sign * best)
    return out


# ---------------------------------------------------------------- robosolve's side
def robosolve_run(text, laws, q0, qd0, duration, numeric_solve=False, **kw):
    """Integrate the problem's own equations of motion with the actuator laws (t, q, qd)."""
    problem = load_problem_text(text)
    model = RobotModel(problem)
    dyn = dynamics_for(model)
    params = {s: v for s, v in problem.parameters.items()}
    t = T_SYM
    rep = dict(params)
    rep.update({a: sp.sympify(laws[i](t, dyn.q, dyn.qd)) for i, a in enumerate(dyn.actuators)})
    forces = [sp.sympify(e).xreplace(rep).xreplace(params) for e in dyn.generalized_forces]
    num = lambda e: sp.sympify(e).xreplace(params)
    plant = compile_plant(dyn.mass_matrix.xreplace(params), dyn.velocity_terms.xreplace(params),
                          dyn.gravity_terms.xreplace(params), forces, dyn.q, dyn.qd, t,
                          kinetic=num(sp.Add(*dyn.kinetic_energy.values())),
                          potential=num(sp.Add(*dyn.potential_energy.values())),
                          symbolic_solve_up_to=0 if numeric_solve else 3)
    return integrate(plant, q0, qd0, duration, **kw)


def numeric_law(law_sym):
    """The same law as a numeric function for the reference (t, q, v) -> tau."""
    return law_sym


def check(run, ref):
    scale = max(1.0, float(np.max(np.abs(np.concatenate([run.q_max, run.q_min])))))
    vscale = max(1.0, float(np.max(np.abs(run.qd))))
    assert np.allclose(run.final, ref["final"], rtol=0, atol=1e-8 * scale), (run.final, ref["final"])
    assert np.allclose(run.final_velocity, ref["final_velocity"], rtol=0, atol=1e-8 * vscale)
    assert np.allclose(run.q_max, ref["max"], rtol=0, atol=1e-8 * scale), (run.q_max, ref["max"])
    assert np.allclose(run.q_min, ref["min"], rtol=0, atol=1e-8 * scale), (run.q_min, ref["min"])


# laws as pairs (symbolic for robosolve, numeric for pinocchio) per joint
def zero(n):
    return [lambda t, q, qd: 0] * n, lambda t, q, v: np.zeros(n)


CASES_1R = {
    "free": ([lambda t, q, qd: 0], lambda t, q, v: [0.0], False),
    "constant_weak": ([lambda t, q, qd: 10], lambda t, q, v: [10.0], False),
    "constant_strong": ([lambda t, q, qd: 40], lambda t, q, v: [40.0], False),
    "sine_with_force": ([lambda t, q, qd: 70 * sp.sin(t)], lambda t, q, v: [70 * math.sin(t)], True),
    "pd_feedback": ([lambda t, q, qd: -80 * (q[0] - sp.pi / 4) - 6 * qd[0]],
                    lambda t, q, v: [-80 * (q[0] - math.pi / 4) - 6 * v[0]], False),
}


@pytest.mark.parametrize("case", list(CASES_1R))
def test_one_link_against_pinocchio(case):
    sym, num, follower = CASES_1R[case]
    text = ONE_LINK % (FOLLOWER if follower else "")
    run = robosolve_run(text, sym, [0.0], [0.0], 5.0)
    check(run, reference(pin_one_link(follower), num, np.zeros(1), np.zeros(1), 5.0))


CASES_2R = {
    "free": ([lambda t, q, qd: 0] * 2, lambda t, q, v: [0.0, 0.0]),
    "constant": ([lambda t, q, qd: 25, lambda t, q, qd: -3], lambda t, q, v: [25.0, -3.0]),
    "time_varying": ([lambda t, q, qd: 15 * sp.cos(2 * t), lambda t, q, qd: 2 * sp.sin(3 * t)],
                     lambda t, q, v: [15 * math.cos(2 * t), 2 * math.sin(3 * t)]),
    "pd_feedback": ([lambda t, q, qd: -60 * (q[0] - 1) - 8 * qd[0],
                     lambda t, q, qd: -30 * (q[1] + sp.Rational(1, 2)) - 3 * qd[1]],
                    lambda t, q, v: [-60 * (q[0] - 1) - 8 * v[0], -30 * (q[1] + 0.5) - 3 * v[1]]),
}


@pytest.mark.parametrize("case", list(CASES_2R))
def test_two_r_against_pinocchio(case):
    sym, num = CASES_2R[case]
    q0, qd0 = np.array([0.3, -0.2]), np.array([0.0, 0.5])
    run = robosolve_run(TWO_R, sym, q0, qd0, 3.0)
    check(run, reference(pin_two_r(), num, q0, qd0, 3.0))


def test_two_r_numeric_solve_path_against_pinocchio():
    # the path of robots with more than 3 joints (M solved by numpy at each evaluation)
    sym, num = CASES_2R["time_varying"]
    q0, qd0 = np.array([0.3, -0.2]), np.array([0.0, 0.5])
    run = robosolve_run(TWO_R, sym, q0, qd0, 3.0, numeric_solve=True)
    check(run, reference(pin_two_r(), num, q0, qd0, 3.0))


CASES_RP = {
    "free": ([lambda t, q, qd: 0] * 2, lambda t, q, v: [0.0, 0.0]),
    "constant": ([lambda t, q, qd: 12, lambda t, q, qd: 2], lambda t, q, v: [12.0, 2.0]),
    "time_varying": ([lambda t, q, qd: 10 * sp.sin(t), lambda t, q, qd: 3 * sp.cos(2 * t) - 1],
                     lambda t, q, v: [10 * math.sin(t), 3 * math.cos(2 * t) - 1]),
    "state_feedback": ([lambda t, q, qd: -40 * q[0] - 5 * qd[0] + 9.81 * 2.0 * 0.3 * sp.cos(q[0]),
                        lambda t, q, qd: -50 * (q[1] - sp.Rational(1, 2)) - 4 * qd[1]],
                       lambda t, q, v: [-40 * q[0] - 5 * v[0] + 9.81 * 2.0 * 0.3 * math.cos(q[0]),
                                        -50 * (q[1] - 0.5) - 4 * v[1]]),
}


@pytest.mark.parametrize("case", list(CASES_RP))
def test_rp_against_pinocchio(case):
    sym, num = CASES_RP[case]
    q0, qd0 = np.array([0.2, 0.4]), np.array([0.0, 0.0])
    run = robosolve_run(RP, sym, q0, qd0, 2.0)
    check(run, reference(pin_rp(), num, q0, qd0, 2.0))


@pytest.mark.parametrize("text,q0,qd0", [(ONE_LINK % "", [0.0], [0.0]),
                                         (TWO_R, [0.3, -0.2], [0.0, 0.5]),
                                         (RP, [0.2, 0.4], [1.0, 0.0])])
def test_free_runs_conserve_energy(text, q0, qd0):
    n = len(q0)
    run = robosolve_run(text, [lambda t, q, qd: 0] * n, q0, qd0, 3.0)
    assert run.work == 0.0
    assert abs(run.energy_end - run.energy_start) <= 1e-8 * run.energy_scale
    assert run.energy_drift <= 1e-8 * run.energy_scale


def test_work_of_a_constant_torque_balances_the_energy():
    run = robosolve_run(ONE_LINK % "", [lambda t, q, qd: 10], [0.0], [0.0], 4.0)
    # W = C * (theta_end - theta_start), closed form for a constant torque
    assert run.work == pytest.approx(10 * run.final[0], rel=1e-8)
    assert abs(run.energy_end - run.energy_start - run.work) <= 1e-8 * run.energy_scale


def test_small_oscillation_period_of_the_pendulum():
    # one-link arm hanging at theta = -pi/2, released 1e-3 rad away: period 2 pi sqrt(I / (m g d))
    L, m1, m2, g = 1.0, 2.0, 1.0, 9.81
    inertia = (m1 / 3 + m2) * L ** 2
    mgd = (m1 / 2 + m2) * g * L
    period = 2 * math.pi * math.sqrt(inertia / mgd)
    eps = 1e-3
    run = robosolve_run(ONE_LINK % "", [lambda t, q, qd: 0], [-math.pi / 2 + eps], [0.0], 0.75 * period)
    # released at the top of its swing: the lowest value comes half a period later
    assert run.t_min[0] == pytest.approx(period / 2, rel=1e-6)
    assert run.q_min[0] == pytest.approx(-math.pi / 2 - eps, rel=1e-9)


def test_free_pendulum_swings_between_0_and_minus_pi():
    run = robosolve_run(ONE_LINK % "", [lambda t, q, qd: 0], [0.0], [0.0], 6.0)
    assert run.q_max[0] == pytest.approx(0.0, abs=1e-9)
    assert run.q_min[0] == pytest.approx(-math.pi, abs=1e-7)


def test_spinning_arm_is_unwrapped():
    run = robosolve_run(ONE_LINK % "", [lambda t, q, qd: 60], [0.0], [0.0], 4.0)
    assert run.final[0] > 4 * math.pi          # several turns, not reduced modulo 2 pi
    assert run.q_max[0] == run.final[0]


def test_budget_stops_a_stiff_run_with_a_reason():
    # an enormous damping gain: eigenvalue ~ -1e9 s^-1 on a 5 s run
    with pytest.raises(RunTooLong, match="stiff"):
        robosolve_run(ONE_LINK % "", [lambda t, q, qd: -1e9 * qd[0] - 1e12 * q[0]], [0.1], [0.0], 5.0,
                      max_evaluations=20000)


def test_stiff_run_is_handed_to_radau():
    # heavy damping: eigenvalues ~ -6e4 and ~ -1 s^-1; DOP853 would need ~1e5 steps
    run = robosolve_run(ONE_LINK % "", [lambda t, q, qd: -1e5 * qd[0]], [0.0], [0.0], 1.0,
                        max_evaluations=100_000)
    assert run.method == "Radau" and "stiff" in run.notes[0]
    # overdamped: the arm creeps down at the terminal speed g(theta) / 1e5
    assert -1e-3 < run.final[0] < 0
