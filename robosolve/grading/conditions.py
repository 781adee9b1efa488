"""Singular conditions written as equations: the joint values (and conditions) they stand for.

An equation whose left side is a product is first the conditions of its factors (det J = 0:
a factor is zero; `factor_conditions`).

grading.md: a singular condition is compared by its values. An equation that gives a joint a
value linearly (`theta2 = pi`) is read as that mapping already (values.py); one that does not
(`sin(theta2) = 0`, `cos(theta3) = 0`, `L1*L2*sin(theta2) = 0`, `sin(theta2)^2 = 0`) stands for
every root of it in (−π, π]: `sin(theta2) = 0` is the two conditions {theta2: 0} and
{theta2: pi}, and `sin(theta3) = 0, theta5 = 0` the two {theta3: 0, theta5: 0} and
{theta3: pi, theta5: 0}. The roots are found numerically at every point the answer is
compared at (the parameters at their values, and moved): on a grid of (−π, π], refined by
bisection where the equation changes sign and by golden sections where it touches zero (an
even root); a pole (tan) is no root. Each expected condition whose values are roots at those
points is matched by one given condition, valued at the nearest roots; the other roots are
conditions given too many. Equations in several joints, in a prismatic joint, with no root or
true for every value stay equations (compared up to a constant factor), and so does one whose
joints are those of an equation the reference itself gives.
"""

from __future__ import annotations

import math

import numpy as np

import sympy as sp

from robosolve.grading.points import values_at
from robosolve.grading.values import Equation

GRID = 3600                       # grid steps over (−π, π]: 0.1° apart
BISECTIONS = 60
GOLDEN_STEPS = 80
ROOT = 1e-9                       # |residual| at a refined root, relative to its typical size
CANDIDATE = 1e-3                  # |residual| at a grid minimum worth refining (an even root)
SAME_ROOT = 1e-7                  # roots closer than this (rad) are one
FACTOR_NODES = 400                # above (expression nodes): an equation is not split into its factors
FACTOR_SECONDS = 10.0             # safety net of CPU time around a factorisation within FACTOR_NODES


def factor_conditions(given: list, joints: dict, revolute) -> list:
    """The set with each condition written as one equation whose left side is a product (det J
    = 0: a factor is zero) replaced by the conditions of its factors: `sin(q3)*(a2*cos(q2) + …)
    = 0` is `sin(q3) = 0` and `a2*cos(q2) + … = 0`; `d^2*cos(theta2) = 0` is `d = 0` and
    `cos(theta2) = 0`. Factors free of the joints (L1*L2) are dropped; a factor linear in a
    prismatic joint is the mapping it gives; an equation of one factor stays as written."""
    out = []
    for el in given:
        parts = _factors(el[0], joints, revolute) if _is_equations(el) and len(el) == 1 else None
        out += parts if parts else [el]
    return out


def _factors(eq, joints: dict, revolute):
    from robosolve.core.simplify import determinant_factors, expression_nodes
    from robosolve.core.timing import time_limit
    from robosolve.errors import SymbolicTimeout

    r = sp.sympify(eq.residual)
    if not r.free_symbols & set(joints) or expression_nodes(r) > FACTOR_NODES:
        return None
    try:
        with time_limit(FACTOR_SECONDS):    # a safety net: the node count decides
            factors = [f for f in determinant_factors(r) if f.free_symbols & set(joints)]
    except (SymbolicTimeout, sp.PolynomialError, ValueError, TypeError):
        return None
    out = []
    for f in factors:
        used = [q for q in joints if f.has(q)]
        value = _linear_root(f, used[0]) if len(used) == 1 and joints[used[0]] not in revolute else None
        out.append({joints[used[0]]: value} if value is not None else (Equation(f, f"{f} = 0"),))
    # one factor stays the equation as written, unless it is in fewer joints (sin(q1 + q2)·cos q1
    # − cos(q1 + q2)·sin q1 is sin q2) or gives a prismatic joint its value (2*d = 1)
    fewer = len(factors) == 1 and set(factors[0].free_symbols & set(joints)) < set(r.free_symbols & set(joints))
    return out if len(factors) > 1 or fewer or (out and isinstance(out[0], dict)) else None


