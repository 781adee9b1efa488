"""Actuator forces needed to follow a synchronized profile (the course's §7.5.1).

tau(t) = M(q) qdd + c(q, qd) + g(q) - f_ext(q) with q, qd, qdd the desired profile.
The profile is polynomial on each interval between switching instants, so tau is
a closed-form expression in t on each of them; it jumps where an acceleration
jumps (0, T/2 and T for bang-bang, docs/course-notes.md#note-torque-jumps).

Peaks (spec, "Joint torques"): the signed value of largest magnitude over [0, T],
with the one-sided limits at the jumps included, so that t_peak is exactly a
switching instant when the extreme sits on a jump.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np
import sympy as sp

from robosolve.core.extremes import tie_tolerance
from robosolve.core.simplify import common_factors, factored
from robosolve.dynamics.numeric import NumericDynamics
from robosolve.motion.profiles import SyncProfile

__all__ = ["TorqueResult", "torques_along", "closed_form_pieces"]


@dataclass
class TorqueResult:
    names: list[str]                       # actuator names, in joint order
    peaks: list[float]                     # signed values of largest magnitude over [0, T]
    t_peaks: list[float]
    t: np.ndarray                          # samples (each switching instant twice: both sides)
    values: np.ndarray                     # (n, N)
    breaks: list[float]                    # switching instants inside (0, T)
    intervals: list[tuple[float, float]]   # the intervals [a, b] of the pieces
    jumps: list = None                     # [(t, values just before, values just after)] at 0, switches, T
    profiles: list[sp.Expr] | None = None  # piecewise closed forms in t, when symbolic
    pieces: list[list[sp.Expr]] | None = None   # per actuator, one expression per interval


def closed_form_pieces(profile: SyncProfile, exprs: Sequence[sp.Expr], q, qd, qdd,
                       subs: dict | None = None) -> tuple[list[list[sp.Expr]], list[sp.Expr]]:
    """Substitute the profile into the actuator expressions, interval by interval.

    Returns (pieces[i][k], piecewise[i]): actuator i on interval k, and the whole
    Piecewise in t (the holding forces at the start before 0 and at the end after T).
    """
    t = profile.t
    bps = profile.breakpoints()
    rep0 = {sp.sympify(k): sp.sympify(v) for k, v in (subs or {}).items()}
    exprs = [sp.sympify(e).xreplace(rep0) if rep0 else sp.sympify(e) for e in exprs]

    def joint_state(j, a, b):
        mid = (a + b) / 2
        for s in j.segments:
            if float(s.t0) <= float(mid) <= float(s.t1):
                # small polynomials: factored rates read as the course writes them, a (T - t)
                return s.position, factored(sp.diff(s.position, t)), factored(sp.diff(s.position, t, 2))
        return j.start, sp.S(0), sp.S(0)

    def rest(at_end: bool):
        rep = {}
        for i, j in enumerate(profile.joints):
            rep[q[i]] = j.end if at_end else j.start
            rep[qd[i]] = sp.S(0)
            rep[qdd[i]] = sp.S(0)
        return [e.xreplace(rep) for e in exprs]

    pieces = [[] for _ in exprs]
    for a, b in zip(bps[:-1], bps[1:]):
        rep = {}
        for i, j in enumerate(profile.joints):
            rep[q[i]], rep[qd[i]], rep[qdd[i]] = joint_state(j, a, b)
        for i, e in enumerate(exprs):
            pieces[i].append(merge_terms(e.xreplace(rep), t))
    before, after = [merge_terms(e, t) for e in rest(False)], [merge_terms(e, t) for e in rest(True)]
    pw = []
    for i in range(len(exprs)):
        if not pieces[i]:
            pw.append(before[i])
            continue
        args = [(before[i], t < 0)]
        args += [(p, t <= b) for p, b in zip(pieces[i], bps[1:])]
        args.append((after[i], True))
        pw.append(sp.Piecewise(*args, evaluate=False))
    return pieces, pw


def merge_terms(expr: sp.Expr, t: sp.Symbol) -> sp.Expr:
    """One term per function of time: the additive terms with the same t-dependent factor
    (a power of t times a sine, say) are merged and their parameter coefficients factored.

    The substituted profile leaves the same factor in several terms (from M q'', c and g);
    merging them is cheap (no trigonometric simplification) and deterministic.
    """
    groups: dict = {}
    for term in sp.Add.make_args(sp.expand(expr, trig=False, mul=True, multinomial=False,
                                           power_base=False, power_exp=False, log=False)):
        coeff, factor = term.as_independent(t, as_Add=False)
        groups.setdefault(factor, []).append(coeff)
    out = []
    for factor in sorted(groups, key=sp.default_sort_key):
        coeff = common_factors(sp.Add(*groups[factor]))
        if coeff != 0:
            out.append(coeff * factor)
    return sp.Add(*out)


def golden_max(f, lo: float, hi: float, iterations: int = 64) -> float:
    """Golden-section search for the maximum of a unimodal f on [lo, hi].

    (Plain Python on purpose: scipy.optimize costs ~0.6 s to import, more than the whole
    torque question.)  64 iterations shrink the bracket by 0.618^64 ~ 4e-14.
    """
    r = (5 ** 0.5 - 1) / 2
    a, b = lo, hi
    c, d = b - r * (b - a), a + r * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(iterations):
        if fc >= fd:
            b, d, fd = d, c, fc
            c = b - r * (b - a)
            fc = f(c)
        else:
            a, c, fc = c, d, fd
            d = a + r * (b - a)
            fd = f(d)
    return (a + b) / 2


def _near_top_maxima(vals: np.ndarray, within: float = 1e-2, keep: int = 12) -> list[int]:
    """Indices, in time order, of the local maxima of the samples ``vals`` (ends included) that
    come within ``within`` (relative) of the largest: the sampled heights of two peaks differ
    from the true ones by up to ~(pi/samples)^2, so any of them may be the true maximum.
    At most ``keep`` of them."""
    m = vals.size
    if m <= 2:
        return [int(np.argmax(vals))]
    inner = np.nonzero((vals[1:-1] >= vals[:-2]) & (vals[1:-1] >= vals[2:]))[0] + 1
    idx = np.concatenate([[0], inner, [m - 1]])
    top = float(vals.max())
    near = [int(k) for k in idx if vals[k] >= top * (1 - within)]
    if len(near) > keep:             # a plateau (round-off ripples): its start and the highest
        highest = sorted(near, key=lambda k: -vals[k])[:keep - 1]
        near = sorted({near[0], *highest})
    return near


def _falls_from_end(f, j: int, ts: np.ndarray, value: float) -> bool:
    """Whether sample j, an end of the interval, is itself the maximum nearby: f is lower just
    inside (a thousandth of a step), so there is nothing to refine (the usual case at a jump)."""
    if 0 < j < ts.size - 1:
        return False
    inward = ts[1] - ts[0] if j == 0 else ts[-2] - ts[-1]
    return f(float(ts[j] + 1e-3 * inward)) < value


def torques_along(profile: SyncProfile, dyn: NumericDynamics, names: Sequence[str],
                  samples_per_interval: int = 241) -> TorqueResult:
    """Sample tau(t) on every interval (closed at both ends) and find the signed peaks."""
    plan = profile.numeric_plan()
    n = dyn.n
    ts_all, vals_all, intervals = [], [], []
    best = [(-1.0, 0.0, 0.0)] * n          # (|tau|, tau, t)
    for k in range(len(plan.coeffs)):
        a, b = float(plan.breaks[k]), float(plan.breaks[k + 1])
        if not b > a:
            continue
        intervals.append((a, b))
        ts = np.linspace(a, b, samples_per_interval)
        Q, QD, QDD = plan.evaluate(ts, k=k)
        tau = dyn.inverse_many(Q, QD, QDD, ts)
        ts_all.append(ts)
        vals_all.append(tau)

        def at(s, i, k=k):
            Qs, QDs, QDDs = plan.evaluate([s], k=k)
            return float(dyn.inverse(Qs[:, 0], QDs[:, 0], QDDs[:, 0], s)[i])

        for i in range(n):
            # every local maximum of |tau| near the sampled one: two peaks of (nearly) equal
            # height (a quintic's acceleration, a symmetric motion) are both refined, so the
            # higher one wins and an exact tie goes to the earlier instant
            for j in _near_top_maxima(np.abs(tau[i])):
                cand, tc = float(tau[i, j]), float(ts[j])
                lo, hi = float(ts[max(j - 1, 0)]), float(ts[min(j + 1, ts.size - 1)])
                if not _falls_from_end(lambda s: abs(at(s, i)), j, ts, abs(cand)):
                    x = golden_max(lambda s: abs(at(s, i)), lo, hi)
                    v = at(x, i)
                    if abs(v) > abs(cand) + tie_tolerance(cand):   # not round-off on a plateau (kept at its start)
                        cand, tc = v, x
                mag = abs(cand)
                cur = best[i]
                if mag > cur[0] + tie_tolerance(max(mag, cur[0])):   # ties keep the earlier instant (core/extremes.py)
                    best[i] = (mag, cand, tc)
    if not intervals:                       # nothing moves: the holding forces
        Q, QD, QDD = plan.evaluate([0.0])
        tau = dyn.inverse_many(Q, QD, QDD, np.array([0.0]))
        ts_all, vals_all = [np.array([0.0])], [tau]
        best = [(abs(float(tau[i, 0])), float(tau[i, 0]), 0.0) for i in range(n)]
    # one-sided values at every switching instant (the arm holds still before 0 and after T)
    # the holding forces just before 0 and just after T (a force varying with time: at 0 and T)
    hold0 = dyn.inverse(plan.start, np.zeros(n), np.zeros(n), 0.0)
    hold1 = dyn.inverse(plan.hold, np.zeros(n), np.zeros(n), float(plan.T))
    jumps = []
    if intervals:
        edges = [iv[0] for iv in intervals] + [intervals[-1][1]]
        for k, s in enumerate(edges):
            before = hold0 if k == 0 else vals_all[k - 1][:, -1]
            after = hold1 if k == len(edges) - 1 else vals_all[k][:, 0]
            jumps.append((float(s), [float(x) for x in before], [float(x) for x in after]))
    return TorqueResult(
        jumps=jumps,
        names=list(names),
        peaks=[b[1] for b in best],
        t_peaks=[b[2] for b in best],
        t=np.concatenate(ts_all),
        values=np.hstack(vals_all),
        breaks=[float(x) for x in plan.breaks[1:-1]],
        intervals=intervals,
    )
