"""Actuator forces along a profile, checked against Robotics Toolbox ``rne`` on a 2R arm."""

import numpy as np
import pytest
import sympy as sp

from robosolve.dynamics.numeric import NumericDynamics
from robosolve.motion.profiles import synchronize
from robosolve.motion.torques import closed_form_pieces, torques_along

from tests.support.robots import arm2r_rtb as rtb_robot, arm2r_symbolic as symbolic


@pytest.fixture(scope="module")
def arm():
    M, c, g, q, qd, qdd, params = symbolic()
    dyn = NumericDynamics.from_symbolic(M, c, g, q, qd, subs=params)
    tau = M * sp.Matrix(qdd) + c + g
    return dict(M=M, c=c, g=g, q=q, qd=qd, qdd=qdd, params=params, dyn=dyn, tau=list(tau))


@pytest.mark.parametrize("shape", ["bang-bang", "trapezoidal", "quintic"])
def test_torques_match_rne_along_the_trajectory(arm, shape):
    robot = rtb_robot()
    prof = synchronize(["q1", "q2"], [0, 0], [sp.pi / 2, -sp.pi / 4], [sp.pi / 2, 2], shape=shape, max_velocity=[1, 1])
    res = torques_along(prof, arm["dyn"], ["C1", "C2"])
    plan = prof.numeric_plan()
    for (a, b) in res.intervals:
        k = plan.interval((a + b) / 2)
        ts = np.linspace(a, b, 23)
        Q, QD, QDD = plan.evaluate(ts, k=k)
        ref = np.array([robot.rne(Q[:, m], QD[:, m], QDD[:, m]) for m in range(ts.size)]).T
        mine = arm["dyn"].inverse_many(Q, QD, QDD)
        assert np.allclose(mine, ref, atol=1e-10)
    # the closed form, piece by piece, gives the same numbers
    pieces, pw = closed_form_pieces(prof, arm["tau"], arm["q"], arm["qd"], arm["qdd"], arm["params"])
    for i in range(2):
        f = sp.lambdify(prof.t, pw[i], "math")
        for (a, b) in res.intervals:
            for s in np.linspace(a, b, 7)[1:-1]:
                Q, QD, QDD = plan.evaluate([s])
                assert f(s) == pytest.approx(robot.rne(Q[:, 0], QD[:, 0], QDD[:, 0])[i], rel=1e-9, abs=1e-9)


def test_peaks_are_signed_extremes_with_one_sided_limits(arm):
    robot = rtb_robot()
    prof = synchronize(["q1", "q2"], [0, 0], [sp.pi / 2, -sp.pi / 4], [sp.pi / 2, 2])
    res = torques_along(prof, arm["dyn"], ["C1", "C2"])
    plan = prof.numeric_plan()
    # brute force with rne on a very fine grid of every interval (closed at both ends)
    for i in range(2):
        best = (0.0, 0.0)
        for (a, b) in res.intervals:
            k = plan.interval((a + b) / 2)
            ts = np.linspace(a, b, 4001)
            Q, QD, QDD = plan.evaluate(ts, k=k)
            vals = np.array([robot.rne(Q[:, m], QD[:, m], QDD[:, m])[i] for m in range(ts.size)])
            m = int(np.argmax(np.abs(vals)))
            if abs(vals[m]) > abs(best[0]):
                best = (vals[m], ts[m])
        assert res.peaks[i] == pytest.approx(best[0], rel=1e-6)
        assert abs(res.t_peaks[i] - best[1]) < 2e-3
    # joint 1 starts horizontal under gravity with +acceleration: its peak is the
    # one-sided value just after t = 0
    assert res.t_peaks[0] == 0.0
    Q, QD, QDD = plan.evaluate([0.0], k=0)
    assert res.peaks[0] == pytest.approx(robot.rne(Q[:, 0], QD[:, 0], QDD[:, 0])[0], rel=1e-12)


