"""Work-space trajectories (course summary §1.2.2): a path in the task coordinates, timed along
its length, converted to joint motion by following one inverse-kinematics branch.

Path x(s), 0 <= s <= L (arc length):

* line:   x(s) = a + s u,                       u = (b - a) / L
* circle: x(s) = c + r (cos(s/r) e1 + sin(s/r) e2), e1 = (a - c)/r, e2 in the plane of the arc,
  the shorter way from a to b (angle phi in (0, pi], L = r phi)

Timing s(t) on [0, T]: trapezoidal (accelerate at a_max, cruise at v_max, decelerate; when
L < v_max^2 / a_max the cruise is never reached: bang-bang, T = 2 sqrt(L / a_max)) or quintic
(s = L (10 tau^3 - 15 tau^4 + 6 tau^5), tau = t / T).

Joints: at each sample, q solves x(q) = x_d(t) by Newton's method from the previous sample,
then q_dot = J^-1 x_dot_d and q_ddot = J^-1 (x_ddot_d - J_dot q_dot).  With fewer coordinates
than joints (J wide) the joint motion is the one of the minimum-norm rates q_dot = J^+ x_dot_d:
x(q) = x_d(t) alone leaves a family of configurations, and Newton's steps from sample to sample
would drift along it (by about 1e-4 rad on a 3R arm), so q is integrated from sample to sample
(classical Runge-Kutta, fixed sub-steps) and only polished by Newton (a minimum-norm correction:
it moves q off the family's direction by round-off only).  Its acceleration is the derivative of
J^+ x_dot_d, which has a null-space part besides J^+ (x_ddot_d - J_dot q_dot):

    q_ddot = J^+ (x_ddot_d - J_dot q_dot) + (I - J^+ J) J_dot^T (J J^T)^-1 x_dot_d

Pure numpy: the arm comes in as callables.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from robosolve.core.extremes import first_of_ties, tie_tolerance

__all__ = ["PathError", "Path", "line", "circle", "Timing", "trapezoidal", "quintic", "Arm",
           "Conversion", "NEWTON_TOL", "newton", "singular_floor", "nearest_solution", "joint_state", "follow", "extremes"]


class PathError(ValueError):
    """A path that cannot be built; ``key`` names the option at fault."""

    def __init__(self, message: str, key: str):
        super().__init__(message)
        self.key = key


@dataclass
class Path:
    kind: str                       # "line" or "circle"
    a: np.ndarray
    b: np.ndarray
    length: float
    center: np.ndarray | None = None
    radius: float = 0.0
    angle: float = 0.0
    e1: np.ndarray | None = None
    e2: np.ndarray | None = None

    def at(self, s: float):
        """(x, dx/ds, d2x/ds2) at arc length s."""
        if self.kind == "line":
            u = (self.b - self.a) / self.length
            return self.a + s * u, u, np.zeros_like(u)
        r, th = self.radius, s / self.radius
        c, sn = math.cos(th), math.sin(th)
        x = self.center + r * (c * self.e1 + sn * self.e2)
        d1 = -sn * self.e1 + c * self.e2
        d2 = -(c * self.e1 + sn * self.e2) / r
        return x, d1, d2


def line(a, b) -> Path:
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    length = float(np.linalg.norm(b - a))
    if not length > 0:
        raise PathError("`from` and `to` are the same point: the path has no length", "to")
    return Path("line", a, b, length)


def circle(a, b, center, normal=None, rtol: float = 1e-6) -> Path:
    """The arc from a to b about ``center``, the shorter way (``normal`` fixes the plane of a half
    circle, and must be perpendicular to it)."""
    a, b, c = (np.asarray(v, dtype=float) for v in (a, b, center))
    if a.size not in (2, 3):
        raise PathError(f"a circular path needs 2 or 3 coordinates (there are {a.size})", "path")
    ra, rb = a - c, b - c
    with np.errstate(over="ignore", invalid="ignore"):       # a centre near 1e200 overflows: said below
        r, r2 = float(np.linalg.norm(ra)), float(np.linalg.norm(rb))
    if not (math.isfinite(r) and math.isfinite(r2)):
        raise PathError("the centre is too far from the path: its distance to `from` and `to` is beyond "
                        "the range of floating-point numbers", "path")
    if not r > 0:
        raise PathError("the centre is the `from` point itself", "path")
    if abs(r - r2) > rtol * max(r, r2):
        raise PathError(f"the centre is not equidistant from `from` and `to` (distances {r:.6g} "
                        f"and {r2:.6g})", "path")
    if np.linalg.norm(b - a) == 0:
        raise PathError("`from` and `to` are the same point: the arc has no length", "to")
    e1 = ra / r
    perp = rb / r - float(np.dot(rb / r, e1)) * e1
    cosphi = float(np.clip(np.dot(ra, rb) / (r * r), -1.0, 1.0))
    phi = math.acos(cosphi)
    n = None if normal is None else np.asarray(normal, dtype=float)
    if n is not None and a.size != 3:
        raise PathError(f"a path in {a.size} coordinates lies in their plane: give no `normal` (it fixes the "
                        "plane of an arc in 3 coordinates)", "path")
    if n is not None and (n.size != 3 or not np.linalg.norm(n) > 0):
        raise PathError("the normal is a non-zero vector of the 3 coordinates", "path")
    if n is not None:
        n = n / np.linalg.norm(n)
        if abs(float(np.dot(n, e1))) > 1e-6 or abs(float(np.dot(n, rb / r))) > 1e-6:
            raise PathError("the normal is not perpendicular to the plane of the arc", "path")
    if np.linalg.norm(perp) > 1e-9:
        e2 = perp / np.linalg.norm(perp)
    elif a.size == 2:
        e2 = np.array([-e1[1], e1[0]])          # a half circle: counter-clockwise
    elif n is not None:
        e2 = np.cross(n, e1)
    else:
        raise PathError("`from` and `to` are opposite ends of a diameter: give the circle's "
                        "`normal` to fix its plane", "path")
    return Path("circle", a, b, r * phi, center=c, radius=r, angle=phi, e1=e1, e2=e2)


@dataclass
class Timing:
    kind: str                      # "trapezoidal", "bang-bang" or "quintic"
    length: float
    T: float
    breaks: list                   # [0, ..., T]: where s_ddot jumps
    v_peak: float = 0.0
    a_max: float = 0.0
    t_acc: float = 0.0

    def at(self, t: float, segment: int | None = None):
        """(s, s_dot, s_ddot) at t; ``segment`` picks the side at a switching instant."""
        if segment is None:
            segment = max(0, min(int(np.searchsorted(self.breaks, t, side="right")) - 1,
                                 len(self.breaks) - 2))
        if self.kind == "quintic":
            T, L = self.T, self.length
            u = t / T
            return (L * (10 * u ** 3 - 15 * u ** 4 + 6 * u ** 5), L * (30 * u ** 2 - 60 * u ** 3 + 30 * u ** 4) / T,
                    L * (60 * u - 180 * u ** 2 + 120 * u ** 3) / T ** 2)
        a, v, ta, T, L = self.a_max, self.v_peak, self.t_acc, self.T, self.length
        if segment == 0:
            return 0.5 * a * t * t, a * t, a
        if segment == len(self.breaks) - 2:
            d = T - t
            return L - 0.5 * a * d * d, a * d, -a
        return 0.5 * a * ta * ta + v * (t - ta), v, 0.0


def trapezoidal(length: float, v_max: float, a_max: float) -> Timing:
    """Trapezoidal speed along the path; bang-bang when the cruise speed is not reached."""
    if length >= v_max * v_max / a_max:
        ta = v_max / a_max
        T = length / v_max + ta
        return Timing("trapezoidal", length, T, [0.0, ta, T - ta, T], v_max, a_max, ta)
    ta = math.sqrt(length / a_max)
    return Timing("bang-bang", length, 2 * ta, [0.0, ta, 2 * ta], a_max * ta, a_max, ta)


def quintic(length: float, duration: float) -> Timing:
    return Timing("quintic", length, duration, [0.0, duration], 1.875 * length / duration,
                  5.773502691896258 * length / duration ** 2)


@dataclass
class Arm:
    """The arm's task map as numeric callables of numpy arrays."""

    x: Callable                    # q -> (m,)
    J: Callable                    # q -> (m, n)
    jdot_qdot: Callable            # (q, q_dot) -> (m,)  = J_dot q_dot
    revolute: list                 # per joint
    jdot: Callable | None = None   # (q, q_dot) -> (m, n) = J_dot (a wide J needs it; default:
                                   # a central difference of J along q_dot)

    def J_dot(self, q, qd):
        if self.jdot is not None:
            return self.jdot(q, qd)
        speed = float(np.max(np.abs(qd)))
        if speed == 0:
            return np.zeros_like(self.J(q))
        h = 1e-5 / speed
        return (self.J(q + h * qd) - self.J(q - h * qd)) / (2 * h)


