"""Forward dynamics: the motion of the arm under given actuator laws (the course's §6.5 runs).

The plant is the problem's own equations of motion

    M(q) q'' + c(q, q') + g(q) = tau(t, q, q') + f_ext(t, q, q')

integrated from a start state over [0, duration].  Pure math: the caller gives sympy
expressions with the parameters already replaced by numbers (``compile_plant``), this
module compiles them into one scalar function and integrates it (``integrate``).

Accuracy: DOP853 (explicit, 8th order) at rtol 1e-10, atol 1e-12 on the state: the
tests ask for 1e-8 relative to the run's scale against an independent integration.
Extremes are found on the dense output (roots of q'_i), not at samples; values within the
run's error of an extreme tie, and the first instant of the tie is reported (core/extremes.py).  The work of
the non-conservative forces (tau + f_ext) . q' is integrated as an extra state, so the
energy balance E_end - E_start = W can be shown even when W has no closed form.

Budget (spec §2: deterministic): every run may evaluate its right-hand side at most
``MAX_EVALUATIONS`` times.  A run that needs more is retried with Radau (implicit)
when the linearised motion is stiff; past the budget again it stops with
``RunTooLong`` explaining the time scales.  The wall clock is only a safety net.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np
import sympy as sp

from robosolve.core.extremes import first_of_ties, tie_tolerance

__all__ = ["Plant", "Run", "RunTooLong", "RunUndefined", "compile_plant", "integrate", "MAX_EVALUATIONS",
           "RTOL", "ATOL"]

RTOL = 1e-10
ATOL = 1e-12
# ~10 s of Python on the 2-core machine (DOP853: 12 evaluations per step, ~60k steps).
MAX_EVALUATIONS = 800_000
# Safety net only (never decides an answer on a normal run): a run stopped by it says so.
WALL_SECONDS = 300.0
# A step in which q' changes sign twice would hide an extremum: each step is also probed here.
PROBES_PER_STEP = 3


class RunTooLong(RuntimeError):
    """The integration needed more than its budget of right-hand-side evaluations."""


class RunUndefined(RunTooLong):
    """The equations have no value along the run (a law's square root or logarithm of a negative
    number): the run stops there, and says where."""


def undefined_message(t: float, exc: Exception) -> str:
    """Why a run stopped where its equations have no value (the math module's error `exc` at t)."""
    if isinstance(exc, OverflowError):
        return (f"the equations of motion overflow at t = {t:.6g} s (a value beyond the range of "
                "floating-point numbers, about 1.8e308: a start state, a gain or a law far too large?)")
    return (f"the equations of motion have no value at t = {t:.6g} s ({exc}: a square root or logarithm "
            "of a negative number in an actuator law or a force?)")


@dataclass
class Plant:
    """A compiled plant: ``rhs(t, y)`` with y = (q, q', W), W the work of tau + f_ext."""

    n: int
    accel: Callable            # (t, *q, *qd) -> [q''..., power]
    energy: Callable | None    # numpy (Q, QD) -> (T, U) arrays, or None
    accel_many: Callable | None = None

    def rhs(self, t, y):
        n = self.n
        out = self.accel(t, *y[:2 * n].tolist())
        return np.array(y[n:2 * n].tolist() + list(out), dtype=float)


@dataclass
class Run:
    """The result of one forward-dynamics run (floats; arrays have one row per joint)."""

    duration: float
    t: np.ndarray              # sample instants for figures (uniform)
    q: np.ndarray              # (n, N)
    qd: np.ndarray             # (n, N)
    final: np.ndarray
    final_velocity: np.ndarray
    q_max: np.ndarray
    t_max: np.ndarray
    q_min: np.ndarray
    t_min: np.ndarray
    work: float                # W = integral of (tau + f_ext) . q' dt
    energy_start: float | None = None
    energy_end: float | None = None
    energy_scale: float | None = None      # max over the run's samples of T + |U|
    energy_drift: float | None = None      # max |E(t) - E(0) - W(t)| at the solver's steps
    evaluations: int = 0
    steps: int = 0
    method: str = "DOP853"
    # per joint: the whole run stays within the run's error of the start (position and rate 0)
    still: np.ndarray | None = None
    notes: list = field(default_factory=list)


def _numeric_only(exprs, args, what):
    extra = set()
    for e in exprs:
        extra |= sp.sympify(e).free_symbols
    extra -= set(args)
    if extra:
        raise ValueError(f"{what} needs a value for " + ", ".join(sorted(str(s) for s in extra)))


def compile_plant(mass, velocity_terms, gravity_terms, forces, q: Sequence[sp.Symbol],
                  qd: Sequence[sp.Symbol], t: sp.Symbol, kinetic=None, potential=None,
                  symbolic_solve_up_to: int = 3) -> Plant:
    """Compile M, c, g and the generalized forces tau + f_ext (functions of t, q, q').

    Every expression must be numeric apart from t, q and q' (ValueError otherwise).
    ``kinetic`` / ``potential``: total T(q, q') and U(q), for the energy balance.
    Up to ``symbolic_solve_up_to`` joints M is solved symbolically (LU) so that each right-hand
    side is one scalar function of floats; beyond, M and the forces are evaluated and solved by
    numpy (the symbolic LU of a big M would be far longer than the numeric solve).
    """
    n = len(q)
    m = sp.Matrix(mass)
    rest = sp.Matrix(forces) - sp.Matrix(velocity_terms) - sp.Matrix(gravity_terms)
    args = [t] + list(q) + list(qd)
    _numeric_only(list(m) + list(rest), args, "the equations of motion")
    power = sum((sp.sympify(forces[i]) * qd[i] for i in range(n)), sp.S.Zero)
    if n <= symbolic_solve_up_to:
        qdd = list(m.LUsolve(rest))
        accel = sp.lambdify(args, qdd + [power], modules="math", cse=True)
    else:
        flat = sp.lambdify(args, list(m) + list(rest) + [power], modules="math", cse=True)

        def accel(*a):
            out = flat(*a)
            mm = np.array(out[:n * n], dtype=float).reshape(n, n)
            return list(np.linalg.solve(mm, np.array(out[n * n:n * n + n], dtype=float))) + [out[-1]]
    energy = None
    if kinetic is not None and potential is not None:
        _numeric_only([kinetic, potential], args[1:], "the energy")
        vec = sp.lambdify(list(q) + list(qd), [kinetic, potential], modules="numpy", cse=True)

        def energy(Q, QD):
            size = np.shape(Q)[1]
            tt, uu = vec(*Q, *QD)
            return (np.broadcast_to(np.asarray(tt, dtype=float), (size,)),
                    np.broadcast_to(np.asarray(uu, dtype=float), (size,)))
    return Plant(n, accel, energy)


class _Counter:
    """Counts right-hand-side evaluations and stops the run past its budget."""

    def __init__(self, plant, budget, deadline):
        self.plant, self.budget, self.deadline = plant, budget, deadline
        self.count = 0
        self.last = (0.0, None)

    def __call__(self, t, y):
        self.count += 1
        if self.count > self.budget:
            self.last = (t, np.array(y))
            raise _OverBudget()
        if self.count % 2000 == 0 and time.monotonic() > self.deadline:
            self.last = (t, np.array(y))
            raise _OverClock()
        try:
            return self.plant.rhs(t, y)
        except (ValueError, OverflowError) as exc:      # the math module's: a law off its domain
            if isinstance(exc, np.linalg.LinAlgError):
                raise                    # a singular M(q) (also a ZeroDivisionError): the caller says so
            raise RunUndefined(undefined_message(t, exc)) from None


class _OverBudget(Exception):
    pass


class _OverClock(Exception):
    pass


def linear_rates(plant: Plant, t: float, y: np.ndarray) -> np.ndarray:
    """Eigenvalues of the linearised motion d(q, q')/dt at (t, y) (finite differences)."""
    n = plant.n
    y = np.asarray(y, dtype=float)[:2 * n]
    base = np.concatenate([y, [0.0]])
    f0 = plant.rhs(t, base)[:2 * n]
    jac = np.empty((2 * n, 2 * n))
    for k in range(2 * n):
        h = 1e-7 * max(1.0, abs(y[k]))
        yy = base.copy()
        yy[k] += h
        jac[:, k] = (plant.rhs(t, yy)[:2 * n] - f0) / h
    return np.linalg.eigvals(jac)


def _explain(plant, t_stop, y_stop, duration, budget, method) -> tuple[str, bool]:
    """Why a run ran out of budget; and whether the motion is stiff there."""
    msg = (f"the run needs more than {budget} evaluations of the equations of motion "
           f"({method} stopped at t = {t_stop:.6g} s of {duration:g} s)")
    stiff = False
    try:
        lam = linear_rates(plant, t_stop, y_stop)
        fast = float(np.max(np.abs(lam)))
        if fast > 0 and math.isfinite(fast):
            k = int(np.argmax(np.abs(lam)))
            decay, freq = abs(float(lam[k].real)), abs(float(lam[k].imag))
            scale = 1.0 / fast
            slow = float(np.min(np.abs(lam[np.abs(lam) > 0]))) if np.any(np.abs(lam) > 0) else fast
            stiff = decay > 0.5 * fast and fast * duration > 1e3 and fast / max(slow, 1e-300) > 1e3
            if stiff:
                msg += (f": the equations are stiff there (the fastest time scale of the linearised "
                        f"motion is {scale:.3g} s against a run of {duration:g} s, the slowest "
                        f"{1 / max(slow, 1e-300):.3g} s); soften the law's gains or shorten the run")
            else:
                cycles = freq * duration / (2 * math.pi)
                msg += (f": the motion is fast there (time scale {scale:.3g} s"
                        + (f", about {cycles:.3g} oscillations over the run" if freq > 0 else "")
                        + "), each of which must be resolved; shorten the run or soften the law")
    except Exception:          # the explanation is a courtesy: never hide the real error
        pass
    return msg, stiff


def integrate(plant: Plant, q0, qd0, duration: float, *, rtol: float = RTOL, atol: float = ATOL,
              max_evaluations: int = MAX_EVALUATIONS, samples: int = 1001,
              wall_seconds: float = WALL_SECONDS, method: str = "DOP853") -> Run:
    """Integrate the plant from (q0, qd0) at t = 0 over [0, duration]."""
    from robosolve.simulation.dop853 import solve_ivp

    n = plant.n
    duration = float(duration)
    if not duration > 0:
        raise ValueError("the run needs a positive duration")
    y0 = np.concatenate([np.asarray(q0, dtype=float).reshape(n), np.asarray(qd0, dtype=float).reshape(n),
                         [0.0]])
    deadline = time.monotonic() + wall_seconds
    # A first attempt with a tenth of the budget: a stiff run is then handed to Radau early
    # instead of after the whole budget; a merely long run restarts with the full budget.
    attempts = [(method, max(1, max_evaluations // 10))]
    notes: list = []
    total = 0
    while True:
        name, budget = attempts[-1]
        counter = _Counter(plant, budget, deadline)
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore", RuntimeWarning)
                sol = solve_ivp(counter, (0.0, duration), y0, method=name, rtol=rtol, atol=atol,
                                dense_output=True)
        except _OverBudget:
            total += counter.count
            msg, stiff = _explain(plant, counter.last[0], counter.last[1], duration, max_evaluations, name)
            if stiff and name != "Radau":
                notes.append("the equations are stiff: integrated with Radau (implicit) instead of DOP853")
                attempts.append(("Radau", max_evaluations))
                continue
            if budget < max_evaluations:
                attempts.append((name, max_evaluations))
                continue
            raise RunTooLong(msg) from None
        except _OverClock:
            raise RunTooLong(f"the run did not finish in {wall_seconds:g} s of computing time "
                             f"(a safety limit; stopped at t = {counter.last[0]:.6g} s)") from None
        total += counter.count
        break
    if not sol.success:
        raise RunTooLong(f"the integration failed at t = {sol.t[-1]:.6g} s: {sol.message}")
    return _collect(plant, sol, duration, samples, total, attempts[-1][0], notes, (rtol, atol))


def _collect(plant, sol, duration, samples, evaluations, method, notes, tolerances) -> Run:
    n = plant.n
    ts = np.linspace(0.0, duration, samples)
    ys = sol.sol(ts)
    ys[:, 0], ys[:, -1] = sol.y[:, 0], sol.y[:, -1]
    q_max, t_max, q_min, t_min, still = _extremes(sol, n, duration, tolerances)
    final = sol.y[:n, -1].copy()
    run = Run(duration, ts, ys[:n], ys[n:2 * n], final, sol.y[n:2 * n, -1].copy(), q_max, t_max,
              q_min, t_min, float(sol.y[-1, -1]), evaluations=evaluations, steps=len(sol.t) - 1,
              method=method, notes=list(notes), still=still)
    if plant.energy is not None:
        kin, pot = plant.energy(sol.y[:n], sol.y[n:2 * n])
        e = kin + pot
        run.energy_start, run.energy_end = float(e[0]), float(e[-1])
        # the scale from the fixed samples (dense output), not the solver's steps: where the
        # steps fall depends on the integrator's version, the samples' values do not
        skin, spot = plant.energy(ys[:n], ys[n:2 * n])
        run.energy_scale = float(np.max(skin + np.abs(spot)))
        run.energy_drift = float(np.max(np.abs(e - e[0] - sol.y[-1])))
    return run


def _extremes(sol, n, duration, tolerances):
    """max/min of each q_i over [0, duration]: the ends and every root of q'_i (dense output);
    ``tolerances``: the run's (rtol, atol), which decide the ties; and whether each joint stays
    at its start: every extreme within the run's error of the start, the rate within its error
    of 0 all along (a joint only so slow that a short run hides its motion is not still)."""
    from scipy.optimize import brentq

    steps = sol.t
    # probe each step at interior points too, so that two sign changes in one step are seen
    frac = np.arange(1, PROBES_PER_STEP + 1) / (PROBES_PER_STEP + 1)
    inner = (steps[:-1, None] + np.diff(steps)[:, None] * frac[None, :]).ravel()
    grid = np.union1d(steps, inner)
    vals = sol.sol(grid)
    q_max, t_max, q_min, t_min = (np.empty(n) for _ in range(4))
    still = np.zeros(n, dtype=bool)
    for i in range(n):
        cands = [(float(sol.y[i, 0]), 0.0), (float(sol.y[i, -1]), float(duration))]
        v = vals[n + i]
        idx = np.nonzero(np.sign(v[:-1]) * np.sign(v[1:]) < 0)[0]
        for k in idx:
            a, b = float(grid[k]), float(grid[k + 1])
            r = brentq(lambda s: float(sol.sol(s)[n + i]), a, b, xtol=1e-14, rtol=4 * np.finfo(float).eps)
            cands.append((float(sol.sol(r)[i]), r))
        for k in np.nonzero(v == 0)[0]:
            cands.append((float(vals[i, k]), float(grid[k])))
        # values within the run's error of the extreme tie, and the first of them is reported
        # (core/extremes.py): an arm at rest at an equilibrium stays at its start, t = 0
        tol = tie_tolerance(float(np.max(np.abs(vals[i]))), *tolerances, len(steps) - 1)
        q_max[i], t_max[i] = first_of_ties(cands, tol, largest=True)
        q_min[i], t_min[i] = first_of_ties(cands, tol, largest=False)
        start, rates = cands[0][0], np.abs(v)
        rate_tol = tie_tolerance(float(np.max(rates)), *tolerances, len(steps) - 1)
        still[i] = max(abs(c[0] - start) for c in cands) <= tol and float(np.max(rates)) <= rate_tol
    return q_max, t_max, q_min, t_min, still
