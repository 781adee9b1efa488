"""One simplification policy for every solver (stable goldens, bounded time).

`tidy` is the cheap default: trig products collapsed entry by entry
(c1*c2 - s1*s2 -> cos(theta1 + theta2)), never a blanket `simplify`.
"""

from __future__ import annotations

import sympy as sp

from robosolve.core.timing import time_limit
from robosolve.errors import SymbolicTimeout


def tidy(expr, seconds: float = 5.0):
    """trigsimp of one expression, or the expression unchanged past `seconds`."""
    expr = sp.sympify(expr)
    if expr.is_Atom or not expr.has(sp.sin, sp.cos):
        return sp.expand(expr) if expr.is_Add or expr.is_Mul else expr
    try:
        with time_limit(seconds):
            return sp.trigsimp(sp.expand(expr))
    except SymbolicTimeout:
        return expr


def tidy_matrix(m: sp.Matrix, seconds: float = 5.0) -> sp.Matrix:
    return m.applyfunc(lambda e: tidy(e, seconds))