# Newton's tolerance on the residual x_d - x(q), relative to max(1, |x_d|)
NEWTON_TOL = 1e-12


def newton(arm: Arm, target, q0, tol: float = NEWTON_TOL, max_iter: int = 30):
    """q with x(q) = target near q0 (minimum-norm steps); None when it does not converge."""
    q = np.array(q0, dtype=float)
    scale = max(1.0, float(np.max(np.abs(target))))
    for _ in range(max_iter):
        r = np.asarray(target, dtype=float) - arm.x(q)
        if float(np.max(np.abs(r))) <= tol * scale:
            return q
        step = np.linalg.lstsq(arm.J(q), r, rcond=None)[0]
        big = float(np.max(np.abs(step)))
        q = q + (step if big <= 0.5 else step * (0.5 / big))
    r = np.asarray(target, dtype=float) - arm.x(q)
    return q if float(np.max(np.abs(r))) <= 1e3 * tol * scale else None


# The least-distance iteration of `nearest_solution`: its steps, then the same with half steps;
# its other starts: q0 moved by this much along each joint, both ways.
NEAREST_ITERATIONS = (200, 400)
NEAREST_SPREAD = 0.5


def nearest_solution(arm: Arm, target, q0, tol: float = 1e-12):
    """The solution of x(q) = target nearest q0 (|q - q0| least), for a wide J, where the
    solutions form a family and Newton's point depends on its steps; None when Newton's method
    from q0 does not reach the target.

    The family may hold several points where q - q0 is normal to it (an elbow up and an elbow
    down): each is sought from Newton's point of q0 and of q0 moved by NEAREST_SPREAD along each
    joint both ways, and the nearest kept (an earlier one unless nearer by 1e-9)."""
    q_newton = newton(arm, target, q0, tol)
    if q_newton is None:
        return None
    q0 = np.asarray(q0, dtype=float)
    best, best_distance = None, math.inf
    moves = [np.zeros_like(q0)] + [sign * NEAREST_SPREAD * e for e in np.eye(q0.size) for sign in (1.0, -1.0)]
    for move in moves:
        q_start = q_newton if not move.any() else newton(arm, target, q0 + move, tol)
        q = None if q_start is None else _least_distance(arm, target, q0, q_start, tol)
        if q is not None and float(np.linalg.norm(q - q0)) < best_distance - 1e-9:
            best, best_distance = q, float(np.linalg.norm(q - q0))
    return q_newton if best is None else best


