"""Synchronized joint motion profiles (the course's §7.4, corrected).

Three rest-to-rest shapes (spec, "Motion profiles"; docs/course-notes.md#note-motion-sync):

* ``bang-bang``: constant acceleration +a up to T/2, -a after (the course's
  profile a t^2/2 | aT^2/4 - a(T - t)^2/2).  Own time T_i = sqrt(4|D_i|/a_i),
  synchronized T = max T_i, rescaled a_i = 4|D_i|/T^2 (magnitudes; the sign of
  D_i goes into the profile).
* ``trapezoidal``: acceleration a_i up to the cruise velocity v_i, cruise, then
  deceleration.  T_i = |D_i|/v_i + v_i/a_i when |D_i| >= v_i^2/a_i, else the
  bang-bang time.  T = max T_i; every other joint keeps its acceleration and
  lowers its cruise velocity to v_i' = (a_i T - sqrt(a_i^2 T^2 - 4 a_i |D_i|))/2
  so that it also ends at T.
* ``quintic``: q = q0 + D (10 s^3 - 15 s^4 + 6 s^5), s = t/T, whose peak
  acceleration is 10|D|/(sqrt(3) T^2); so T_i = sqrt(10|D_i|/(sqrt(3) a_i)) and
  the reported accelerations are the peaks at the synchronized T.

A joint that does not move (D = 0) has own time 0, acceleration 0 and a constant
profile (Robotics Toolbox's ``trapezoidal`` crashes on it, its issue #315).
Every profile holds its end value after T (the arm is at rest) and its start
value before 0.

Values stay exact when the inputs are exact (sympy Rational, pi, sqrt...).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import sympy as sp

from robosolve.core.simplify import collected_radicals
from robosolve.core.symbols import TIME

__all__ = ["SHAPES", "Segment", "JointMotion", "SyncProfile", "synchronize", "ProfileError"]

SHAPES = ("bang-bang", "trapezoidal", "quintic")

_QUINTIC_PEAK = 10 / sp.sqrt(3)       # peak |qdd| T^2 / |D| of the quintic


class ProfileError(ValueError):
    """Bad input for a profile (negative limits, missing velocity limit...)."""


@dataclass(frozen=True)
class Segment:
    """One polynomial piece of a joint profile: q(t) = ``position`` for t0 <= t <= t1."""

    t0: sp.Expr
    t1: sp.Expr
    position: sp.Expr          # expression in the time symbol, course form (not expanded)
    label: str                 # "acceleration", "cruise", "deceleration", "rest", "quintic"


@dataclass(frozen=True)
class JointMotion:
    """The motion of one joint within a synchronized profile."""

    name: str
    start: sp.Expr
    end: sp.Expr
    delta: sp.Expr             # end - start
    direction: sp.Expr         # sign(delta): 1, -1 or 0
    max_acceleration: sp.Expr
    max_velocity: sp.Expr | None
    own_time: sp.Expr          # the joint alone, at its limits
    acceleration: sp.Expr      # magnitude used at the synchronized T (peak for quintic)
    velocity: sp.Expr          # peak (bang-bang, quintic) or cruise (trapezoidal) speed
    segments: tuple[Segment, ...]   # pieces inside [0, T]; empty when the joint does not move

    @property
    def moves(self) -> bool:
        return self.direction != 0

    @property
    def switch_times(self) -> tuple[sp.Expr, ...]:
        """Instants in (0, T) where the acceleration of this joint changes law."""
        return tuple(s.t0 for s in self.segments[1:])


@dataclass(frozen=True)
class SyncProfile:
    """A synchronized multi-joint profile: all joints start at 0 and stop at T."""

    shape: str
    t: sp.Symbol
    T: sp.Expr
    slowest: tuple[str, ...]           # names of the joints whose own time is T
    joints: tuple[JointMotion, ...]
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def names(self) -> list[str]:
        return [j.name for j in self.joints]

    def breakpoints(self) -> list[sp.Expr]:
        """Sorted instants 0 = t_0 < t_1 < ... < t_k = T where some acceleration jumps."""
        pts = {sp.S(0), self.T}
        for j in self.joints:
            pts.update(s.t0 for s in j.segments)
            pts.update(s.t1 for s in j.segments)
        return sorted(pts, key=_sort_key)

    def position(self, i: int) -> sp.Expr:
        """Piecewise position of joint i in t (start before 0, end after T)."""
        return self._piecewise(i, 0)

    def velocity(self, i: int) -> sp.Expr:
        return self._piecewise(i, 1)

    def acceleration(self, i: int) -> sp.Expr:
        return self._piecewise(i, 2)

    def _piecewise(self, i: int, order: int) -> sp.Expr:
        key = ("pw", i, order)
        if key not in self._cache:
            j, t = self.joints[i], self.t
            rest = j.start if order == 0 else sp.S(0)
            if not j.segments:
                self._cache[key] = rest
            else:
                pieces = [(rest, t < 0)]
                for s in j.segments:
                    pieces.append((sp.diff(s.position, t, order), t <= s.t1))
                pieces.append((j.end if order == 0 else sp.S(0), True))
                self._cache[key] = sp.Piecewise(*pieces, evaluate=False)
        return self._cache[key]

    # ---------------------------------------------------------------- numeric
    def numeric_plan(self) -> "NumericPlan":
        """Float polynomial coefficients of every joint on every interval (for ODEs, plots)."""
        if "plan" not in self._cache:
            self._cache["plan"] = NumericPlan.from_profile(self)
        return self._cache["plan"]


class NumericPlan:
    """Desired trajectory as float polynomials, interval by interval.

    ``breaks`` = [0, t_1, ..., T] (floats).  On interval k (breaks[k] <= t <= breaks[k+1])
    joint i follows sum_p coeffs[k][i, p] (t - breaks[k])^p, p = 0..5.  After T the
    joints hold their end values (``hold``), before 0 their start values.
    """

    DEG = 6

    def __init__(self, breaks, coeffs, start, hold):
        import numpy as np
        self.breaks = np.asarray(breaks, dtype=float)
        self.coeffs = [np.asarray(c, dtype=float) for c in coeffs]
        self.start = np.asarray(start, dtype=float)
        self.hold = np.asarray(hold, dtype=float)
        self.n = len(self.start)
        self.T = float(self.breaks[-1])

    @classmethod
    def from_profile(cls, prof: SyncProfile) -> "NumericPlan":
        t, tau = prof.t, sp.Dummy("tau")
        bps = prof.breakpoints()
        coeffs = []
        for a, b in zip(bps[:-1], bps[1:]):
            mid = (a + b) / 2
            rows = []
            for j in prof.joints:
                expr = j.start
                for s in j.segments:
                    if _num(s.t0) <= _num(mid) <= _num(s.t1):
                        expr = s.position
                        break
                poly = sp.Poly(sp.expand(sp.sympify(expr).subs(t, tau + a)), tau)
                c = [0.0] * cls.DEG
                for (p,), v in poly.terms():
                    c[p] = float(v)
                rows.append(c)
            coeffs.append(rows)
        start = [float(j.start) for j in prof.joints]
        hold = [float(j.end) for j in prof.joints]
        if not coeffs:                       # nothing moves: T = 0
            coeffs = [[[h] + [0.0] * (cls.DEG - 1) for h in hold]]
            bps = [sp.S(0), sp.S(0)]
        return cls([float(b) for b in bps], coeffs, start, hold)

    def interval(self, t: float) -> int:
        """Index of the interval containing t (the last one for t >= T)."""
        import numpy as np
        k = int(np.searchsorted(self.breaks, t, side="right")) - 1
        return min(max(k, 0), len(self.coeffs) - 1)

    def evaluate(self, times, k: int | None = None):
        """(q, qd, qdd) arrays of shape (n, len(times)).

        With ``k`` the polynomials of interval k are used for every time (one-sided
        values at the ends of the interval); otherwise each time picks its own
        interval, and times outside [0, T] give the rest values.
        """
        import numpy as np
        times = np.atleast_1d(np.asarray(times, dtype=float))
        q = np.empty((self.n, times.size))
        qd = np.zeros_like(q)
        qdd = np.zeros_like(q)
        if k is not None:
            idx = np.full(times.size, k)
        else:
            idx = np.clip(np.searchsorted(self.breaks, times, side="right") - 1, 0, len(self.coeffs) - 1)
        for kk in np.unique(idx):
            sel = idx == kk
            tau = times[sel] - self.breaks[kk]
            c = self.coeffs[kk]
            powers = np.vstack([tau ** p for p in range(self.DEG)])
            dpow = np.vstack([np.zeros_like(tau)] + [p * tau ** (p - 1) for p in range(1, self.DEG)])
            ddpow = np.vstack([np.zeros_like(tau)] * 2 + [p * (p - 1) * tau ** (p - 2) for p in range(2, self.DEG)])
            q[:, sel] = c @ powers
            qd[:, sel] = c @ dpow
            qdd[:, sel] = c @ ddpow
        if k is None:
            after = times > self.T
            before = times < 0
            q[:, after] = self.hold[:, None]
            qd[:, after] = qdd[:, after] = 0.0
            q[:, before] = self.start[:, None]
            qd[:, before] = qdd[:, before] = 0.0
        return q, qd, qdd


# --------------------------------------------------------------------- helpers
def _sort_key(e):
    return (_num(e), sp.default_sort_key(e))


def _num(e) -> float:
    try:
        return float(sp.N(e, 30))
    except (TypeError, ValueError):
        raise ProfileError(f"cannot order {e} numerically (a parameter without a value?)")


def _is_number(e) -> bool:
    return sp.sympify(e).is_number


def _pick_max(values: Sequence[sp.Expr]) -> sp.Expr:
    """The largest of exact values (compared at 30 digits), or Max(...) when symbolic."""
    if all(_is_number(v) for v in values):
        best = values[0]
        for v in values[1:]:
            if _num(v) > _num(best) * (1 + 1e-25) + 1e-30:
                best = v
        return best
    return sp.Max(*values)


def _nice(e):
    """Exact numbers with their radicals collected (radsimp: fast); never a blanket simplify."""
    e = sp.sympify(e)
    if e.is_number and not e.is_Rational and not e.has(sp.Float):
        return collected_radicals(e)
    return e


def synchronize(
    names: Sequence[str],
    start: Sequence,
    end: Sequence,
    max_acceleration: Sequence,
    shape: str = "bang-bang",
    max_velocity: Sequence | None = None,
    t: sp.Symbol | None = None,
) -> SyncProfile:
    """Build the synchronized profile of the joints ``names`` from ``start`` to ``end``.

    Example: bang-bang from (0, 2) to (1, -2) with a_max = (4, 2): own times
    (1, 2*sqrt(2)), T = 2*sqrt(2), accelerations (1/2, 2).
    """
    if shape not in SHAPES:
        raise ProfileError(f"unknown shape {shape!r} (expected one of {', '.join(SHAPES)})")
    t = TIME if t is None else t
    n = len(names)
    if not (len(start) == len(end) == len(max_acceleration) == n):
        raise ProfileError("start, end and max_acceleration need one value per joint")
    if shape == "trapezoidal":
        if max_velocity is None or len(max_velocity) != n:
            raise ProfileError("the trapezoidal shape needs max_velocity for every joint")
    q0 = [sp.sympify(v) for v in start]
    q1 = [sp.sympify(v) for v in end]
    acc = [sp.sympify(v) for v in max_acceleration]
    vel = [sp.sympify(v) for v in max_velocity] if max_velocity is not None else [None] * n
    for nm, a in zip(names, acc):
        if _is_number(a) and not _num(a) > 0:
            raise ProfileError(f"max_acceleration of {nm} must be positive (got {a})")
    for nm, v in zip(names, vel):
        if v is not None and _is_number(v) and not _num(v) > 0:
            raise ProfileError(f"max_velocity of {nm} must be positive (got {v})")

    delta = [b - a for a, b in zip(q0, q1)]
    dist = [sp.Abs(d) for d in delta]
    sign = [sp.sign(d) for d in delta]
    own = [_own_time(shape, d, a, v) for d, a, v in zip(dist, acc, vel)]
    own = [_nice(x) for x in own]
    T = _pick_max(own)
    slowest = _slowest(names, own, T)
    joints = [_joint_motion(shape, names[i], q0[i], q1[i], delta[i], dist[i], sign[i], acc[i], vel[i],
                            own[i], T, names[i] in slowest, t) for i in range(n)]
    return SyncProfile(shape, t, T, slowest, tuple(joints))


def _own_time(shape: str, d, a, v):
    """The time of a joint moving |D| = d alone at its limits (0 when it does not move)."""
    if d == 0:
        return sp.S(0)
    if shape == "bang-bang":
        return sp.sqrt(4 * d / a)
    if shape == "quintic":
        return sp.sqrt(_QUINTIC_PEAK * d / a)
    if _num(d) >= _num(v ** 2 / a):
        return d / v + v / a
    return sp.sqrt(4 * d / a)      # trapezoidal too short to reach v: the bang-bang time


def _slowest(names, own, T) -> tuple[str, ...]:
    """The moving joints whose own time is T (none when the times are symbolic)."""
    if not all(_is_number(x) for x in own):
        return ()
    return tuple(nm for nm, x in zip(names, own) if x != 0 and abs(_num(x) - _num(T)) <= 1e-12 * max(1.0, _num(T)))


def _joint_motion(shape, name, q0, q1, delta, d, s, a, v, own, T, slowest: bool, t) -> JointMotion:
    """One joint's motion from q0 to q1 (D = delta, |D| = d, sign s) ending at the synchronized T."""
    if d == 0:
        return JointMotion(name, q0, q1, delta, sp.S(0), a, v, sp.S(0), sp.S(0), sp.S(0), ())
    if shape == "bang-bang":
        acceleration, velocity, segs = _bang_bang_pieces(q0, d, s, T, t)
    elif shape == "quintic":
        acceleration, velocity, segs = _quintic_pieces(q0, delta, d, T, t)
    else:
        acceleration, velocity, segs = _trapezoidal_pieces(q0, q1, d, s, a, v, T, t, slowest)
    return JointMotion(name, q0, q1, delta, s, a, v, own, acceleration, velocity, segs)


