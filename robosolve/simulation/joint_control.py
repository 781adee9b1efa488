"""Closed-loop joint control along a desired profile (the course's §7.5.2, generalized).

Plant: M(q) qdd + c(q, qd) + g(q) = tau + f_ext(q).  Error e = q_d - q.  Laws
(spec, "Control"):

* ``p``:               tau = Kp e                      (the course's controller, no gravity compensation)
* ``pd``:              tau = Kp e + Kd edot
* ``pd_gravity``:      tau = Kp e + Kd edot + g(q)
* ``computed_torque``: tau = M(q) (qdd_d + Kd edot + Kp e) + c(q, qd) + g(q)

The ODE is integrated in ERROR coordinates (state e, edot): the solver's relative
tolerance then applies to the error itself, which is what is reported, even when it
is a thousandth of the motion.  The desired acceleration jumps at the profile's
switching instants (0, T/2, T for bang-bang), so the integration restarts at each of
them instead of letting the step size collapse.  The method is LSODA (switches
automatically to a stiff BDF method when high derivative gains make the loop stiff).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from robosolve.core.extremes import first_of_ties, tie_tolerance
from robosolve.dynamics.numeric import NumericDynamics
from robosolve.motion.profiles import NumericPlan
from robosolve.simulation.forward import undefined_message

__all__ = ["LAWS", "ControlResult", "simulate", "SimulationTooLong", "TIME_LIMIT", "MAX_EVALUATIONS",
           "max_abs_refined", "polished_crests"]

# Work budget of one simulation, counted (not timed) so that the outcome is the same on an idle
# or a busy machine: at most this many evaluations of the equations of motion.  An undamped P
# loop on a very light link (a PUMA wrist: inertia 1e-4 kg m^2, Kp = 5000 -> 1 kHz), gains of
# 1e12 or `duration: 1e6` must resolve every oscillation and would run for many minutes and keep
# gigabytes of solver steps (the dense output holds one interpolant per step): they are stopped
# with an explanation instead.  Measured on the 2R test arm: Kp = 5000 needs 16k evaluations,
# Kp = 5e5 180k; the budget also bounds the memory (about 1 kB per solver step).
MAX_EVALUATIONS = 400_000
# Wall-clock limit (s): only a last safety net for a machine far slower than any seen; the
# message says so (the counted budget above decides in every normal case).
TIME_LIMIT = 600.0


class SimulationTooLong(RuntimeError):
    """The closed-loop simulation exceeded its time budget."""

LAWS = ("p", "pd", "pd_gravity", "computed_torque")

# Measured on the 2R arm with Kp = 5000 (tests/test_motion_control.py): rtol 1e-8 gives
# max errors within ~1e-6 relative of a 1e-13 reference, a 100x margin over the 1e-4 goal.
RTOL = 1e-8
ATOL_ERROR = 1e-12        # on e (rad or m)
ATOL_RATE = 1e-10         # on edot


@dataclass
class ControlResult:
    law: str
    duration: float
    t: np.ndarray                  # sample instants (uniform grid plus the switching instants)
    q: np.ndarray                  # (n, N) actual joint values
    q_desired: np.ndarray          # (n, N)
    error: np.ndarray              # (n, N) e = q_d - q
    effort: np.ndarray             # (n, N) actuator forces of the law
    max_error: np.ndarray          # (n,) max |e| over [0, duration]
    t_max_error: np.ndarray        # (n,) where it occurs
    final_error: np.ndarray        # (n,) signed e(duration)
    breaks: list[float] = field(default_factory=list)
    nfev: int = 0
    method: str = "LSODA"
    external: np.ndarray | None = None   # (n, N) generalized external forces f_ext(q), for the plots
    dense: object = None           # t -> (q_desired, e) anywhere in [0, duration] (dense output)


def _intervals(plan: NumericPlan, duration: float):
    """(t_a, t_b, coeffs about t_a) covering [0, duration]."""
    # A break a rounding away from the duration (0.19999999999999998 against 0.2: a path's
    # samples k·Δt) is the duration: an interval of 1e-17 s is no interval (LSODA refuses it as
    # illegal input and the run fell back to Radau with a warning on the console).
    tol = 1e-12 * max(1.0, duration)
    out = []
    for k, c in enumerate(plan.coeffs):
        a, b = float(plan.breaks[k]), float(plan.breaks[k + 1])
        if a >= duration - tol:
            break
        if b > a:
            out.append((a, duration if b >= duration - tol else b, c))
    end = out[-1][1] if out else 0.0
    if duration > end:
        hold = np.zeros_like(plan.coeffs[0])
        hold[:, 0] = plan.hold
        if out and duration - end <= tol:
            out[-1] = (out[-1][0], duration, out[-1][2])
        else:
            out.append((end, duration, hold))
    return out


def _powers(tau: float, deg: int):
    p = np.empty(deg)
    dp = np.zeros(deg)
    ddp = np.zeros(deg)
    x = 1.0
    for k in range(deg):
        p[k] = x
        x *= tau
    for k in range(1, deg):
        dp[k] = k * p[k - 1]
    for k in range(2, deg):
        ddp[k] = k * (k - 1) * p[k - 2]
    return p, dp, ddp


def _law_torque(law, kp, kd, e, ed, qdd_d, m, c, g):
    if law == "p":
        return kp * e
    if law == "pd":
        return kp * e + kd * ed
    if law == "pd_gravity":
        return kp * e + kd * ed + g
    return m @ (qdd_d + kd * ed + kp * e) + c + g


def simulate(dyn: NumericDynamics, plan: NumericPlan, law: str, kp, kd=None, start=None,
             duration: float | None = None, samples: int = 801,
             rtol: float = RTOL, atol=None, method: str = "LSODA",
             time_limit: float | None = TIME_LIMIT, max_evaluations: int | None = None) -> ControlResult:
    """Simulate the closed loop from ``start`` at rest (default: the profile's start).

    ``kp``, ``kd``: per-joint gains (sequences of n floats; kd defaults to 0).
    ``duration`` defaults to the profile's T.  Returns samples for plots and the
    max / final errors, refined on the solver's dense output.
    """
    if law not in LAWS:
        raise ValueError(f"unknown control law {law!r} (expected one of {', '.join(LAWS)})")
    n = dyn.n
    kp = np.asarray(kp, dtype=float).reshape(n)
    kd = np.zeros(n) if kd is None else np.asarray(kd, dtype=float).reshape(n)
    duration = plan.T if duration is None else float(duration)
    if not duration > 0:
        raise ValueError("the simulation needs a positive duration (the profile does not move?)")
    q_start = plan.start if start is None else np.asarray(start, dtype=float).reshape(n)
    intervals = _intervals(plan, duration)

    qd0, qdd0_, _ = plan.evaluate([0.0], k=0)
    y = np.concatenate([qd0[:, 0] - q_start, qdd0_[:, 0] - 0.0])   # e(0), edot(0) (start at rest)

    if atol is None:
        atol = np.concatenate([np.full(n, ATOL_ERROR), np.full(n, ATOL_RATE)])
    import time

    deadline = None if not time_limit else time.monotonic() + time_limit
    budget = _Budget(MAX_EVALUATIONS if max_evaluations is None else max_evaluations, deadline,
                     lambda why: _too_long(dyn, law, kp, kd, q_start, duration, why), time_limit)
    sols, nfev = _integrate(dyn, plan.DEG, law, kp, kd, intervals, y, budget, method, rtol, atol)
    grid, q_des, err, effort, external = _samples(dyn, plan.DEG, law, kp, kd, sols, intervals,
                                                  duration, samples)
    max_err, t_max = _max_errors(sols, n, duration, rtol, np.broadcast_to(atol, (2 * n,)))
    final = sols[-1][3].y[:n, -1].copy()
    q = q_des - err
    return ControlResult(law, duration, grid, q, q_des, err, effort, max_err, t_max, final,
                         breaks=[iv[0] for iv in intervals[1:]], nfev=nfev, method=method,
                         external=external, dense=_dense(sols, n, plan.DEG))


def _dense(sols, n: int, deg: int):
    """t -> (q_desired, e) on the solver's dense output (the piece that holds t)."""
    def at(t: float):
        for a, b, coeffs, sol in sols:
            if t <= b:
                break
        p, _dp, _ddp = _powers(t - a, deg)
        return coeffs @ p, sol.sol(t)[:n]
    return at


def max_abs_refined(f, ts: np.ndarray, values: np.ndarray, xatol: float) -> tuple[float, float]:
    """(max |f|, where) over [ts[0], ts[-1]] from the samples values = f(ts): the largest local
    maxima of the samples (the ends included) are polished on f, so an oscillation's crest
    between two samples is found, not the sample beside it (ties: the earliest instant)."""
    cands = polished_crests(f, ts, values, xatol)
    best = max(c[0] for c in cands)
    return best, first_of_ties(cands, tie_tolerance(best))[1]


def polished_crests(f, ts: np.ndarray, values, xatol: float) -> list[tuple[float, float]]:
    """[(|f|, t)] at the largest local maxima of |values| (samples of f at ts, the ends included),
    each polished on |f| between its neighbouring samples (a crest between two samples)."""
    from robosolve.core.minimize import minimize_bounded

    vals = np.abs(np.asarray(values, dtype=float))
    cands = []
    for j in _top_local_maxima(vals):
        lo, hi = ts[max(j - 1, 0)], ts[min(j + 1, ts.size - 1)]
        tc, vc = float(ts[j]), float(vals[j])
        if hi > lo:
            res = minimize_bounded(lambda s: -abs(f(s)), (float(lo), float(hi)), xatol=xatol)
            if -res.fun > vc:
                if j in (0, ts.size - 1):     # an end stays a candidate: a flat start (a loop
                    cands.append((vc, tc))    # starting on its reference at rest) ties with the hair
                tc, vc = float(res.x), float(-res.fun)   # above it the polish finds just inside
        cands.append((vc, tc))
    return cands


def _error_rhs(dyn: NumericDynamics, fast, law, kp, kd, a, coeffs, deg):
    """d/dt (e, edot) on the interval that starts at ``a`` (the dynamics' compiled closed loop
    when it has one)."""
    n = dyn.n
    if fast is not None:
        return _fast_rhs(fast, a, coeffs.tolist(), n, timed=dyn.timed)

    def rhs(t, yy):
        p, dp, ddp = _powers(t - a, deg)
        qdes, vdes, ades = coeffs @ p, coeffs @ dp, coeffs @ ddp
        e, ed = yy[:n], yy[n:]
        q, qd = qdes - e, vdes - ed
        m, c, g, f = dyn.terms(q, qd, t)
        tau = _law_torque(law, kp, kd, e, ed, ades, m, c, g)
        qdd = np.linalg.solve(m, tau + f - c - g)
        return np.concatenate([ed, ades - qdd])

    return rhs


def _integrate(dyn: NumericDynamics, deg, law, kp, kd, intervals, y, budget, method, rtol, atol):
    """The error ODE from state ``y``, restarted at every switching instant:
    ([(t_a, t_b, coeffs, solution)], evaluations)."""
    from robosolve.simulation.dop853 import solve_ivp

    fast = dyn.closed_loop(law, kp, kd)
    sols = []
    nfev = 0
    for a, b, coeffs in intervals:
        rhs = budget.guard(_error_rhs(dyn, fast, law, kp, kd, a, coeffs, deg))
        sol = solve_ivp(rhs, (a, b), y, method=method, rtol=rtol, atol=atol, dense_output=True)
        if not sol.success:
            sol = solve_ivp(rhs, (a, b), y, method="Radau", rtol=rtol, atol=atol, dense_output=True)
            if not sol.success:
                raise RuntimeError(f"the closed-loop simulation failed at t = {sol.t[-1]:.6g}: {sol.message}")
        nfev += sol.nfev
        sols.append((a, b, coeffs, sol))
        y = sol.y[:, -1]
    return sols, nfev


def _samples(dyn: NumericDynamics, deg, law, kp, kd, sols, intervals, duration, samples):
    """The figures' samples, on a uniform grid plus every switching instant:
    (grid, q_desired, error, effort, external), each (n, N) but the grid."""
    n = dyn.n
    grid = np.union1d(np.linspace(0.0, duration, samples), [iv[0] for iv in intervals] + [duration])
    q_des = np.empty((n, grid.size))
    err = np.empty((n, grid.size))
    effort = np.empty((n, grid.size))
    external = np.empty((n, grid.size))
    lo = 0
    for idx, (a, b, coeffs, sol) in enumerate(sols):
        hi = grid.size if idx == len(sols) - 1 else int(np.searchsorted(grid, b, side="right"))
        ts = grid[lo:hi]
        if ts.size:
            yy = sol.sol(ts)
            tau = ts - a
            pw = np.vstack([tau ** k for k in range(deg)])
            dpw = np.vstack([np.zeros_like(tau)] + [k * tau ** (k - 1) for k in range(1, deg)])
            ddpw = np.vstack([np.zeros_like(tau)] * 2 + [k * (k - 1) * tau ** (k - 2) for k in range(2, deg)])
            qdes, vdes, ades = coeffs @ pw, coeffs @ dpw, coeffs @ ddpw
            e, ed = yy[:n], yy[n:]
            q_des[:, lo:hi] = qdes
            err[:, lo:hi] = e
            effort[:, lo:hi] = _effort_many(dyn, law, kp, kd, qdes - e, vdes - ed, e, ed, ades, ts)
            external[:, lo:hi] = _external_many(dyn, qdes - e, vdes - ed, ts)
        lo = hi
    return grid, q_des, err, effort, external


def _max_errors(sols, n, duration, rtol, atol):
    """(max |e|, instant) per joint, arrays of n; the run's tolerances ``rtol``, ``atol`` (on
    the state e, edot) decide the ties."""
    max_err = np.zeros(n)
    t_max = np.zeros(n)
    for i in range(n):
        max_err[i], t_max[i] = _max_abs_error(sols, i, duration, (rtol, float(atol[i])))
    return max_err, t_max


def _max_abs_error(sols, i, duration, tolerances):
    """max |e_i| and where: the solver's own steps sample every oscillation finely; the best
    few local maxima are then polished on the dense output."""
    cands = []
    for a, b, _c, sol in sols:
        cands += polished_crests(lambda s, sol=sol: sol.sol(s)[i], sol.t, sol.y[i],
                                 xatol=1e-12 * max(1.0, duration))
    # crests within the run's error of the largest tie, and the first of them is reported
    # (core/extremes.py): an undamped loop's equal crests give the first one, not the one the
    # integrator's error lifted
    scale = max(c[0] for c in cands)
    steps = sum(len(sol.t) - 1 for *_, sol in sols)
    return first_of_ties(cands, tie_tolerance(scale, *tolerances, steps))


class _Budget:
    """Counts the evaluations of the right-hand side over the whole simulation; raises
    SimulationTooLong past the counted budget (deterministic) or the wall-clock safety net."""

    def __init__(self, evaluations: int, deadline, message, seconds=None):
        self.left, self.deadline, self.message = evaluations, deadline, message
        self.total, self.seconds = evaluations, seconds

    def guard(self, rhs):
        import time

        def guarded(t, yy):
            self.left -= 1
            if self.left < 0:
                raise SimulationTooLong(self.message(
                    f"its budget of {self.total:,} evaluations of the equations of motion"))
            if self.deadline is not None and self.left % 500 == 0 and time.monotonic() > self.deadline:
                raise SimulationTooLong(self.message(
                    f"{self.seconds:g} s (a wall-clock safety limit, reached only on a very slow machine)"))
            try:
                return rhs(t, yy)
            except (ValueError, OverflowError) as exc:   # the math module's: a force off its domain
                if isinstance(exc, np.linalg.LinAlgError):
                    raise                # a singular M(q) (also a ZeroDivisionError): the caller says so
                raise SimulationTooLong(undefined_message(t, exc)) from None

        return guarded


def _too_long(dyn, law, kp, kd, q0, duration, limit: str) -> str:
    """Explain a simulation that ran out of budget: the fastest closed-loop oscillation, or
    the instability a negative gain causes."""
    msg = f"the closed-loop simulation did not finish within {limit}"
    if law != "computed_torque" and (np.any(np.asarray(kp) < 0) or np.any(np.asarray(kd) < 0)):
        return msg + (": a negative gain makes the loop unstable (the error grows exponentially "
                      "instead of being corrected); use positive gains")
    try:
        m, _c, _g, _f = dyn.terms(np.asarray(q0, dtype=float), np.zeros(dyn.n), 0.0)
        stiff = np.diag(kp) if law != "computed_torque" else m @ np.diag(kp)
        w = np.sqrt(np.max(np.abs(np.linalg.eigvals(np.linalg.solve(m, stiff)))))
        cycles = w * duration / (2 * np.pi)
        msg += (f": with these gains the arm oscillates at up to {w / (2 * np.pi):.3g} Hz "
                f"(about {cycles:.3g} oscillations over {duration:g} s, each of which must be resolved)")
        if law == "p":
            msg += "; lower the gains of the light joints, or add damping (law: pd)"
    except Exception:
        pass
    return msg


def _fast_rhs(fast, a: float, coeffs: list, n: int, timed: bool = False):
    """Right-hand side in pure Python floats: Horner for the desired polynomials."""
    rows = [list(reversed(r)) for r in coeffs]      # highest power first
    drows = [[(len(r) - 1 - k) * v for k, v in enumerate(rev[:-1])] for r, rev in zip(coeffs, rows)]
    ddrows = [[(len(dr) - 1 - k) * v for k, v in enumerate(dr[:-1])] for dr in drows]
    asarray = np.asarray

    def horner(cs, x):
        acc = 0.0
        for v in cs:
            acc = acc * x + v
        return acc

    def rhs(t, yy):
        x = t - a
        yl = yy.tolist()
        e, ed = yl[:n], yl[n:]
        q = [horner(rows[i], x) - e[i] for i in range(n)]
        qd = [horner(drows[i], x) - ed[i] for i in range(n)]
        ad = [horner(ddrows[i], x) for i in range(n)]
        qdd = fast(*q, *qd, *e, *ed, *ad, t) if timed else fast(*q, *qd, *e, *ed, *ad)
        return asarray(ed + [ad[i] - qdd[i] for i in range(n)])

    return rhs


def _top_local_maxima(vals: np.ndarray, keep: int = 12) -> list[int]:
    """Indices, in time order, of the largest local maxima of vals (ends included), at most
    ``keep``: the highest ones and the earliest ones within 1 % of the top (the first of crests
    that tie, core/extremes.py, is among them however many crests there are)."""
    m = len(vals)
    if m <= 2:
        return [int(np.argmax(vals))]
    inner = np.nonzero((vals[1:-1] >= vals[:-2]) & (vals[1:-1] >= vals[2:]))[0] + 1
    idx = np.concatenate([[0], inner, [m - 1]])
    top = vals[idx]
    best = top.max()
    near = idx[top >= best * (1 - 1e-2)]
    order = np.argsort(-vals[near], kind="stable")[:keep - keep // 4]
    return sorted({int(near[k]) for k in order} | {int(k) for k in near[:keep // 4]})


def _external_many(dyn, q, qd, ts=None):
    """Generalized external forces f_ext(q) at many samples (arrays (n, N)); ``ts`` the times
    (a force may vary with time)."""
    many = getattr(dyn, "_terms_many", None)
    if many is not None:
        return np.broadcast_to(dyn.terms_many(q, qd, ts)[3], q.shape)
    return np.column_stack([dyn.terms(q[:, k], qd[:, k], None if ts is None else ts[k])[3]
                            for k in range(q.shape[1])]) if q.shape[1] else np.empty_like(q)


def _effort_many(dyn, law, kp, kd, q, qd, e, ed, ades, ts=None):
    """Actuator forces of the law at many samples (arrays (n, N))."""
    kp_, kd_ = kp[:, None], kd[:, None]
    if law == "p":
        return kp_ * e
    if law == "pd":
        return kp_ * e + kd_ * ed
    out = np.empty_like(q)
    many = getattr(dyn, "_terms_many", None)
    if many is not None:
        m, c, g, _f = dyn.terms_many(q, qd, ts)
        if law == "pd_gravity":
            return kp_ * e + kd_ * ed + g
        return np.einsum("ijk,jk->ik", m, ades + kd_ * ed + kp_ * e) + c + g
    for k in range(q.shape[1]):
        m, c, g, _f = dyn.terms(q[:, k], qd[:, k], None if ts is None else ts[k])
        out[:, k] = _law_torque(law, kp, kd, e[:, k], ed[:, k], ades[:, k], m, c, g)
    return out
