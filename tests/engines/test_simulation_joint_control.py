"""Closed-loop control simulation, checked against an independent pinocchio ``aba`` simulation."""

import numpy as np
import pytest
import sympy as sp

from robosolve.simulation.joint_control import simulate
from robosolve.dynamics.numeric import NumericDynamics
from robosolve.motion.profiles import synchronize

from tests.support.robots import arm2r_pin as pin_model, arm2r_symbolic as symbolic


@pytest.fixture(scope="module")
def arm():
    M, c, g, q, qd, qdd, params = symbolic()
    return NumericDynamics.from_symbolic(M, c, g, q, qd, subs=params)


@pytest.fixture(scope="module")
def plan():
    # 2 s bang-bang profile (joint 1 is the slowest)
    return synchronize(["q1", "q2"], [0, 0], [sp.pi / 2, -sp.pi / 4], [sp.pi / 2, 2]).numeric_plan()


def reference(plan, law, kp, kd, duration, start=None, method="DOP853"):
    """Independent simulation: pinocchio aba/rnea, state (q, qd), DOP853 (or Radau) at 1e-12."""
    pin = pytest.importorskip("pinocchio")
    from scipy.integrate import solve_ivp
    model = pin_model()
    data = model.createData()
    kp = np.asarray(kp, float)
    kd = np.zeros(2) if kd is None else np.asarray(kd, float)
    br = [b for b in plan.breaks if b < duration] + [duration]
    y = np.concatenate([plan.start if start is None else np.asarray(start, float), np.zeros(2)])
    errs = []
    for a, b in zip(br[:-1], br[1:]):
        k = plan.interval(a) if a < plan.T else None

        def f(t, y, k=k):
            qdes, vdes, ades = (x[:, 0] for x in plan.evaluate([t], k=k))
            x, v = y[:2], y[2:]
            e, ed = qdes - x, vdes - v
            if law == "p":
                tau = kp * e
            elif law == "pd":
                tau = kp * e + kd * ed
            elif law == "pd_gravity":
                tau = kp * e + kd * ed + pin.computeGeneralizedGravity(model, data, x)
            else:
                tau = pin.rnea(model, data, x, v, ades + kd * ed + kp * e)
            return np.concatenate([v, pin.aba(model, data, x, v, tau)])

        sol = solve_ivp(f, (a, b), y, method=method, rtol=1e-10, atol=1e-13, dense_output=True)
        y = sol.y[:, -1]
        ts = np.linspace(a, b, 40001)
        errs.append(plan.evaluate(ts, k=k)[0] - sol.sol(ts)[:2])
    e = np.hstack(errs)
    return np.abs(e).max(axis=1), e[:, -1]


def _check(res, ref):
    mx, fin = ref
    assert np.allclose(res.max_error, mx, rtol=1e-4, atol=0)
    # the final error is signed and may sit near zero: relative to the max error
    assert np.all(np.abs(res.final_error - fin) <= 1e-4 * mx)


def test_pd_against_pinocchio(arm, plan):
    # 1.2 s: crosses the switching instant T/2 = 1 s
    res = simulate(arm, plan, "pd", [400, 300], [40, 20], duration=1.2)
    _check(res, reference(plan, "pd", [400, 300], [40, 20], 1.2))


@pytest.mark.slow
@pytest.mark.parametrize("law,kd", [("p", None), ("pd", [100, 100]), ("pd_gravity", [100, 100])])
def test_laws_against_pinocchio_kp_5000(arm, plan, law, kd):
    res = simulate(arm, plan, law, [5000, 5000], kd, duration=2.5)
    _check(res, reference(plan, law, [5000, 5000], kd, 2.5))


@pytest.mark.slow
def test_stiff_loop_high_derivative_gain(arm, plan):
    # Kd = 1e5 on links of inertia ~0.1: eigenvalues near -1e6, a non-stiff method would
    # need ~1e6 steps; LSODA switches to BDF
    res = simulate(arm, plan, "pd", [5000, 5000], [1e5, 1e5], duration=1.0)
    assert res.nfev < 20000
    _check(res, reference(plan, "pd", [5000, 5000], [1e5, 1e5], 1.0, method="Radau"))