def _bang_bang_pieces(q0, d, s, T, t):
    """(rescaled acceleration, peak velocity, segments): +a up to T/2, -a after."""
    ar = _nice(4 * d / T ** 2)
    h = T / 2
    segs = (
        Segment(sp.S(0), h, q0 + s * ar * t ** 2 / 2, "acceleration"),
        Segment(h, T, q0 + s * (ar * T ** 2 / 4 - ar * (T - t) ** 2 / 2), "deceleration"),
    )
    return ar, _nice(ar * T / 2), segs


def _quintic_pieces(q0, delta, d, T, t):
    """(peak acceleration, peak velocity, the one quintic segment) at the synchronized T."""
    ar = _nice(_QUINTIC_PEAK * d / T ** 2)
    u = t / T
    segs = (Segment(sp.S(0), T, q0 + delta * (10 * u ** 3 - 15 * u ** 4 + 6 * u ** 5), "quintic"),)
    return ar, _nice(15 * d / (8 * T)), segs


def _trapezoidal_pieces(q0, q1, d, s, a, v, T, t, slowest: bool):
    """(acceleration, cruise velocity, segments): the slowest joint keeps its limits, every other
    keeps its acceleration and lowers its cruise velocity so that it also ends at T."""
    if slowest:
        vc = v if _num(d) >= _num(v ** 2 / a) else sp.sqrt(a * d)
    else:
        vc = _nice((a * T - sp.sqrt(a ** 2 * T ** 2 - 4 * a * d)) / 2)
    ta = _nice(vc / a)
    if abs(_num(2 * ta) - _num(T)) <= 1e-12 * _num(T):      # triangular: no cruise
        ta = T / 2
        segs = (
            Segment(sp.S(0), ta, q0 + s * a * t ** 2 / 2, "acceleration"),
            Segment(ta, T, q1 - s * a * (T - t) ** 2 / 2, "deceleration"),
        )
    else:
        segs = (
            Segment(sp.S(0), ta, q0 + s * a * t ** 2 / 2, "acceleration"),
            Segment(ta, T - ta, q0 + s * (vc * t - vc ** 2 / (2 * a)), "cruise"),
            Segment(T - ta, T, q1 - s * a * (T - t) ** 2 / 2, "deceleration"),
        )
    return a, vc, segs