def _linear_root(f, q):
    try:
        poly = sp.Poly(f, q)
    except sp.PolynomialError:
        return None
    if poly.degree() != 1:
        return None
    a, b = poly.all_coeffs()
    return None if a.has(q) or b.has(q) else sp.expand(-b / a)


def one_joint_conditions(given: list, joints: dict, revolute, expected: list) -> tuple[list, list]:
    """(the set's other elements, its conditions of one revolute joint per equation): each
    condition (the element, its parts), a part (joint name, joint symbol, residual), the joints
    distinct. `joints`: symbol -> name; `expected`: the reference's elements (as read: the
    joints of its own equations stay equations)."""
    theirs = {frozenset(_joint_of(eq.residual, joints) or () for eq in el)
              for el in expected if _is_equations(el)}
    rest, conditions = [], []
    for el in given:
        parts = _condition(el, joints, revolute) if _is_equations(el) else None
        if parts is None or frozenset(name for name, _, _ in parts) in theirs:
            rest.append(el)
        else:
            conditions.append((el, parts))
    return rest, conditions


def _is_equations(el) -> bool:
    return isinstance(el, tuple) and bool(el) and all(isinstance(x, Equation) for x in el)


def _joint_of(residual, joints: dict):
    used = [q for q in joints if getattr(residual, "has", lambda _: False)(q)]
    return (joints[used[0]],) if len(used) == 1 else None


def _condition(el, joints, revolute):
    parts = []
    for eq in el:
        used = [q for q in joints if getattr(eq.residual, "has", lambda _: False)(q)]
        if len(used) != 1 or joints[used[0]] not in revolute:
            return None
        parts.append((joints[used[0]], used[0], eq.residual))
    return parts if len({name for name, _, _ in parts}) == len(parts) else None


def expand(parts, expected: list, columns: dict, n: int, close) -> list | None:
    """The given elements one condition stands for (evaluated: {joint: values at the n points}),
    or None when it is no set of roots (true everywhere, no value, or no root at all): it then
    stays an equation. `expected`: the reference's elements, evaluated; `columns`: the other
    symbols' values at the points; `close(given, expected, name)`: the comparison of one joint's
    values (grading's tolerance, at the points that count)."""
    roots = {name: roots_at(residual, q, columns, n) for name, q, residual in parts}
    if any(r is None for r in roots.values()):
        return None
    names = set(roots)
    counts = np.prod([[len(r) for r in roots[name]] for name in sorted(names)], axis=0)
    if not counts.any():
        return None
    out = []
    for el in expected:
        if isinstance(el, dict) and set(el) == names:
            nearest = {name: _nearest(roots[name], el[name]) for name in el}
            if all(close(nearest[name], el[name], name) for name in names):
                out.append(nearest)
    extra = int(counts.max()) - len(out)
    return out + [{name: np.full(n, math.nan) for name, _, _ in parts} for _ in range(max(extra, 0))]


def _nearest(roots: list, values) -> np.ndarray:
    """At each point, the root nearest the expected value (modulo 2π); nan where there is none."""
    out = np.full(len(roots), math.nan)
    for p, (r, v) in enumerate(zip(roots, np.broadcast_to(values, (len(roots),)))):
        if len(r) and np.isfinite(v):
            d = np.abs(np.mod(r - v + math.pi, 2 * math.pi) - math.pi)
            out[p] = r[int(np.argmin(d))]
    return out


