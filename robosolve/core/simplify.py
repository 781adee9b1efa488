"""One simplification policy for every solver (stable goldens, bounded time).

`tidy` is the cheap default: trig products collapsed entry by entry
(c1*c2 - s1*s2 -> cos(theta1 + theta2)), never a blanket `simplify`.
"""

from __future__ import annotations

import sympy as sp
from sympy.simplify.fu import TR10i

from robosolve.core.timing import time_limit
from robosolve.errors import SymbolicTimeout


# Above this size trigsimp costs seconds and rarely pays: the entry is left as is.
MAX_TIDY_OPS = 300


_MEMO: dict = {}
_MEMO_SIZE = 20_000


def tidy(expr, seconds: float = 5.0):
    """trigsimp of one expression, or the expression unchanged past `seconds`
    (or when it is too large to be worth it). Memoised: chain products and
    points re-tidy the same entries many times."""
    expr = sp.sympify(expr)
    hit = _MEMO.get(expr)
    if hit is not None:
        return hit
    out, complete = _tidy(expr, seconds)
    if complete and len(_MEMO) < _MEMO_SIZE:
        _MEMO[expr] = out
        _MEMO[out] = out
    return out


def _tidy(expr, seconds: float):
    if expr.is_Atom or not expr.has(sp.sin, sp.cos):
        return (sp.expand(expr) if expr.is_Add or expr.is_Mul else expr), True
    if sp.count_ops(expr) > MAX_TIDY_OPS:
        return expr, True
    try:
        with time_limit(seconds) as token:
            expanded = sp.expand(expr)
            # Addition formulas first (c1 c2 - s1 s2 -> cos(q1 + q2)): fast, and it
            # leaves trigsimp, slow on long chains, little or nothing to do.
            collapsed = TR10i(expanded)
            if not _has_trig_products(collapsed):
                return collapsed, True
            return sp.trigsimp(collapsed), True
    except SymbolicTimeout as exc:
        if exc.token is not token:
            raise          # an enclosing step's time is up
        return expr, False


def _has_trig_products(expr) -> bool:
    """True when a product or power of sin/cos is left (something trigsimp may reduce)."""
    for node in sp.preorder_traversal(expr):
        if node.is_Pow and isinstance(node.base, (sp.sin, sp.cos)):
            return True
        if node.is_Mul and sum(1 for a in node.args if isinstance(a, (sp.sin, sp.cos))
                               or (a.is_Pow and isinstance(a.base, (sp.sin, sp.cos)))) > 1:
            return True
    return False


def tidy_matrix(m: sp.Matrix, seconds: float = 5.0) -> sp.Matrix:
    return m.applyfunc(lambda e: tidy(e, seconds))


def small_trig(expr):
    """Trig-simplify a *small* expression (the dynamics engine's sympy fallback algebra:
    pieces of one link at a time); expressions without sin/cos are only expanded."""
    expr = sp.sympify(expr)
    if expr.is_number or not expr.has(sp.sin, sp.cos):
        return sp.expand(expr)
    return sp.trigsimp(sp.expand(expr))