def test_computed_torque_tracks_exactly(arm, plan):
    res = simulate(arm, plan, "computed_torque", [100, 100], [20, 20])
    assert np.all(res.max_error < 1e-9)
    # from a wrong start it converges: e'' + Kd e' + Kp e = 0, critically damped here
    res = simulate(arm, plan, "computed_torque", [100, 100], [20, 20], start=[0.1, -0.1])
    assert res.max_error == pytest.approx([0.1, 0.1], rel=1e-9)
    e_ref = 0.1 * (1 + 10 * 2.0) * np.exp(-10 * 2.0)        # (1 + wt) e^(-wt), w = 10
    assert res.final_error == pytest.approx([-e_ref, e_ref], rel=1e-5)


def test_error_shrinks_as_kp_grows(arm, plan):
    errs = [simulate(arm, plan, "p", [kp, kp], duration=1.0).max_error for kp in (200, 2000, 20000)]
    assert np.all(errs[0] > errs[1]) and np.all(errs[1] > errs[2])
    # roughly 1/Kp for a P controller (gravity and inertia loads over a stiff spring)
    assert np.all(errs[1] / errs[2] > 5)


def test_zero_gains_the_arm_falls(arm, plan):
    res = simulate(arm, plan, "p", [0, 0], duration=0.5)
    # starting horizontal at rest, gravity pulls joint 1 down: q1 < 0, e1 = q_d - q > 0
    q_end = res.q[:, -1]
    assert q_end[0] < -0.2
    mx, fin = reference(plan, "p", [0, 0], None, 0.5)
    assert np.allclose(res.final_error, fin, rtol=1e-6)
    assert np.allclose(res.max_error, mx, rtol=1e-6)


def test_effort_and_samples(arm, plan):
    res = simulate(arm, plan, "p", [5000, 5000], duration=2.5)
    assert res.t[0] == 0 and res.t[-1] == 2.5
    assert np.allclose(res.effort, 5000 * res.error)
    assert np.allclose(res.q + res.error, res.q_desired)
    # after T the desired trajectory holds the end values
    assert np.allclose(res.q_desired[:, -1], [np.pi / 2, -np.pi / 4])


def test_bad_law(arm, plan):
    with pytest.raises(ValueError, match="unknown control law"):
        simulate(arm, plan, "pid", [1, 1])


def test_time_budget_explains_the_oscillation(arm, plan):
    from robosolve.simulation.joint_control import SimulationTooLong

    with pytest.raises(SimulationTooLong, match="oscillates at up to .* Hz"):
        simulate(arm, plan, "p", [5e6, 5e6], time_limit=0.05)


def test_counted_budget_stops_a_stiff_loop_the_same_way_on_any_machine(arm, plan):
    """The budget is a count of right-hand-side evaluations, not seconds (issue 11): the same
    input stops at the same point whatever the load."""
    from robosolve.simulation.joint_control import SimulationTooLong

    with pytest.raises(SimulationTooLong, match="budget of 2,000 evaluations.*oscillates at up to"):
        simulate(arm, plan, "p", [5e6, 5e6], time_limit=None, max_evaluations=2000)


def test_negative_gain_is_described_as_unstable(arm, plan):
    from robosolve.simulation.joint_control import SimulationTooLong

    with pytest.raises(SimulationTooLong, match="negative gain makes the loop unstable"):
        simulate(arm, plan, "p", [-5000, 100], time_limit=None, max_evaluations=2000)


def test_max_abs_refined_finds_a_crest_between_samples_and_the_earliest_of_a_tie():
    from robosolve.simulation.joint_control import max_abs_refined

    w = 7.3
    ts = np.linspace(0.0, 1.0, 23)                 # coarse: the crests fall between samples
    f = lambda t: 2.5 * np.sin(w * t)               # noqa: E731  |f| peaks at pi/(2w) and 3pi/(2w)
    value, where = max_abs_refined(f, ts, f(ts), xatol=1e-13)
    assert value == pytest.approx(2.5, rel=1e-12)
    assert where == pytest.approx(np.pi / (2 * w), abs=1e-6)      # the earlier of the two equal crests
