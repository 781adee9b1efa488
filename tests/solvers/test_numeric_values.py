"""The numeric values of answers (solvers/base._scalar): a float evaluation node by node,
against sympy's 17-digit evalf of the substituted expression (the reference), with evalf kept
for what the float evaluation does not handle."""

from __future__ import annotations

import math
import random

import pytest
import sympy as sp

from robosolve.solvers.base import _scalar, _to_float

q1, q2, L, m = sp.symbols("q1 q2 L m")
SUBS = {q1: sp.Float(0.7), q2: sp.Rational(-3, 5), L: sp.Rational(1, 2), m: sp.Float(2.5)}


def _random_expr(rng: random.Random, depth: int):
    leaves = [q1, q2, L, m, sp.Rational(3, 7), sp.Float(0.25), sp.pi, sp.Integer(-2), sp.E]
    if depth == 0:
        return rng.choice(leaves)
    a, b = _random_expr(rng, depth - 1), _random_expr(rng, depth - 1)
    return rng.choice([a + b, a * b, a - b, sp.sin(a), sp.cos(a) ** 2, sp.atan2(a, b),
                       sp.sqrt(a * a + 1), sp.exp(sp.sin(a)), a / (b * b + 1), sp.Abs(a) ** sp.Rational(3, 2)])


def test_float_values_agree_with_evalf():
    rng = random.Random(20261203)
    for _ in range(400):
        e = _random_expr(rng, rng.randint(1, 4))
        ref = float(e.xreplace(SUBS).evalf(17))
        got = _scalar(e, SUBS)
        assert math.isclose(got, ref, rel_tol=1e-13, abs_tol=1e-13), e


def test_shared_subexpressions_in_a_matrix_and_the_fallbacks():
    big = sum(sp.sin(k * q1) * sp.cos(q2) ** k for k in range(1, 8))
    M = sp.Matrix([[big, big ** 2], [big * L, sp.Piecewise((1, q1 > 0), (0, True))]])
    got = _to_float(M, SUBS)
    ref = [[float(x.xreplace(SUBS).evalf(17)) for x in M.row(i)] for i in range(2)]
    for r in range(2):
        for c in range(2):
            assert math.isclose(got[r][c], ref[r][c], rel_tol=1e-13)
    # a square root of a negative number: evalf's complex value, an error as before
    with pytest.raises(ValueError):
        _scalar(sp.sqrt(q2), SUBS)