def _least_distance(arm: Arm, target, q0, q, tol: float):
    """From q on the solutions, the least-distance iteration (x linearised at q, the point of that
    linear set nearest q0): q <- q0 + J^+(q) (target - x(q) + J(q) (q - q0)); its fixed points
    are on the family with q - q0 normal to it (q - q0 = J^T lambda). Half steps when whole
    ones do not settle; None when neither does."""
    target = np.asarray(target, dtype=float)
    for iterations, share in zip(NEAREST_ITERATIONS, (1.0, 0.5)):
        p = q
        for _ in range(iterations):
            J = arm.J(p)
            p_next = q0 + np.linalg.lstsq(J, target - arm.x(p) + J @ (p - q0), rcond=None)[0]
            move = float(np.max(np.abs(p_next - p)))
            p = p + share * (p_next - p)
            if not np.all(np.isfinite(p)):
                break
            if move <= 1e-14 * max(1.0, float(np.max(np.abs(p)))):
                return newton(arm, target, p, tol)      # onto x(q) = target to `tol`
    return None


def joint_state(arm: Arm, q, xd, xdd):
    """(q_dot, q_ddot, smallest singular value of J) at q: q_dot = J^+ x_dot_d and q_ddot its
    time derivative (with the null-space part when J is wide, see the module's docstring)."""
    J = arm.J(q)
    sv = np.linalg.svd(J, compute_uv=False)
    Jp = np.linalg.pinv(J)
    qd = Jp @ xd
    qdd = Jp @ (xdd - arm.jdot_qdot(q, qd))
    m, n = J.shape
    if m < n and sv.size and sv[-1] > 0:
        lam = np.linalg.solve(J @ J.T, xd)            # q_dot = J^T lam
        qdd = qdd + (np.eye(n) - Jp @ J) @ (arm.J_dot(q, qd).T @ lam)
    return qd, qdd, float(sv[-1]) if sv.size else 0.0


