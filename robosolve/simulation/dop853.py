"""DOP853 with dense output, step for step the integrator of scipy's
``solve_ivp(fun, t_span, y0, method="DOP853", rtol=..., atol=..., dense_output=True)``.

Why a copy: ``import scipy.integrate`` costs about half a second of CPU (it imports
scipy.optimize, scipy.special, scipy.sparse and scipy.linalg), more than a whole work-space
simulation of a 2R arm. This module is the same algorithm in the same floating-point
operations, in the same order, with the same coefficients (:mod:`dop853_tableau`): scipy 1.17's
``RungeKutta._step_impl``, ``DOP853._estimate_error_norm`` / ``_dense_output_impl``,
``select_initial_step``, ``Dop853DenseOutput`` and ``OdeSolution`` (BSD-3-Clause, Copyright (c)
2001-2002 Enthought, Inc. 2003, SciPy Developers). The steps, the solution and the dense output
are therefore bit for bit scipy's (`tests/engines/test_dop853.py` compares them on the
simulations' right-hand sides); every other method, or an option this copy does not take, goes
to scipy itself.
"""

from __future__ import annotations

import warnings
from itertools import groupby

import numpy as np

from robosolve.simulation import dop853_tableau as tab

__all__ = ["solve_ivp", "Result", "Solution"]

SAFETY = 0.9            # scipy/integrate/_ivp/rk.py
MIN_FACTOR = 0.2
MAX_FACTOR = 10
EPS = np.finfo(float).eps
N_STAGES = tab.N_STAGES
A = tab.A[:N_STAGES, :N_STAGES]
B = tab.B
C = tab.C[:N_STAGES]
A_EXTRA = tab.A[N_STAGES + 1:]
C_EXTRA = tab.C[N_STAGES + 1:]
ERROR_EXPONENT = -1 / (7 + 1)       # error estimator of order 7
TOO_SMALL_STEP = "Required step size is less than spacing between numbers."
FINISHED = "The solver successfully reached the end of the integration interval."


class Result:
    """What the callers read of scipy's OdeResult."""

    def __init__(self, t, y, sol, nfev, status, message):
        self.t, self.y, self.sol, self.nfev = t, y, sol, nfev
        self.njev = self.nlu = 0
        self.t_events = self.y_events = None
        self.status, self.message, self.success = status, message, status >= 0


def solve_ivp(fun, t_span, y0, method="DOP853", t_eval=None, dense_output=False, events=None,
              vectorized=False, args=None, **options):
    """scipy.integrate.solve_ivp; DOP853 without t_eval, events, args or step options here."""
    y_arr = np.asarray(y0)
    if (method != "DOP853" or t_eval is not None or events is not None or vectorized or args is not None
            or set(options) - {"rtol", "atol"} or np.issubdtype(y_arr.dtype, np.complexfloating)):
        from scipy.integrate import solve_ivp as scipy_solve_ivp

        return scipy_solve_ivp(fun, t_span, y0, method=method, t_eval=t_eval, dense_output=dense_output,
                               events=events, vectorized=vectorized, args=args, **options)
    t0, tf = map(float, t_span)
    return _Stepper(fun, t0, y_arr, tf, options.get("rtol", 1e-3), options.get("atol", 1e-6)).run(dense_output)


def _norm(x):
    return np.linalg.norm(x) / x.size ** 0.5