def test_torques_jump_at_the_switching_instants(arm):
    prof = synchronize(["q1", "q2"], [0, 0], [1, 1], [2, 2])
    res = torques_along(prof, arm["dyn"], ["C1", "C2"])
    T = float(prof.T)
    assert res.breaks == [pytest.approx(T / 2)]
    # each switching instant is sampled on both sides
    mid = np.nonzero(np.isclose(res.t, T / 2))[0]
    assert len(mid) == 2
    jump = res.values[:, mid[1]] - res.values[:, mid[0]]
    # the jump is M(q(T/2)) times the acceleration step (-2a)
    q_mid = prof.numeric_plan().evaluate([T / 2])[0][:, 0]
    m, _c, _g, _f = arm["dyn"].terms(q_mid, np.zeros(2))
    qd_mid = prof.numeric_plan().evaluate([T / 2])[1][:, 0]
    m, _c, _g, _f = arm["dyn"].terms(q_mid, qd_mid)
    assert np.allclose(jump, m @ np.array([-4.0, -4.0]), rtol=1e-9)


def test_closed_form_is_exact_with_exact_inputs():
    q1, qd1, qdd1, m, L, g = sp.symbols("q1 q1_dot q1_ddot m L g")
    # one-link pendulum, rod: (mL^2/3) qdd + (mgL/2) cos q = C
    tau = m * L ** 2 / 3 * qdd1 + m * g * L / 2 * sp.cos(q1)
    prof = synchronize(["q1"], [0], [sp.pi / 2], [sp.pi])
    pieces, pw = closed_form_pieces(prof, [tau], [q1], [qd1], [qdd1])
    t = prof.t
    assert sp.simplify(pieces[0][0] - (m * L ** 2 * sp.pi / 3 + m * g * L / 2 * sp.cos(sp.pi * t ** 2 / 2))) == 0
    assert pw[0].subs(t, 5) == 0            # held vertical at the end: no gravity torque


def test_jump_table(arm):
    robot = rtb_robot()
    prof = synchronize(["q1", "q2"], [0, 0], [1, 1], [2, 2])
    res = torques_along(prof, arm["dyn"], ["C1", "C2"])
    T = float(prof.T)
    assert [j[0] for j in res.jumps] == [0.0, pytest.approx(T / 2), pytest.approx(T)]
    # before 0 and after T: the static holding torques (rne at rest)
    assert np.allclose(res.jumps[0][1], robot.rne(np.zeros(2), np.zeros(2), np.zeros(2)))
    assert np.allclose(res.jumps[-1][2], robot.rne(np.ones(2), np.zeros(2), np.zeros(2)))
    # just after 0: the acceleration +a = 4|D|/T^2 = 2 starts
    assert np.allclose(res.jumps[0][2], robot.rne(np.zeros(2), np.zeros(2), np.full(2, 2.0)))


def _sliding_mass(m=2.0):
    """One prismatic joint moving a mass m horizontally: F = m x''."""
    x, xd = sp.symbols("x x_dot")
    return NumericDynamics.from_symbolic(sp.Matrix([[m]]), sp.Matrix([0]), sp.Matrix([0]), [x], [xd])


@pytest.mark.parametrize("delta", [-0.3, 0.3])
def test_a_tie_between_two_interior_peaks_goes_to_the_earlier_one(delta):
    # F = m x'' along a quintic: two peaks of equal magnitude m * 10|D|/(sqrt(3) T^2), at
    # u = (3 -+ sqrt(3))/6 of T (closed form), the first with the sign of D.  Both lie inside
    # the one interval [0, T]: the earlier must win, not whichever sample round-off favours.
    m, a = 2.0, 2.0
    prof = synchronize(["x"], [0], [delta], [a], shape="quintic")
    res = torques_along(prof, _sliding_mass(m), ["F1"])
    T = float(prof.T)
    assert T == pytest.approx((10 * abs(delta) / (3 ** 0.5 * a)) ** 0.5, rel=1e-14)
    assert res.peaks[0] == pytest.approx(np.sign(delta) * m * a, rel=1e-12)
    assert res.t_peaks[0] == pytest.approx(T * (3 - 3 ** 0.5) / 6, abs=1e-7)


def test_a_constant_force_over_an_interval_peaks_at_its_start():
    # bang-bang on a sliding mass: F = +m a on [0, T/2], -m a on [T/2, T] (equal magnitudes,
    # constant on each interval): the tie goes to t = 0, with the sign of the first half
    prof = synchronize(["x"], [1], [-1], [2])
    res = torques_along(prof, _sliding_mass(3.0), ["F1"])
    assert res.peaks[0] == pytest.approx(-6.0, rel=1e-14)
    assert res.t_peaks[0] == 0.0
