"""sympy's `count_ops(expr)` (visual=False) without its symbolic bookkeeping.

`count_ops` is the measure robosolve's simplification policy and its report choices compare
(the shorter of two forms, "too long to show"); sympy computes it by building one symbol per
operation and adding them all up at the end, which is most of its time. The count is a sum over
the nodes of the expression (each node's own operations plus its children's), so it is computed
here node by node, with each node's count kept, as integers. The rules are sympy's, line for
line (sympy 1.14, `sympy.core.function.count_ops`): a negative Rational is a NEG, a denominator
a DIV, `-x - y` a NEG and a SUB, a Mul of n factors n - 1 MULs, a function or a power one
operation. `tests/engines/test_opcount.py` compares the two on every expression the bundled
problems count and on random ones.
"""

from __future__ import annotations

import sympy as sp
from sympy.concrete.summations import Sum
from sympy.core.function import Derivative, _coeff_isneg
from sympy.core.operations import LatticeOp
from sympy.integrals.integrals import Integral
from sympy.simplify.radsimp import fraction

# Counts of the nodes seen, by node (expressions are immutable and hashable). Bounded: a
# long session keeps at most this many.
_COUNTS: dict = {}
_MAX_COUNTS = 200_000


def count_ops(expr) -> int:
    """The same integer as `sympy.count_ops(expr)` for an expression, a matrix or a list."""
    if isinstance(expr, sp.MatrixBase) or isinstance(expr, (list, tuple)):
        return sum(count_ops(e) for e in expr)
    if not isinstance(expr, sp.Expr) or expr.is_Relational or _special(expr):
        return sp.count_ops(expr)
    return _count(expr)


def _special(expr) -> bool:
    """Expressions whose rules are sympy's alone here (matrix expressions)."""
    return bool(getattr(expr, "is_MatrixExpr", False))


def _count(a) -> int:
    hit = _COUNTS.get(a)
    if hit is None:
        hit = _node(a)
        if len(_COUNTS) < _MAX_COUNTS:
            _COUNTS[a] = hit
    return hit


def _no_denominator(a) -> bool:
    """fraction(a) is (a, 1): every factor of the Mul is a power with a positive integer
    exponent, an integer, or a factor `fraction` puts in the numerator as it is (a symbol, a
    Float, a sum, a function other than exp), and commutative (the common case of a trig
    polynomial's terms, where sympy's `fraction` is the count's most expensive step)."""
    for t in a.args:
        if not t.is_commutative:
            return False
        if t.is_Pow:
            if not (t.exp.is_Integer and t.exp > 0):
                return False
        elif t.is_Rational:
            if t.q != 1:
                return False
        elif isinstance(t, sp.exp) or not (t.is_Symbol or t.is_Float or t.is_Add or t.is_Function):
            return False
    return True


def _node(a) -> int:
    n = 0
    if a.is_Rational:
        if a is not sp.S.One:
            return int(a.p < 0) + int(a.q != 1)
    elif a.is_Mul:
        if _coeff_isneg(a):
            n += 1
            a = a.as_two_terms()[1] if a.args[0] is sp.S.NegativeOne else -a
        num, den = (a, sp.S.One) if a.is_Mul and _no_denominator(a) else fraction(a)
        if num.is_Integer:
            return n + 1 + int(bool(num < 0)) + _count(den)
        if den is not sp.S.One:
            return n + 1 + (0 if den.is_Integer else _count(den)) + _count(num)
        # a Mul with no denominator (or what the negation left): counted below
    elif a.is_Add:
        args = a.args
        negs = 0
        for i, ai in enumerate(args):
            if _coeff_isneg(ai):
                negs += 1
                n += _count(-ai)
            else:
                n += _count(ai)
            if i > 0:
                n += 1              # SUB or ADD
        if negs == len(args):       # -x - y: NEG + SUB (a first negative term: SUB - ADD, 0)
            n += 1
        return n
    if a.is_Pow and a.exp is sp.S.NegativeOne:
        return n + 1 + _count(a.base)
    if a == sp.S.Exp1:
        return n + 1
    if a.is_Pow and a.base == sp.S.Exp1:
        return n + 1 + _count(a.exp)
    if a.is_Mul or isinstance(a, LatticeOp):
        n += len(a.args) - 1
    elif a.args and (a.is_Pow or a.is_Function or isinstance(a, (Derivative, Integral, Sum))):
        n += 1
    if not a.is_Symbol:
        n += sum(_count(x) if isinstance(x, sp.Basic) else 0 for x in a.args)
    return n