def _min_norm_rates(arm: Arm, q, xd):
    """J^+ x_dot = J^T (J J^T)^-1 x_dot (J wide, of full rank along a path that is followed)."""
    J = arm.J(q)
    return J.T @ np.linalg.solve(J @ J.T, xd)


# Runge-Kutta sub-steps of the minimum-norm motion (J wide): each at most T / RK_STEPS_PER_T.
# Classical RK4's error is O(h^4): measured on a 3R arm against DOP853 at rtol 1e-13, the end
# configuration is off by 5e-12 rad with T/200, 3e-13 with T/800 (two sub-steps per sample).
RK_STEPS_PER_T = 800


def min_norm_step(arm: Arm, path: Path, timing: Timing, q, t0: float, t1: float, segment: int):
    """q at t1 on the motion q_dot = J^+(q) x_dot_d(t) through q at t0 (within one segment of the
    timing law): classical Runge-Kutta with sub-steps of at most T / RK_STEPS_PER_T."""
    q = np.asarray(q, dtype=float)
    span = t1 - t0
    if span == 0:
        return q
    count = max(1, int(math.ceil(abs(span) * RK_STEPS_PER_T / timing.T)))
    h = span / count

    def f(t, y):
        return _min_norm_rates(arm, y, task_state(path, timing, t, segment)[2])

    for step in range(count):
        t = t0 + step * h
        k1 = f(t, q)
        k2 = f(t + h / 2, q + h / 2 * k1)
        k3 = f(t + h / 2, q + h / 2 * k2)
        k4 = f(t + h, q + h * k3)
        q = q + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    return q


@dataclass
class Conversion:
    t: np.ndarray                  # (N,)
    segment: np.ndarray            # (N,) the timing segment of each sample
    s: np.ndarray
    x: np.ndarray                  # (m, N) desired task values, and rates / accelerations
    xd: np.ndarray
    xdd: np.ndarray
    q: np.ndarray                  # (n, N)
    qd: np.ndarray
    qdd: np.ndarray
    sigma: np.ndarray              # (N,) smallest singular value of J
    failure: dict | None = None    # {"kind": "unreachable" | "singular", "t", "x", "q"}
    extra: dict = field(default_factory=dict)


def task_state(path: Path, timing: Timing, t: float, segment: int | None = None):
    s, sd, sdd = timing.at(t, segment)
    x, d1, d2 = path.at(s)
    return s, x, d1 * sd, d2 * sd * sd + d1 * sdd


def _grid(timing: Timing, samples: int):
    ts, segs = [], []
    T = timing.T
    for k in range(len(timing.breaks) - 1):
        a, b = timing.breaks[k], timing.breaks[k + 1]
        count = max(3, int(round(samples * (b - a) / T)) + 1)
        for t in np.linspace(a, b, count):
            ts.append(float(t))
            segs.append(k)
    return np.array(ts), np.array(segs)


def singular_floor(scale: float, x_scale: float, sigma_tol: float = 1e-6) -> float:
    """The smallest singular value below which a configuration counts as singular: sigma_tol of
    |J|, and at least ten times what an exactly singular one shows once Newton has solved it.
    At a fold (an arm stretched or folded) x(q) is quadratic along the singular direction, so a
    residual r leaves q off by sqrt(2 r / k) there and sigma at about sqrt(2 r k), k ~ |J| the
    curvature: sqrt(2e-12 * 0.65) = 1.1e-6 on a 2R arm of reach 1, above 1e-6 |J| = 6.5e-7."""
    residual = NEWTON_TOL * max(1.0, x_scale)
    return max(sigma_tol * scale, 10.0 * math.sqrt(residual * scale))