class _Stepper:
    """OdeSolver + RungeKutta + DOP853 of scipy, for float states."""

    def __init__(self, fun, t0, y0, t_bound, rtol, atol):
        self.t_old, self.t, self.t_bound = None, t0, t_bound
        y0 = y0.astype(float, copy=False)
        if y0.ndim != 1:
            raise ValueError("`y0` must be 1-dimensional.")
        if not np.isfinite(y0).all():
            raise ValueError("All components of the initial state `y0` must be finite.")
        self.y, self._user, self.nfev = y0, fun, 0
        self.direction = np.sign(t_bound - t0) if t_bound != t0 else 1
        self.n = self.y.size
        self.status = "running"
        self.y_old = None
        if np.any(rtol < 100 * EPS):
            warnings.warn("At least one element of `rtol` is too small. "
                          f"Setting `rtol = np.maximum(rtol, {100 * EPS})`.", stacklevel=3)
            rtol = np.maximum(rtol, 100 * EPS)
        atol = np.asarray(atol)
        if atol.ndim > 0 and atol.shape != (self.n,):
            raise ValueError("`atol` has wrong shape.")
        if np.any(atol < 0):
            raise ValueError("`atol` must be positive.")
        self.rtol, self.atol = rtol, atol
        self.f = self.fun(self.t, self.y)
        self.h_abs = self._initial_step()
        self.K_extended = np.empty((tab.N_STAGES_EXTENDED, self.n), dtype=self.y.dtype)
        self.K = self.K_extended[:N_STAGES + 1]
        self.h_previous = None

    def fun(self, t, y):
        self.nfev += 1
        return np.asarray(self._user(t, y), dtype=float)

    def _initial_step(self):
        """scipy's select_initial_step (max_step = inf, order 7)."""
        t0, y0, f0, rtol, atol = self.t, self.y, self.f, self.rtol, self.atol
        if y0.size == 0:
            return np.inf
        interval_length = abs(self.t_bound - t0)
        if interval_length == 0.0:
            return 0.0
        scale = atol + np.abs(y0) * rtol
        d0 = _norm(y0 / scale)
        d1 = _norm(f0 / scale)
        h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
        h0 = min(h0, interval_length)
        y1 = y0 + h0 * self.direction * f0
        f1 = self.fun(t0 + h0 * self.direction, y1)
        d2 = _norm((f1 - f0) / scale) / h0
        if d1 <= 1e-15 and d2 <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1 / (7 + 1))
        return min(100 * h0, h1, interval_length, np.inf)

    def run(self, dense_output: bool) -> Result:
        """scipy's solve_ivp loop without t_eval and events."""
        ts, ys, interpolants = [self.t], [self.y], []
        status, message = None, None
        while status is None:
            message = self.step()
            if self.status == "finished":
                status = 0
            elif self.status == "failed":
                status = -1
                break
            t, y = self.t, self.y
            if dense_output:
                interpolants.append(self.dense_output())
            if not (len(ts) > 1 and ts[-1] == t and dense_output):
                ts.append(t)
                ys.append(y)
            elif interpolants:
                interpolants.pop()
        message = FINISHED if status == 0 else message
        ts = np.array(ts)
        sol = Solution(ts, interpolants) if dense_output else None
        return Result(ts, np.vstack(ys).T, sol, self.nfev, status, message)

    def step(self):
        if self.n == 0 or self.t == self.t_bound:
            self.t_old, self.t, self.status = self.t, self.t_bound, "finished"
            return None
        t = self.t
        success, message = self._step_impl()
        if not success:
            self.status = "failed"
        else:
            self.t_old = t
            if self.direction * (self.t - self.t_bound) >= 0:
                self.status = "finished"
        return message

    def _step_impl(self):
        t, y, rtol, atol = self.t, self.y, self.rtol, self.atol
        min_step = 10 * np.abs(np.nextafter(t, self.direction * np.inf) - t)
        h_abs = min_step if self.h_abs < min_step else self.h_abs     # max_step = inf
        step_accepted = step_rejected = False
        while not step_accepted:
            if h_abs < min_step:
                return False, TOO_SMALL_STEP
            h = h_abs * self.direction
            t_new = t + h
            if self.direction * (t_new - self.t_bound) > 0:
                t_new = self.t_bound
            h = t_new - t
            h_abs = np.abs(h)
            y_new, f_new = self._rk_step(t, y, h)
            scale = atol + np.maximum(np.abs(y), np.abs(y_new)) * rtol
            error_norm = self._error_norm(h, scale)
            if error_norm < 1:
                factor = MAX_FACTOR if error_norm == 0 else min(MAX_FACTOR, SAFETY * error_norm ** ERROR_EXPONENT)
                if step_rejected:
                    factor = min(1, factor)
                h_abs *= factor
                step_accepted = True
            else:
                h_abs *= max(MIN_FACTOR, SAFETY * error_norm ** ERROR_EXPONENT)
                step_rejected = True
        self.h_previous, self.y_old = h, y
        self.t, self.y, self.h_abs, self.f = t_new, y_new, h_abs, f_new
        return True, None

    def _rk_step(self, t, y, h):
        K = self.K
        K[0] = self.f
        for s, (a, c) in enumerate(zip(A[1:], C[1:]), start=1):
            dy = np.dot(K[:s].T, a[:s]) * h
            K[s] = self.fun(t + c * h, y + dy)
        y_new = y + h * np.dot(K[:-1].T, B)
        f_new = self.fun(t + h, y_new)
        K[-1] = f_new
        return y_new, f_new

    def _error_norm(self, h, scale):
        K = self.K
        err5 = np.dot(K.T, tab.E5) / scale
        err3 = np.dot(K.T, tab.E3) / scale
        err5_norm_2 = np.linalg.norm(err5) ** 2
        err3_norm_2 = np.linalg.norm(err3) ** 2
        if err5_norm_2 == 0 and err3_norm_2 == 0:
            return 0.0
        denom = err5_norm_2 + 0.01 * err3_norm_2
        return np.abs(h) * err5_norm_2 / np.sqrt(denom * len(scale))

    def dense_output(self):
        if self.n == 0 or self.t == self.t_old:
            return _Constant(self.t_old, self.t, self.y)
        K, h = self.K_extended, self.h_previous
        for s, (a, c) in enumerate(zip(A_EXTRA, C_EXTRA), start=N_STAGES + 1):
            dy = np.dot(K[:s].T, a[:s]) * h
            K[s] = self.fun(self.t_old + c * h, self.y_old + dy)
        F = np.empty((tab.INTERPOLATOR_POWER, self.n), dtype=self.y_old.dtype)
        f_old = K[0]
        delta_y = self.y - self.y_old
        F[0] = delta_y
        F[1] = h * f_old - delta_y
        F[2] = 2 * delta_y - h * (self.f + f_old)
        F[3:] = h * np.dot(tab.D, K)
        return _Dense(self.t_old, self.t, self.y_old, F)