def _values(residual, q, columns: dict, qs: np.ndarray, at: np.ndarray) -> np.ndarray:
    """The residual at joint values `qs`, each at point `at[i]` of the columns (nan where it
    cannot be evaluated)."""
    cols = {s: np.asarray(v)[at] for s, v in columns.items() if s != q}
    cols[q] = qs
    out = values_at(residual, cols, len(qs))
    return np.full(len(qs), math.nan) if out is None else out


def roots_at(residual, q, columns: dict, n: int) -> list | None:
    """The roots in (−π, π] of the residual as a function of q at each of the n points (a
    sorted array each), or None when it is true for every q at some point or has no value."""
    grid = -math.pi + 2 * math.pi * (np.arange(GRID) + 1) / GRID
    values = _values(residual, q, columns, np.tile(grid, n), np.repeat(np.arange(n), GRID)).reshape(n, GRID)
    size = np.nanmedian(np.abs(values), axis=1) if np.isfinite(values).any() else np.full(n, math.nan)
    if not np.all(np.isfinite(size)) or np.any(size <= 1e-12):
        return None               # no value there, or zero for (almost) every q: not a condition
    step = 2 * math.pi / GRID
    # sign changes, between grid points k and k + 1 (the last one and the first, around the circle)
    right = np.roll(values, -1, axis=1)
    p_s, k_s = np.nonzero((values * right < 0) & np.isfinite(values) & np.isfinite(right))
    lo = grid[k_s]
    roots_s = _bisect(residual, q, columns, lo, lo + step, p_s)
    # grid minima of |r| near zero (an even root, or a root on the grid itself)
    a = np.abs(values)
    p_t, k_t = np.nonzero((a <= np.roll(a, 1, axis=1)) & (a <= np.roll(a, -1, axis=1))
                          & (a <= CANDIDATE * size[:, None]))
    roots_t = _golden(residual, q, columns, grid[k_t] - step, grid[k_t] + step, p_t)
    found = [[] for _ in range(n)]
    for p, x in zip(np.concatenate([p_s, p_t]), np.concatenate([roots_s, roots_t])):
        found[int(p)].append(x)
    out = []
    for p, xs in enumerate(found):
        xs = [x for x in xs if np.isfinite(x)]
        if xs:
            r = np.abs(_values(residual, q, columns, np.array(xs), np.full(len(xs), p)))
            xs = [float(np.mod(x + math.pi, 2 * math.pi) - math.pi) for x, v in zip(xs, r) if v <= ROOT * size[p]]
            xs = [math.pi if x <= -math.pi + 1e-12 else x for x in xs]
        out.append(_distinct(xs))
    return out


def _distinct(xs: list) -> np.ndarray:
    out: list = []
    for x in sorted(xs):
        if not any(abs(math.remainder(x - y, 2 * math.pi)) <= SAME_ROOT for y in out):
            out.append(x)
    return np.array(out)


def _bisect(residual, q, columns, lo, hi, at) -> np.ndarray:
    if not len(lo):
        return np.array([])
    f_lo = _values(residual, q, columns, lo, at)
    for _ in range(BISECTIONS):
        mid = (lo + hi) / 2
        f_mid = _values(residual, q, columns, mid, at)
        left = np.sign(f_mid) == np.sign(f_lo)
        lo, f_lo = np.where(left, mid, lo), np.where(left, f_mid, f_lo)
        hi = np.where(left, hi, mid)
    return (lo + hi) / 2


def _golden(residual, q, columns, lo, hi, at) -> np.ndarray:
    """The minimum of |residual| in [lo, hi] for each bracket (golden sections)."""
    if not len(lo):
        return np.array([])
    ratio = (math.sqrt(5) - 1) / 2
    for _ in range(GOLDEN_STEPS):
        x1, x2 = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
        f1 = np.abs(_values(residual, q, columns, x1, at))
        f2 = np.abs(_values(residual, q, columns, x2, at))
        lower = f1 <= f2
        hi, lo = np.where(lower, x2, hi), np.where(lower, lo, x1)
    return (lo + hi) / 2
