"""The instant of an extreme of integrated data is not decided by integration noise
(robosolve.core.extremes: values within the run's error of the extreme tie, the first instant
of the tie is reported).

References: closed forms (an equilibrium stays put; x'' = -w^2 x is A cos(w t - phi)) and scipy's
solve_ivp at rtol 1e-13.
"""

import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import solve_ivp

from robosolve.core.extremes import first_of_ties, tie_tolerance
from robosolve.dynamics.numeric import NumericDynamics
from robosolve.motion.profiles import synchronize
from robosolve.simulation.forward import compile_plant, integrate
from robosolve.simulation.joint_control import simulate

T_SYM = sp.Symbol("t")


def test_the_rule():
    # the first instant of the tie, with the value there; the round-off floor and the integrator's error
    assert first_of_ties([(1.0, 0.0), (1.0 + 1e-13, 0.5), (0.2, 0.7)], tie_tolerance(1.0)) == (1.0, 0.0)
    assert first_of_ties([(1.0, 0.0), (1.0 + 1e-9, 0.5)], tie_tolerance(1.0)) == (1.0 + 1e-9, 0.5)
    assert first_of_ties([(1.0, 0.0), (1.0 + 1e-9, 0.5)], tie_tolerance(1.0, 1e-10, 1e-12, 100)) == (1.0, 0.0)
    assert first_of_ties([(-2.0, 0.3), (-2.0 - 1e-14, 0.1), (5.0, 0.0)], tie_tolerance(5.0),
                         largest=False) == (-2.0 - 1e-14, 0.1)


def two_r_hanging():
    """The 2R of the report (L = 0.1, m = 0.01: a uniform rod, a point at the tip) in a vertical
    plane, its equations written by hand: hanging straight down, q = (-pi/2, 0), it is at rest."""
    L, m, g = 0.1, 0.01, 9.81
    q1, q2, r1, r2 = sp.symbols("q1 q2 r1 r2")
    c2, s2 = sp.cos(q2), sp.sin(q2)
    mass = [[L**2 * m * (2 * c2 + sp.Rational(7, 3)), L**2 * m * (c2 + 1)], [L**2 * m * (c2 + 1), L**2 * m]]
    velocity = [-L**2 * m * s2 * (2 * r1 * r2 + r2**2), L**2 * m * s2 * r1**2]
    gravity = [L * g * m * (sp.Rational(3, 2) * sp.cos(q1) + sp.cos(q1 + q2)), L * g * m * sp.cos(q1 + q2)]
    return compile_plant(mass, velocity, gravity, [0, 0], [q1, q2], [r1, r2], T_SYM)


def test_an_arm_at_rest_at_an_equilibrium_stays_at_its_start():
    # before: max of q1 at t = 0.471 s and min of q2 at t = 0.471 s, noise of 1e-14
    start = [-math.pi / 2, 0.0]
    run = integrate(two_r_hanging(), start, [0.0, 0.0], 0.5)
    assert list(run.q_max) == start and list(run.q_min) == start
    assert list(run.t_max) == [0.0, 0.0] and list(run.t_min) == [0.0, 0.0]
    assert list(run.still) == [True, True]


def test_a_joint_is_still_only_when_its_rate_stays_zero_too():
    # x'' = -1 from rest for 1e-6 s moves x by 5e-13, below the run's error on x; the rate
    # reaches 1e-6, far above it: the joint moves (a short run does not make it still)
    falling = compile_plant([[1]], [0], [1], [0], [sp.Symbol("x")], [sp.Symbol("v")], T_SYM)
    assert not integrate(falling, [0.0], [0.0], 1e-6).still[0]
    assert not integrate(oscillator(1.0), [1.0], [0.0], 3.0).still[0]
    assert integrate(oscillator(1.0), [0.0], [0.0], 3.0).still[0]


def oscillator(w2):
    x, v = sp.symbols("x v")
    return compile_plant([[1]], [0], [w2 * x], [0], [x], [v], T_SYM)


@pytest.mark.parametrize("x0,v0,duration", [(0.3, 0.0, 20.0), (2.0, 0.0, 50.0), (0.3, 0.4, 30.0)])
def test_an_undamped_oscillation_reports_its_first_crest_and_trough(x0, v0, duration):
    # x'' = -w^2 x: x = A cos(w t - phi); every crest is A, every trough -A (before: a crest
    # several periods on, the one the integrator's error lifted)
    w = 2.0
    amp, phi = math.hypot(x0, v0 / w), math.atan2(v0 / w, x0)
    run = integrate(oscillator(w * w), [x0], [v0], duration)
    assert run.t_max[0] == pytest.approx(phi / w, abs=1e-6)
    assert run.t_min[0] == pytest.approx((phi + math.pi) / w, abs=1e-6)
    assert run.q_max[0] == pytest.approx(amp, rel=1e-8)
    assert run.q_min[0] == pytest.approx(-amp, rel=1e-8)
    ref = solve_ivp(lambda t, y: [y[1], -w * w * y[0]], (0, duration), [x0, v0], method="DOP853",
                    rtol=1e-13, atol=1e-15, dense_output=True)
    assert ref.sol(run.t_max[0])[0] == pytest.approx(amp, rel=1e-10)
    assert ref.sol(run.t_min[0])[0] == pytest.approx(-amp, rel=1e-10)


@pytest.mark.parametrize("kp,duration", [(50.0, 10.0), (50.0, 40.0)])
def test_an_undamped_p_loop_reports_its_first_largest_error(kp, duration):
    # a mass of 2 kg held at 0 by tau = Kp e from x = 0.1 at rest: e = -0.1 cos(w t), every crest
    # of |e| is 0.1, the first at t = 0 (before: a crest at 4.4 s / 36.4 s)
    x, xd = sp.symbols("x x_dot")
    dyn = NumericDynamics.from_symbolic(sp.Matrix([[2]]), sp.Matrix([0]), sp.Matrix([0]), [x], [xd], subs={})
    plan = synchronize(["x"], [0], [0], [1]).numeric_plan()
    res = simulate(dyn, plan, "p", [kp], None, start=[0.1], duration=duration)
    w = math.sqrt(kp / 2)
    assert res.t_max_error[0] == 0.0
    assert res.max_error[0] == pytest.approx(0.1, rel=1e-12)
    assert res.final_error[0] == pytest.approx(-0.1 * math.cos(w * duration), abs=1e-6)
    assert np.all(np.abs(res.error[0]) <= 0.1 * (1 + 1e-6))