class _Dense:
    """scipy's Dop853DenseOutput: one step's interpolant."""

    def __init__(self, t_old, t, y_old, F):
        self.t_old, self.t, self.h, self.F, self.y_old = t_old, t, t - t_old, F, y_old

    def __call__(self, t):
        t = np.asarray(t)
        if t.ndim > 1:
            raise ValueError("`t` must be a float or a 1-D array.")
        x = (t - self.t_old) / self.h
        if t.ndim == 0:
            y = np.zeros_like(self.y_old)
        else:
            x = x[:, None]
            y = np.zeros((len(x), len(self.y_old)), dtype=self.y_old.dtype)
        for i, f in enumerate(reversed(self.F)):
            y += f
            if i % 2 == 0:
                y *= x
            else:
                y *= 1 - x
        y += self.y_old
        return y.T


class _Constant:
    """scipy's ConstantDenseOutput (a step of length zero)."""

    def __init__(self, t_old, t, value):
        self.t_old, self.t, self.value = t_old, t, value

    def __call__(self, t):
        t = np.asarray(t)
        if t.ndim > 1:
            raise ValueError("`t` must be a float or a 1-D array.")
        if t.ndim == 0:
            return self.value
        ret = np.empty((self.value.shape[0], t.shape[0]))
        ret[:] = self.value[:, None]
        return ret


class Solution:
    """scipy's OdeSolution (alt_segment False): the interpolants of all steps as one function."""

    def __init__(self, ts, interpolants):
        ts = np.asarray(ts)
        d = np.diff(ts)
        if not ((ts.size == 2 and ts[0] == ts[-1]) or np.all(d > 0) or np.all(d < 0)):
            raise ValueError("`ts` must be strictly increasing or decreasing.")
        self.n_segments = len(interpolants)
        if ts.shape != (self.n_segments + 1,):
            raise ValueError("Numbers of time stamps and interpolants don't match.")
        self.ts, self.interpolants = ts, interpolants
        self.ascending = bool(ts[-1] >= ts[0])
        self.t_min, self.t_max = (ts[0], ts[-1]) if self.ascending else (ts[-1], ts[0])
        self.side = "left" if self.ascending else "right"
        self.ts_sorted = ts if self.ascending else ts[::-1]

    def __call__(self, t):
        t = np.asarray(t)
        if t.ndim == 0:
            ind = np.searchsorted(self.ts_sorted, t, side=self.side)
            segment = min(max(ind - 1, 0), self.n_segments - 1)
            if not self.ascending:
                segment = self.n_segments - 1 - segment
            return self.interpolants[segment](t)
        order = np.argsort(t)
        reverse = np.empty_like(order)
        reverse[order] = np.arange(order.shape[0])
        t_sorted = t[order]
        segments = np.searchsorted(self.ts_sorted, t_sorted, side=self.side)
        segments -= 1
        segments[segments < 0] = 0
        segments[segments > self.n_segments - 1] = self.n_segments - 1
        if not self.ascending:
            segments = self.n_segments - 1 - segments
        ys, start = [], 0
        for segment, group in groupby(segments):
            end = start + len(list(group))
            ys.append(self.interpolants[segment](t_sorted[start:end]))
            start = end
        return np.hstack(ys)[:, reverse]
