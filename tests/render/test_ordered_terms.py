"""core.printing.ordered_terms against sympy's Expr.as_ordered_terms (the reference it follows):
the order of a sum's terms in every printed text, on random sums with integer, rational,
decimal, irrational and complex coefficients, powers, roots, functions of sums, and in every
order the printers use."""
import random

import pytest
import sympy as sp

from robosolve.core.printing import _SAME_AS_TERMS, ordered_terms

x, y, z, m = sp.symbols("x y z m")
q1, q2 = sp.symbols("q1 q2")
ATOMS = [x, y, z, m, sp.sin(q1), sp.cos(q2), sp.sin(q1 + q2), sp.cos(q1 - 2 * q2), sp.sqrt(x + 1),
         sp.exp(y / 3), sp.pi, sp.sqrt(2), sp.Abs(z)]
COEFFS = [1, -1, 2, -3, sp.Rational(1, 3), sp.Rational(-5, 7), sp.Float("0.25"), sp.Float("-1.5e-3"),
          sp.Float("9.80665"), sp.I, 2 + 3 * sp.I, sp.pi]


def _random_sum(rng):
    terms = []
    for _ in range(rng.randint(2, 7)):
        t = sp.sympify(rng.choice(COEFFS))
        for a in rng.sample(ATOMS, rng.randint(0, 3)):
            t *= a ** rng.choice([1, 1, 2, -1, sp.Rational(1, 2)])
        terms.append(t)
    return sp.Add(*terms)


@pytest.mark.skipif(not _SAME_AS_TERMS, reason="this sympy sorts with its own code")
@pytest.mark.parametrize("seed", range(60))
def test_same_order_as_sympy(seed):
    rng = random.Random(seed)
    e = _random_sum(rng)
    for order in (None, "lex", "grlex", "rev-lex"):
        assert ordered_terms(e, order) == e.as_ordered_terms(order=order), (e, order)


def test_special_cases():
    cases = [1 - 2 * x, sp.Integer(3) + x, x + sp.O(x**2), sp.Float(2.5) - sp.Rational(1, 2) * y]
    for e in cases:
        assert ordered_terms(e) == e.as_ordered_terms()