def follow(arm: Arm, path: Path, timing: Timing, q_start, samples: int = 401,
           sigma_tol: float = 1e-6) -> Conversion:
    """The joint motion along the timed path, from the branch of ``q_start`` (which reaches
    the path's start). Stops at the first sample out of reach or at a singularity (the ends
    included: a singular start stops it at t = 0, with no sample kept)."""
    ts, segs = _grid(timing, samples)
    m, n = path.a.size, len(q_start)
    out = {k: [] for k in ("s", "x", "xd", "xdd", "q", "qd", "qdd", "sigma")}
    q_prev, qd_prev, t_prev, failure = np.asarray(q_start, dtype=float), np.zeros(n), 0.0, None
    scale = max(float(np.linalg.norm(arm.J(q_prev), 2)), 1e-300)
    x_scale = float(np.max(np.abs(np.concatenate([path.a, path.b]))))
    if path.center is not None:          # an arc reaches |c| + r
        x_scale = max(x_scale, float(np.max(np.abs(path.center))) + path.radius)
    floor = singular_floor(scale, x_scale, sigma_tol)
    wide = path.a.size < n
    for t, seg in zip(ts, segs):
        s, x, xd, xdd = task_state(path, timing, t, seg)
        if wide:       # the minimum-norm motion, integrated (Newton alone drifts along the family)
            guess = min_norm_step(arm, path, timing, q_prev, t_prev, float(t), seg)
        else:
            guess = q_prev + qd_prev * (t - t_prev)
        q = newton(arm, x, guess)
        if q is None:
            failure = _leaving(arm, path, timing, t_prev, float(t), seg, q_prev)
            break
        qd, qdd, sig = joint_state(arm, q, xd, xdd)
        jump = float(np.max(np.abs(q - guess)))
        if sig < floor or (t > 0 and jump > 0.2):
            failure = {"kind": "singular", "t": float(t), "x": x.tolist(), "q": q.tolist()}
            if sig >= floor:     # J keeps its rank: the joints outrun the samples near a singularity
                failure.update(jump=jump, sigma=min(sig, out["sigma"][-1] if out["sigma"] else sig))
            break
        for k, v in zip(out, (s, x, xd, xdd, q, qd, qdd, sig)):
            out[k].append(v)
        q_prev, qd_prev, t_prev = q, qd, t
    N = len(out["s"])
    conv = Conversion(ts[:N], segs[:N], np.array(out["s"]),
                      *(np.array(out[k]).reshape(N, m).T for k in ("x", "xd", "xdd")),
                      *(np.array(out[k]).reshape(N, n).T for k in ("q", "qd", "qdd")),
                      np.array(out["sigma"]), failure)
    if failure is None:
        _singular_between(arm, path, timing, conv, floor)
    return conv


def state_at(arm: Arm, path: Path, timing: Timing, conv: Conversion, t: float, segment: int):
    """(q, q_dot, q_ddot, sigma) at any t of a segment, by Newton from the nearest sample."""
    k = int(np.argmin(np.abs(conv.t - t) + 1e9 * (conv.segment != segment)))
    _s, x, xd, xdd = task_state(path, timing, t, segment)
    if conv.q.shape[1] and x.size < conv.q.shape[0]:
        guess = min_norm_step(arm, path, timing, conv.q[:, k], float(conv.t[k]), float(t), segment)
    else:
        guess = conv.q[:, k] + conv.qd[:, k] * (t - conv.t[k])
    q = newton(arm, x, guess)
    if q is None:
        q = conv.q[:, k]
    qd, qdd, sig = joint_state(arm, q, xd, xdd)
    return q, qd, qdd, sig


