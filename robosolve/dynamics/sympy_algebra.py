"""The dynamics engine's fallback algebra: `SympyAlgebra`, the interface of the trig ring
(`robosolve.core.trigring.TrigAlgebra`) on plain sympy expressions, with small-piece
`trigsimp` (core/simplify.py's `small_trig`), for inputs that are not polynomials in
cos qᵢ, sin qᵢ (sin(qᵢ/2))."""

from __future__ import annotations

import sympy as sp

from robosolve.core.simplify import small_trig
from robosolve.core.trigring import TrigAlgebra

__all__ = ["SympyAlgebra"]


class SympyAlgebra:
    """The same interface on plain sympy expressions (fallback, small-piece trigsimp)."""

    zero = sp.S.Zero
    one = sp.S.One
    half = sp.S.Half

    def __init__(self, q, exprs, simplify=True):
        self.q = list(q)
        self.elements = [sp.sympify(e) for e in exprs]
        self._simp = small_trig if simplify else (lambda e: e)

    def element(self, k):
        return self.elements[k]

    def from_expr(self, expr):
        return sp.sympify(expr)

    def reduce(self, p):
        return self._simp(p)

    def diff(self, p, i):
        return self._simp(sp.diff(p, self.q[i]))

    def depends(self, p, i) -> bool:
        return sp.sympify(p).has(self.q[i])

    def to_expr(self, p):
        return p

    def to_matrix(self, m):
        return sp.Matrix(m)


for _name in ("matmul", "rigid_inverse", "mdiff", "madd", "zeros", "eye"):
    setattr(SympyAlgebra, _name, getattr(TrigAlgebra, _name))
