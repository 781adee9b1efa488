"""Every solution of f(q) = 0 by deterministic multi-start Levenberg-Marquardt.

The starts are a full grid for up to three unknowns and a fixed Halton set
beyond; all starts iterate together (numpy batches; a start leaves the batch once
converged), the converged ones are refined one by one with Newton/Gauss-Newton to machine precision, wrapped,
deduplicated and verified.  A second pass deflates the solutions already found
so that starts are pushed away from them towards the ones still missing (the IK
engine skips it when a closed form's verified solutions confirm the set).
Revolute angles are wrapped into (-pi, pi]; an equation flagged `angular`
(a sum of angles = an orientation) is compared modulo 2 pi.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from robosolve.core.angles import wrap_angle  # noqa: F401  (the one rule; ik.engine imports it here)
from robosolve.core.numpy_code import numpy_modules

TWO_PI = 2.0 * math.pi
RESIDUAL_TOL = 1e-9     # a solution must reproduce the target to this (FK check)
DEDUPE_TOL = 1e-6       # two solutions closer than this (max norm) are the same


def _clean(v: float) -> float:
    return 0.0 if abs(v) < 1e-15 else v + 0.0


def wrap_array(a):
    return np.pi - np.mod(np.pi - a, TWO_PI)


@dataclass
class NumericSystem:
    """f: R^n -> R^m and its Jacobian, evaluated on batches of configurations.

    `f(Q)` takes Q of shape (N, n) and returns (N, m); `jac(Q)` returns (N, m, n).
    `revolute[i]` says which unknowns are angles; `angular[k]` which equations
    are compared modulo 2 pi.
    """

    f: object
    jac: object
    revolute: list[bool]
    angular: list[bool]
    scale: float = 1.0          # typical length, for the prismatic start box
    # the plain search's end points by start set (`solve_all` without and then with deflation
    # runs the same deterministic batch first: the second time it is read back)
    batches: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def tol(self) -> float:
        """Residual accepted as a solution: 1e-9, relative for problems with large numbers."""
        return RESIDUAL_TOL * max(1.0, self.scale * 1e-3)

    def residual(self, Q):
        r = self.f(Q)
        if any(self.angular):
            idx = [k for k, a in enumerate(self.angular) if a]
            r[:, idx] = wrap_array(r[:, idx])
        return r


def lambdify_system(exprs, q_syms, revolute, angular=None, scale=1.0) -> NumericSystem:
    """Build a `NumericSystem` from sympy expressions (every other symbol substituted)."""
    import sympy as sp

    exprs = [sp.sympify(e) for e in exprs]
    m, n = len(exprs), len(q_syms)
    jac = sp.Matrix(exprs).jacobian(list(q_syms))
    f_raw = sp.lambdify(list(q_syms), exprs, modules=numpy_modules(), cse=True)
    j_raw = sp.lambdify(list(q_syms), list(jac), modules=numpy_modules(), cse=True)

    def f(Q):
        Q = np.atleast_2d(np.asarray(Q, dtype=float))
        cols = f_raw(*Q.T)
        return np.stack([np.broadcast_to(np.asarray(c, dtype=float), (Q.shape[0],)) for c in cols], axis=1)

    def jf(Q):
        Q = np.atleast_2d(np.asarray(Q, dtype=float))
        cols = j_raw(*Q.T)
        J = np.stack([np.broadcast_to(np.asarray(c, dtype=float), (Q.shape[0],)) for c in cols], axis=1)
        return J.reshape(Q.shape[0], m, n)

    return NumericSystem(f, jf, list(revolute), list(angular or [False] * m), float(scale))


# ---------------------------------------------------------------------------
# starts

def _halton(count: int, dim: int) -> np.ndarray:
    primes = [2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37][:dim]
    out = np.empty((count, dim))
    for j, b in enumerate(primes):
        for i in range(count):
            f, r, k = 1.0, 0.0, i + 1
            while k:
                f /= b
                r += f * (k % b)
                k //= b
            out[i, j] = r
    return out


def start_points(boxes: list[tuple[float, float]], budget: int = 4096) -> np.ndarray:
    """Deterministic starts in the product of `boxes`: a grid (n <= 3) or Halton points."""
    n = len(boxes)
    if n == 0:
        return np.zeros((1, 0))
    per = int(round(budget ** (1.0 / n)))
    if n <= 3 and per >= 4:
        axes = []
        for lo, hi in boxes:
            # cell centres: never exactly on a symmetric singular configuration
            axes.append(lo + (hi - lo) * (np.arange(per) + 0.5 + 0.0137) / per)
        mesh = np.meshgrid(*axes, indexing="ij")
        return np.stack([g.ravel() for g in mesh], axis=1)
    u = _halton(budget, n)
    lo = np.array([b[0] for b in boxes])
    hi = np.array([b[1] for b in boxes])
    return lo + u * (hi - lo)


# ---------------------------------------------------------------------------
# iterations

def _lm_batch(system: NumericSystem, Q, iters=80, deflate=None):
    """Batched Levenberg-Marquardt on |r(Q)|^2 (optionally deflated).

    A start whose cost is below 1e-28 has converged and leaves the batch: the rest iterate on
    their own (each row's arithmetic is independent of the others, so the rows still moving get
    the same steps as in the full batch; the converged ones would only move by rounding)."""
    # a target far beyond the reach (1e150) overflows JᵀJ: such steps are made finite and refused
    # below, so numpy's warnings (on stderr, under the CLI's output) would say nothing of use
    with np.errstate(over="ignore", invalid="ignore"):
        return _lm_iterations(system, Q, iters, deflate)


def _lm_iterations(system: NumericSystem, Q, iters, deflate):
    N, n = Q.shape
    Q = np.array(Q, dtype=float)
    lam = np.full(N, 1e-3)
    rev = np.array(system.revolute, dtype=bool)

    def eval_r(Q):
        r = system.residual(Q)
        if deflate is not None and len(deflate):
            d2 = ((Q[:, None, :] - deflate[None, :, :]) ** 2)
            d2 = np.where(rev[None, None, :], (2 - 2 * np.cos(Q[:, None, :] - deflate[None, :, :])), d2)
            mult = np.prod(1.0 / d2.sum(axis=2) + 1.0, axis=1)
            return r * mult[:, None]
        return r

    r = eval_r(Q)
    cost = np.einsum("ij,ij->i", r, r)
    eye = np.eye(n)
    live = np.flatnonzero(~(cost < 1e-28))
    for _ in range(iters):
        if not live.size:
            break
        Ql, rl, cl, laml = Q[live], r[live], cost[live], lam[live]
        if deflate is not None and len(deflate):
            # numerical Jacobian of the deflated residual (cheap: n is small)
            h = 1e-7
            J = np.empty((live.size, rl.shape[1], n))
            for k in range(n):
                Qh = Ql.copy()
                Qh[:, k] += h
                J[:, :, k] = (eval_r(Qh) - rl) / h
        else:
            J = system.jac(Ql)
        JT = np.transpose(J, (0, 2, 1))
        A = JT @ J
        g = np.einsum("imn,im->in", J, rl)
        diag = np.einsum("ijj->ij", A)
        Ad = A + laml[:, None, None] * (eye[None] * (diag[:, None, :] + 1e-9))
        try:
            step = -np.linalg.solve(Ad, g[:, :, None])[:, :, 0]
        except np.linalg.LinAlgError:
            step = -np.einsum("inm,im->in", np.linalg.pinv(Ad), g)
        step = np.nan_to_num(step, nan=0.0, posinf=0.0, neginf=0.0)
        # cap the step so the iteration stays in the region of the starts
        norm = np.linalg.norm(step, axis=1)
        big = norm > 1.0
        step[big] *= (1.0 / norm[big])[:, None]
        Qn = Ql + step
        Qn[:, rev] = wrap_array(Qn[:, rev])
        rn = eval_r(Qn)
        cn = np.einsum("ij,ij->i", rn, rn)
        ok = np.isfinite(cn) & (cn < cl)
        Q[live] = np.where(ok[:, None], Qn, Ql)
        r[live] = np.where(ok[:, None], rn, rl)
        cost[live] = np.where(ok, cn, cl)
        lam[live] = np.where(ok, laml / 3.0, np.minimum(laml * 4.0, 1e12))
        live = live[~(cost[live] < 1e-28)]
    return Q, cost


def refine(system: NumericSystem, q, iters=40):
    """Gauss-Newton (minimum-norm steps) to machine precision; returns (q, |r|_inf)."""
    q = np.array(q, dtype=float)
    rev = np.array(system.revolute, dtype=bool)
    best_q, best = q.copy(), np.inf
    for _ in range(iters):
        r = system.residual(q[None])[0]
        nr = float(np.max(np.abs(r))) if r.size else 0.0
        if nr < best:
            best_q, best = q.copy(), nr
        if nr == 0.0:
            break
        J = system.jac(q[None])[0]
        step = np.linalg.lstsq(J, -r, rcond=1e-13)[0]
        if not np.all(np.isfinite(step)):
            break
        q = q + step
        q[rev] = wrap_array(q[rev])
        if np.max(np.abs(step)) < 1e-16:
            break
    return best_q, best


# ---------------------------------------------------------------------------
# results

@dataclass
class NumericSolution:
    q: list[float]
    residual: float
    rank_deficient: bool = False     # Jacobian loses rank here (boundary / singular)


@dataclass
class NumericResult:
    solutions: list[NumericSolution] = field(default_factory=list)
    family: bool = False             # a continuum of solutions was found
    family_free: list[int] = field(default_factory=list)   # joints that vary along it
    best_residual: float = math.inf  # smallest residual reached (unreachable targets)
    best_q: list[float] | None = None


def _close(a, b, rev, tol=DEDUPE_TOL):
    d = np.abs(np.asarray(a) - np.asarray(b))
    d = np.where(rev, np.minimum(d, TWO_PI - d), d)
    return bool(np.all(d <= tol * np.maximum(1.0, np.abs(np.asarray(a)))))


def _close_to_any(a, found: list, rev, tol=DEDUPE_TOL) -> bool:
    """any(_close(a, f, rev, tol) for f in found), in one numpy pass over the stacked
    solutions (the same element-wise arithmetic: thousands of start points are checked
    against the solutions found so far)."""
    if not found:
        return False
    a = np.asarray(a)
    d = np.abs(a - np.asarray(found))
    d = np.where(rev, np.minimum(d, TWO_PI - d), d)
    return bool(np.any(np.all(d <= tol * np.maximum(1.0, np.abs(a)), axis=1)))


def _rows_near(Q, f, rev, tol=1e-4):
    """Rows of Q within tol of the solution f: _close(row, f) for every row, in one pass."""
    d = np.abs(Q - f)
    d = np.where(rev, np.minimum(d, TWO_PI - d), d)
    return np.all(d <= tol * np.maximum(1.0, np.abs(Q)), axis=1)


def sort_solutions(sols, get=lambda s: s, tol=1e-9):
    """Lexicographic sort in joint order with values within `tol` equal (stable)."""
    import functools

    def cmp(a, b):
        qa, qb = get(a), get(b)
        for x, y in zip(qa, qb):
            if abs(x - y) > tol:
                return -1 if x < y else 1
        return 0

    return sorted(sols, key=functools.cmp_to_key(cmp))


def _is_family(system: NumericSystem, q, delta=1e-3):
    """True when solutions continue away from q (a continuum), with the moving joints."""
    q = np.asarray(q, dtype=float)
    J = system.jac(q[None])[0]
    n = q.size
    if n == 0:
        return False, []
    _, s, vt = np.linalg.svd(J, full_matrices=True)
    smax = s[0] if s.size else 0.0
    rank = int(np.sum(s > 1e-8 * max(smax, 1e-300)))
    if rank >= n:
        return False, []
    for v in vt[rank:]:
        # solve f(q') = 0 with v.(q' - q) = delta from q + delta v
        p = q + delta * v
        for _ in range(60):
            r = np.concatenate([system.residual(p[None])[0], [v @ (p - q) - delta]])
            Jp = np.vstack([system.jac(p[None])[0], v[None]])
            step = np.linalg.lstsq(Jp, -r, rcond=1e-13)[0]
            p = p + step
            if np.max(np.abs(step)) < 1e-15:
                break
        r = system.residual(p[None])[0]
        if np.max(np.abs(r)) < 1e-12 * max(1.0, system.scale) and abs(v @ (p - q) - delta) < 1e-9:
            free = [i for i in range(n) if abs(v[i]) > 1e-6]
            return True, free
    return False, []


def polish_singular(system: NumericSystem, q, iters=30):
    """At a double root (square J singular) Newton is only linear: solve f = 0 and det J = 0."""
    q = np.array(q, dtype=float)
    n = q.size

    def g(p):
        J = system.jac(p[None])[0]
        if J.shape[0] != n:
            return None
        return np.concatenate([system.residual(p[None])[0], [np.linalg.det(J)]])

    r = g(q)
    if r is None:
        return q
    best, best_n = q.copy(), np.max(np.abs(r))
    for _ in range(iters):
        G = np.empty((r.size, n))
        for k in range(n):
            h = 1e-7 * max(1.0, abs(q[k]))
            qh = q.copy()
            qh[k] += h
            G[:, k] = (g(qh) - r) / h
        G[:-1] = system.jac(q[None])[0]
        step = np.linalg.lstsq(G, -r, rcond=1e-13)[0]
        q = q + step
        r = g(q)
        nr = np.max(np.abs(r))
        if nr < best_n:
            best, best_n = q.copy(), nr
        if np.max(np.abs(step)) < 1e-15:
            break
    f_best = np.max(np.abs(system.residual(best[None])[0]))
    return best if f_best <= system.tol else np.asarray(q)


DEFAULT_BUDGET = {1: 64, 2: 576, 3: 4096}


def _plain_batch(system: NumericSystem, starts):
    """`_lm_batch` from these starts, kept on the system: `solve_all` without and then with
    deflation runs the same deterministic batch first, and the second time reads it back."""
    key = (starts.shape, starts.tobytes())
    if key not in system.batches:
        system.batches[key] = _lm_batch(system, starts)
    return system.batches[key]


def solve_all(system: NumericSystem, boxes, budget: int | None = None, deflation: bool = True) -> NumericResult:
    """Every isolated solution of the system reached from starts in `boxes`."""
    n = len(boxes)
    if budget is None:
        budget = DEFAULT_BUDGET.get(n, 4096)
    rev = np.array(system.revolute, dtype=bool)
    res = NumericResult()
    if n == 0:
        r = system.residual(np.zeros((1, 0)))[0]
        nr = float(np.max(np.abs(r))) if r.size else 0.0
        res.best_residual = nr
        if nr < system.tol:
            res.solutions.append(NumericSolution([], nr))
        return res
    starts = start_points(boxes, budget)
    found: list[np.ndarray] = []
    residuals: list[float] = []

    def harvest(Q, cost):
        order = np.argsort(cost, kind="stable")
        covered = np.zeros(len(Q), dtype=bool)     # start i ended near a solution found
        for f in found:
            covered |= _rows_near(Q, f, rev)
        for i in order:
            if not np.isfinite(cost[i]):
                continue
            if cost[i] > 1e-8:
                if cost[i] < res.best_residual ** 2 or res.best_q is None:
                    qq, nr = refine(system, Q[i])
                    if nr < res.best_residual:
                        res.best_residual, res.best_q = nr, [float(x) for x in qq]
                continue
            if covered[i]:
                continue
            qq, nr = refine(system, Q[i])
            if nr < res.best_residual:
                res.best_residual, res.best_q = nr, [float(x) for x in qq]
            if nr > system.tol:
                continue
            if _close_to_any(qq, found, rev):
                continue
            found.append(qq)
            covered |= _rows_near(Q, qq, rev)
            residuals.append(nr)
            if len(found) > 64:
                return True
        return False

    Q, cost = _plain_batch(system, starts)
    overflow = harvest(Q, cost)
    if deflation and found and not overflow:
        sub = starts[:: max(1, len(starts) // 512)]
        Q2, _ = _lm_batch(system, sub, iters=60, deflate=np.array(found))
        # polish the deflated end points on the true system
        Q3, cost3 = _lm_batch(system, Q2, iters=30)
        overflow = harvest(Q3, cost3)

    # continua: a solution from which solutions continue
    for qq in found[:8]:
        fam, free = _is_family(system, qq)
        if fam:
            res.family, res.family_free = True, free
            break
    if overflow and not res.family:
        res.family = True

    sols = []
    for qq, nr in zip(found, residuals):
        J = system.jac(qq[None])[0]
        s = np.linalg.svd(J, compute_uv=False)
        deficient = s.size < qq.size or (s.size > 0 and s[-1] < 1e-6 * max(s[0], 1e-300))
        if deficient and not res.family and J.shape[0] == J.shape[1]:
            p = polish_singular(system, qq)
            rp = float(np.max(np.abs(system.residual(p[None])[0])))
            if rp <= system.tol:
                qq, nr = p, rp
        sols.append(NumericSolution([wrap_angle(float(v)) if rv else _clean(float(v)) for v, rv in zip(qq, rev)],
                                    float(nr), bool(deficient)))
    res.solutions = sort_solutions(sols, get=lambda s: s.q)
    return res
