"""Where expressions are compared: seeded sample points, and fast numeric evaluation.

grading.md: joints in their limits, else in (−π, π]; rates and accelerations in [−2, 2];
actuators in [−5, 5]; `t` in [0, T]; each parameter at its value times a factor in
[0.8, 1.25] (null parameters in [0.5, 2]); at least two points keep every parameter at
its value and at least two move them all. We take 8 of each. Each symbol's values come
from its own `random.Random(seed string)` (seeded through SHA-512, so the points do not
depend on PYTHONHASHSEED, nor on which other symbols an answer happens to use).
Evaluation is one `lambdify` (numpy) per tree; a point where the expected value is not
finite is dropped.
"""

from __future__ import annotations

import math
import random
import warnings
from dataclasses import dataclass

import numpy as np
import sympy as sp

from robosolve.grading.values import map_leaves

FIXED_POINTS = 8                   # parameters at their values
MOVED_POINTS = 8                   # every parameter moved
RATE_RANGE = (-2.0, 2.0)
ACTUATOR_RANGE = (-5.0, 5.0)
FACTOR_RANGE = (0.8, 1.25)
NULL_RANGE = (0.5, 2.0)
DEFAULT_RANGE = (-math.pi, math.pi)


@dataclass
class SymbolRoles:
    """What each symbol of a question stands for, and the range it is sampled in."""

    parameters: dict               # Symbol -> float value at the question (None: null parameter)
    joints: dict                   # Symbol -> (lo, hi)
    rates: set
    actuators: set
    t_symbol: object = None
    t_range: tuple = (0.0, 1.0)

    def values(self, symbol, seed: str) -> np.ndarray:
        rng = random.Random(f"{seed}/{symbol.name}")
        n = FIXED_POINTS + MOVED_POINTS

        def uniform(lo, hi, count=n):
            return [rng.uniform(lo, hi) for _ in range(count)]

        if symbol in self.parameters:
            v = self.parameters[symbol]
            if v is None:
                return np.array(uniform(*NULL_RANGE))
            return np.array([v] * FIXED_POINTS + [v * f for f in uniform(*FACTOR_RANGE, MOVED_POINTS)])
        if symbol in self.joints:
            lo, hi = self.joints[symbol]
            return np.array(uniform(lo, hi))
        if symbol in self.rates:
            return np.array(uniform(*RATE_RANGE))
        if symbol in self.actuators:
            return np.array(uniform(*ACTUATOR_RANGE))
        if symbol == self.t_symbol:
            return np.array(uniform(*self.t_range))
        return np.array(uniform(*DEFAULT_RANGE))


@dataclass
class Sampling:
    symbols: tuple                  # sorted by name
    columns: dict                   # Symbol -> np.ndarray of its values at the points
    fixed: np.ndarray               # bool mask: the points that keep the parameters at their values

    @property
    def size(self) -> int:
        return len(self.fixed)


def sample(symbols, roles: SymbolRoles, seed: str) -> Sampling:
    ordered = tuple(sorted(symbols, key=lambda s: s.name))
    columns = {s: roles.values(s, seed) for s in ordered}
    fixed = np.array([True] * FIXED_POINTS + [False] * MOVED_POINTS)
    return Sampling(ordered, columns, fixed)


def single_point() -> Sampling:
    """The 'points' of a numeric comparison: one, with no symbol."""
    return Sampling((), {}, np.array([True]))


# -- evaluation -------------------------------------------------------------
def _is_number(x) -> bool:
    """A leaf the comparison evaluates: an expression or a number (not a flag)."""
    return isinstance(x, (sp.Basic, float, int)) and not isinstance(x, bool)


def _as_real(x, n: int) -> np.ndarray:
    a = np.asarray(x)
    if a.dtype == object:
        a = np.array([complex(v) for v in np.broadcast_to(a, (n,))])
    if np.iscomplexobj(a):
        a = np.where(np.abs(a.imag) <= 1e-9 * (1 + np.abs(a.real)), a.real, np.nan)
    return np.broadcast_to(a.astype(float), (n,)).copy()


def _constant(e) -> float:
    if isinstance(e, (float, int)):
        return float(e)
    if isinstance(e, sp.Number):
        return float(e)
    try:
        c = complex(sp.N(e, 17))
    except (TypeError, ValueError):
        return math.nan
    return c.real if abs(c.imag) <= 1e-9 * (1 + abs(c.real)) else math.nan


