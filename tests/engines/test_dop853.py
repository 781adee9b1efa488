"""robosolve.simulation.dop853 against scipy's solve_ivp(method="DOP853"): the same steps, the
same solution and the same dense output, bit for bit (the copy exists to skip scipy's import)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp as scipy_solve_ivp

from robosolve.simulation.dop853 import solve_ivp


def _pendulum(t, y):
    return np.array([y[1], -9.81 * np.sin(y[0]) - 0.3 * y[1] + 0.5 * np.cos(3 * t)])


def _arm(t, y):
    """A 2R-like closed loop: stiff gains, coupled inertia, a switching reference."""
    q, qd = y[:2], y[2:]
    ref = np.array([np.sin(t), 0.5 * t if t < 0.7 else 0.35])
    m = np.array([[2 + np.cos(q[1]), 0.5 + 0.5 * np.cos(q[1])], [0.5 + 0.5 * np.cos(q[1]), 0.5]])
    tau = 5000 * (ref - q) - 40 * qd
    return np.concatenate([qd, np.linalg.solve(m, tau - np.array([-np.sin(q[1]) * qd[1] ** 2, 0.0]))])


def _decay(t, y):
    return -50.0 * y


CASES = [(_pendulum, (0.0, 5.0), [1.0, 0.0], 1e-10, 1e-12),
         (_arm, (0.0, 1.3), [0.1, -0.2, 0.0, 0.0], 1e-10, 1e-12),
         (_arm, (0.2, 1.0), [0.0, 0.0, 1.0, -1.0], 1e-6, 1e-9),
         (_decay, (1.0, 0.0), [1.0, 2.0, 3.0], 1e-8, [1e-10, 1e-9, 1e-8]),
         (_pendulum, (0.0, 0.0), [0.3, 0.1], 1e-10, 1e-12)]


@pytest.mark.parametrize("case", range(len(CASES)))
def test_identical_to_scipy(case):
    fun, span, y0, rtol, atol = CASES[case]
    ours = solve_ivp(fun, span, np.array(y0), method="DOP853", rtol=rtol, atol=atol, dense_output=True)
    ref = scipy_solve_ivp(fun, span, np.array(y0), method="DOP853", rtol=rtol, atol=atol, dense_output=True)
    assert ours.success and ref.success and ours.status == ref.status
    assert ours.nfev == ref.nfev
    assert np.array_equal(ours.t, ref.t) and np.array_equal(ours.y, ref.y)
    lo, hi = min(span), max(span)
    probe = np.concatenate([np.linspace(lo - 0.1, hi + 0.1, 333), ref.t, [lo, hi]])
    assert np.array_equal(ours.sol(probe), ref.sol(probe))
    for t in probe[::17]:
        assert np.array_equal(ours.sol(float(t)), ref.sol(float(t)))


def test_without_dense_output_and_other_methods():
    ours = solve_ivp(_pendulum, (0, 1), [1.0, 0.0], method="DOP853", rtol=1e-9, atol=1e-12)
    ref = scipy_solve_ivp(_pendulum, (0, 1), [1.0, 0.0], method="DOP853", rtol=1e-9, atol=1e-12)
    assert ours.sol is None and np.array_equal(ours.y, ref.y)
    radau = solve_ivp(_decay, (0, 1), [1.0], method="Radau", rtol=1e-8, atol=1e-10, dense_output=True)
    assert radau.success and abs(radau.y[0, -1] - np.exp(-50)) < 1e-9


def test_failure_is_reported_like_scipy():
    def blow_up(t, y):
        return y ** 2
    ours = solve_ivp(blow_up, (0, 2), [1.0], method="DOP853", rtol=1e-10, atol=1e-12, dense_output=True)
    ref = scipy_solve_ivp(blow_up, (0, 2), [1.0], method="DOP853", rtol=1e-10, atol=1e-12, dense_output=True)
    assert not ours.success and ours.status == ref.status == -1
    assert ours.message == ref.message and np.array_equal(ours.t, ref.t)