def _refine(fun, conv: Conversion, k: int, sign: float = 1.0):
    """max of sign*fun(t, segment) near sample k, within its segment: (value, t)."""
    from robosolve.core.minimize import minimize_bounded

    seg = conv.segment[k]
    idx = np.nonzero(conv.segment == seg)[0]
    lo = conv.t[max(k - 1, idx[0])]
    hi = conv.t[min(k + 1, idx[-1])]
    best = (sign * fun(conv.t[k], seg), float(conv.t[k]))
    if hi > lo:
        res = minimize_bounded(lambda tt: -sign * fun(tt, seg), (lo, hi), xatol=1e-12 * max(1.0, conv.t[-1]))
        if -res.fun > best[0]:
            best = (float(-res.fun), float(res.x))
    return best


def extremes(arm: Arm, path: Path, timing: Timing, conv: Conversion):
    """max |q_dot_i|, max |q_ddot_i| over [0, T] (refined between samples) and min sigma:
    (vel (n,), acc (n,), (sigma_min, t))."""
    n = conv.q.shape[0]
    vel, acc = np.zeros(n), np.zeros(n)
    for i in range(n):
        for arr, out, which in ((conv.qd, vel, 1), (conv.qdd, acc, 2)):
            k = int(np.argmax(np.abs(arr[i])))
            out[i] = _refine(lambda tt, sg, i=i, w=which: abs(state_at(arm, path, timing, conv, tt, sg)[w][i]),
                             conv, k)[0]
    sig = conv.sigma
    cands = [_refine(lambda tt, sg: state_at(arm, path, timing, conv, tt, sg)[3], conv, k, sign=-1.0)
             for k in _near_bottom_minima(sig)]
    # dips within the conversion's error of the lowest tie: the first is reported (core/extremes.py)
    smin, tmin = first_of_ties(cands, tie_tolerance(float(np.max(sig)), CONVERSION_RTOL))
    return vel, acc, (-smin, tmin)


# the conversion's relative error on q (Newton to 1e-12; the minimum-norm motion's RK4 5e-12 rad)
CONVERSION_RTOL = 1e-11


def _near_bottom_minima(vals: np.ndarray, within: float = 1e-2, keep: int = 12) -> list[int]:
    """Indices, in time order, of the local minima of the samples (ends included) within
    ``within`` of the lowest, relative to the range: the earliest and the lowest, ``keep`` in all."""
    m = vals.size
    if m <= 2:
        return [int(np.argmin(vals))]
    inner = np.nonzero((vals[1:-1] <= vals[:-2]) & (vals[1:-1] <= vals[2:]))[0] + 1
    idx = np.concatenate([[0], inner, [m - 1]])
    low, span = float(vals.min()), float(vals.max() - vals.min())
    near = [int(k) for k in idx if vals[k] <= low + within * max(span, abs(low))]
    lowest = sorted(near, key=lambda k: vals[k])[:keep - keep // 4]
    return sorted(set(lowest) | set(near[:keep // 4]))


def _singular_between(arm, path, timing, conv, tol):
    """A singular configuration between samples (sigma dips to 0 at a local minimum)."""
    sig = conv.sigma
    for k in range(1, sig.size - 1):
        if sig[k] <= sig[k - 1] and sig[k] <= sig[k + 1] and conv.segment[k - 1] == conv.segment[k + 1]:
            val, t = _refine(lambda tt, sg: state_at(arm, path, timing, conv, tt, sg)[3], conv, k, sign=-1.0)
            if -val < tol:
                _s, x, _xd, _xdd = task_state(path, timing, t, conv.segment[k])
                conv.failure = {"kind": "singular", "t": t, "x": x.tolist(),
                                "q": state_at(arm, path, timing, conv, t, conv.segment[k])[0].tolist()}
                return


def _leaving(arm, path, timing, t_in: float, t_out: float, seg: int, q_in):
    """Where the path leaves the reach, by bisection between a reached and an unreached instant."""
    q_last = np.asarray(q_in, dtype=float)
    for _ in range(40):
        mid = 0.5 * (t_in + t_out)
        q = newton(arm, task_state(path, timing, mid, seg)[1], q_last)
        if q is None:
            t_out = mid
        else:
            t_in, q_last = mid, q
    x = task_state(path, timing, t_out, seg)[1]
    return {"kind": "unreachable", "t": float(t_out), "x": x.tolist(), "q": q_last.tolist()}
