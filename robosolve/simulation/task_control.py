"""Work-space control (course summary §1.2.2, the actual scheme): the error in the task
coordinates e = x_d - x(q) drives the actuators.

* ``task_pd_gravity``:      tau = J^T (Kp e + Kd e_dot) + g(q)
* ``task_computed_torque``: tau = M J^-1 (x_ddot_d + Kd e_dot + Kp e - J_dot q_dot) + c + g

integrated on the plant M q_ddot + c + g = tau + f_ext with state (q, q_dot), restarted at each
switching instant of the timing law; the errors' extremes are refined on the dense output (crests
within the run's error of the largest tie, the first is reported: core/extremes.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from robosolve.core.extremes import first_of_ties, tie_tolerance
from robosolve.simulation.joint_control import (MAX_EVALUATIONS, TIME_LIMIT, SimulationTooLong, _Budget,
                                                 polished_crests)

TASK_LAWS = ("task_pd_gravity", "task_computed_torque")
RTOL = 1e-10
ATOL = 1e-12


@dataclass
class TaskControlResult:
    law: str
    duration: float
    t: np.ndarray            # (N,)
    q: np.ndarray            # (n, N)
    x: np.ndarray            # (m, N) actual task coordinates
    x_desired: np.ndarray    # (m, N)
    error: np.ndarray        # (m, N) e = x_d - x
    effort: np.ndarray       # (n, N)
    max_error: np.ndarray    # (m,)
    t_max_error: np.ndarray  # (m,)
    final_error: np.ndarray  # (m,)
    nfev: int = 0


def task_torque(law, kp, kd, arm, q, qd, xd, vd, ad, m, c, g):
    J = arm.J(q)
    e = xd - arm.x(q)
    ed = vd - J @ qd
    if law == "task_pd_gravity":
        return J.T @ (kp * e + kd * ed) + g
    return m @ np.linalg.solve(J, ad + kd * ed + kp * e - arm.jdot_qdot(q, qd)) + c + g


def _intervals(breaks, T, duration):
    out = [(breaks[k], min(breaks[k + 1], duration), k) for k in range(len(breaks) - 1) if breaks[k] < duration]
    if duration > T:
        out.append((T, duration, None))
    return out


def simulate_task(dyn, arm, desired, breaks, law, kp, kd, q0, duration, samples=2001,
                  max_evaluations=None, time_limit=TIME_LIMIT) -> TaskControlResult:
    """``desired(t, segment) -> (x_d, x_dot_d, x_ddot_d)``; ``breaks`` of the timing law [0, ..., T]."""
    import time

    from robosolve.simulation.dop853 import solve_ivp

    if law not in TASK_LAWS:
        raise ValueError(f"unknown task law {law!r}")
    n = dyn.n
    kp, kd = np.asarray(kp, dtype=float), np.asarray(kd, dtype=float)
    T = float(breaks[-1])
    deadline = None if not time_limit else time.monotonic() + time_limit
    budget = _Budget(MAX_EVALUATIONS if max_evaluations is None else max_evaluations, deadline,
                     lambda why: f"the closed-loop simulation did not finish within {why}", time_limit)
    y = np.concatenate([np.asarray(q0, dtype=float), np.zeros(n)])
    sols, nfev = [], 0
    for a, b, seg in _intervals(list(breaks), T, duration):
        def rhs(t, yy, seg=seg):
            q, qd = yy[:n], yy[n:]
            xd, vd, ad = desired(t, seg)
            m, c, g, f = dyn.terms(q, qd, t)
            tau = task_torque(law, kp, kd, arm, q, qd, xd, vd, ad, m, c, g)
            return np.concatenate([qd, np.linalg.solve(m, tau + f - c - g)])
        sol = solve_ivp(budget.guard(rhs), (a, b), y, method="DOP853", rtol=RTOL, atol=ATOL, dense_output=True)
        if not sol.success:
            raise RuntimeError(f"the closed-loop simulation failed at t = {sol.t[-1]:.6g}: {sol.message}")
        nfev += sol.nfev
        sols.append((a, b, seg, sol))
        y = sol.y[:, -1]
    return _result(dyn, arm, desired, law, kp, kd, sols, duration, samples, nfev)


def _state(sols, t):
    for a, b, seg, sol in sols:
        if t <= b:
            return sol.sol(t), seg
    return sols[-1][3].sol(t), sols[-1][2]


def _error_at(arm, desired, sols, t):
    y, seg = _state(sols, t)
    n = y.size // 2
    return desired(t, seg)[0] - arm.x(y[:n])


def _result(dyn, arm, desired, law, kp, kd, sols, duration, samples, nfev):
    grid = np.union1d(np.linspace(0.0, duration, samples), [s[0] for s in sols] + [duration])
    n = dyn.n
    cols = {k: [] for k in ("q", "x", "xd", "e", "tau")}
    for t in grid:
        y, seg = _state(sols, t)
        q, qd = y[:n], y[n:]
        xd, vd, ad = desired(t, seg)
        m, c, g, _f = dyn.terms(q, qd, t)
        x = arm.x(q)
        for k, v in zip(cols, (q, x, xd, xd - x, task_torque(law, kp, kd, arm, q, qd, xd, vd, ad, m, c, g))):
            cols[k].append(v)
    e, xs = np.array(cols["e"]).T, np.array(cols["x"]).T
    mx, tm = np.zeros(e.shape[0]), np.zeros(e.shape[0])
    steps = sum(len(sol.t) - 1 for *_, sol in sols)
    for i in range(e.shape[0]):
        cands = polished_crests(lambda s: _error_at(arm, desired, sols, s)[i], grid, e[i],
                                xatol=1e-12 * max(1.0, duration))
        # crests within the run's error of the largest tie: the first is reported (core/extremes.py);
        # the state is q, so e = x_d - x(q) is known to the integrator's tolerance on x, not on e
        scale = max(max(c[0] for c in cands), float(np.max(np.abs(xs[i]))))
        tol = tie_tolerance(scale, RTOL, ATOL, steps)
        mx[i], tm[i] = first_of_ties(cands, tol)
    return TaskControlResult(law, duration, grid, np.array(cols["q"]).T, xs,
                             np.array(cols["xd"]).T, e, np.array(cols["tau"]).T, mx, tm, e[:, -1].copy(), nfev)


__all__ = ["TASK_LAWS", "TaskControlResult", "simulate_task", "task_torque", "SimulationTooLong"]