def evaluate(tree, sampling: Sampling):
    """The tree with every expression replaced by its values at the points (np arrays)."""
    exprs: list = []
    map_leaves(tree, exprs.append, _is_number)
    n = sampling.size
    out = [None] * len(exprs)
    symbolic = [i for i, e in enumerate(exprs) if isinstance(e, sp.Basic) and e.free_symbols]
    for i, e in enumerate(exprs):
        if i not in symbolic:
            out[i] = np.full(n, _constant(e))
    if symbolic:
        memo: dict = {}
        slow = []
        for i in symbolic:
            try:
                with np.errstate(all="ignore"), warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    out[i] = _as_real(tree_values(exprs[i], sampling.columns, memo), n)
            except Exception:  # noqa: BLE001 - a node it does not know: lambdify below
                slow.append(i)
        symbolic = slow
    if symbolic:
        args = [sampling.columns[s] for s in sampling.symbols]
        try:
            f = sp.lambdify(sampling.symbols, [exprs[i] for i in symbolic], modules="numpy")
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore")
                results = f(*args)
            for i, r in zip(symbolic, results):
                out[i] = _as_real(r, n)
        except Exception:  # noqa: BLE001 - a function numpy lacks: evaluate point by point
            for i in symbolic:
                out[i] = _pointwise(exprs[i], sampling)
    values = iter(out)
    return map_leaves(tree, lambda _: next(values), _is_number)


def values_at(expr, columns: dict, n: int) -> np.ndarray | None:
    """The values of one expression at n points (`columns`: each symbol's values), by the tree
    walk or else one `lambdify`; None when neither can (no slow point-by-point fallback: the
    callers evaluate at thousands of points) or a symbol has no column."""
    if not isinstance(expr, sp.Basic):
        return np.full(n, float(expr))
    if not expr.free_symbols <= set(columns):
        return None
    with np.errstate(all="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return _as_real(tree_values(expr, columns, {}), n)
        except Exception:  # noqa: BLE001 - a node it does not know: lambdify below
            pass
        symbols = sorted(expr.free_symbols, key=lambda s: s.name)
        try:
            return _as_real(sp.lambdify(symbols, expr, modules="numpy")(*(columns[s] for s in symbols)), n)
        except Exception:  # noqa: BLE001 - a function numpy lacks
            return None


class _Unsupported(Exception):
    """An expression node the direct evaluator does not know (lambdify takes over)."""


_UNARY = {sp.sin: np.sin, sp.cos: np.cos, sp.tan: np.tan, sp.asin: np.arcsin, sp.acos: np.arccos,
          sp.atan: np.arctan, sp.exp: np.exp, sp.log: np.log, sp.Abs: np.abs,
          sp.sinh: np.sinh, sp.cosh: np.cosh, sp.tanh: np.tanh, sp.sign: np.sign}


def tree_values(e, columns: dict, memo: dict):
    """Values of a sympy expression at the points, by walking its tree with numpy.

    Much quicker than `lambdify` for the small expressions of answers (no code is printed
    and compiled); shared subexpressions are evaluated once (`memo`).
    """
    hit = memo.get(e)
    if hit is not None:
        return hit
    if e.is_Symbol:
        if e not in columns:
            raise _Unsupported(e)
        v = columns[e]
    elif e.is_Number or e is sp.pi or e is sp.E:
        v = complex(e) if e.is_Number and not e.is_real else float(e)
    elif e.is_Add:
        v = sum(tree_values(a, columns, memo) for a in e.args)
    elif e.is_Mul:
        v = 1.0
        for a in e.args:
            v = v * tree_values(a, columns, memo)
    elif e.is_Pow:
        base, ex = e.args
        b = tree_values(base, columns, memo)
        if ex == sp.S.Half:
            v = np.sqrt(b)
        elif ex.is_Integer:
            v = np.asarray(b, dtype=float) ** int(ex) if int(ex) < 0 else b ** int(ex)
        else:
            v = np.power(b, tree_values(ex, columns, memo))
    elif e.func in _UNARY:
        v = _UNARY[e.func](tree_values(e.args[0], columns, memo))
    elif e.func == sp.atan2:
        v = np.arctan2(tree_values(e.args[0], columns, memo), tree_values(e.args[1], columns, memo))
    else:
        raise _Unsupported(e.func)
    memo[e] = v
    return v


def _pointwise(expr, sampling: Sampling) -> np.ndarray:
    vals = []
    for k in range(sampling.size):
        subs = {s: sp.Float(sampling.columns[s][k]) for s in sampling.symbols}
        try:
            vals.append(_constant(expr.xreplace(subs)))
        except Exception:  # noqa: BLE001
            vals.append(math.nan)
    return np.array(vals, dtype=float)
