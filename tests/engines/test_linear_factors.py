"""core.linear_factors against sympy's factor_list (the independent reference): the same
coefficient, factors and multiplicities on random products of random polynomials in sines and
cosines, with repeated factors, monomials, integer contents and signs."""
import random

import pytest
import sympy as sp

from robosolve.core.linear_factors import factor_list_zz

q = sp.symbols("q1:5")
GENS = [g for x in q for g in (sp.sin(x), sp.cos(x))] + [sp.Symbol("d")]


def _random_poly(rng, nterms, max_deg):
    terms = []
    for _ in range(nterms):
        c = rng.choice([-3, -2, -1, 1, 1, 2, 5])
        mono = sp.Integer(c)
        for g in rng.sample(GENS, rng.randint(0, 3)):
            mono *= g ** rng.randint(1, max_deg)
        terms.append(mono)
    return sp.Add(*terms)


def _as_set(result):
    c, factors = result
    return sp.Integer(c), sorted((sp.sstr(f.as_expr()), k) for f, k in factors)


@pytest.mark.parametrize("seed", range(40))
def test_equal_to_sympy_factor_list(seed):
    rng = random.Random(seed)
    expr = sp.Integer(rng.choice([1, -1, 6, -4]))
    for _ in range(rng.randint(1, 4)):
        piece = _random_poly(rng, rng.randint(1, 5), rng.choice([1, 1, 2]))
        expr *= piece ** rng.choice([1, 1, 2])
    poly = sp.Poly(sp.expand(expr), *[g for g in GENS if sp.expand(expr).has(g)] or [GENS[0]])
    assert _as_set(factor_list_zz(poly)) == _as_set(poly.factor_list())


def test_irreducible_linear_and_monomial_cases():
    s1, c1, s2, c2 = GENS[:4]
    cases = [
        s1 * c2 + 3 * c1,                       # primitive, degree one: irreducible
        6 * s1 * c2 + 4 * c1 * c2,              # content 2·c2 (a monomial gcd)
        (s1 + c2) * (c1 * s2 - 2) * s2 ** 2,    # a square of a generator left to sympy
        -(s1 * s2 + c1 * c2) ** 2 * (s1 + 1),   # a repeated factor, a negative sign
        s1 ** 2 + c1 ** 2 - 1,                  # degree two in every generator
    ]
    for expr in cases:
        e = sp.expand(expr)
        poly = sp.Poly(e, *[g for g in GENS if e.has(g)])
        assert _as_set(factor_list_zz(poly)) == _as_set(poly.factor_list()), expr


def test_other_domains_go_to_sympy():
    poly = sp.Poly(sp.Rational(1, 2) * GENS[0] + GENS[1], GENS[0], GENS[1])
    assert factor_list_zz(poly) == poly.factor_list()


@pytest.mark.parametrize("seed", range(30))
def test_sympy_factor_of_an_integer_polynomial(seed):
    """simplify._integer_polynomial_factor (what _memo_factor uses for a sum over ZZ) against
    sympy's factor: the same expression, node for node."""
    from robosolve.core.simplify import _integer_polynomial_factor

    rng = random.Random(100 + seed)
    expr = sp.Integer(rng.choice([1, -1, 2, -6]))
    for _ in range(rng.randint(1, 3)):
        expr *= _random_poly(rng, rng.randint(1, 4), rng.choice([1, 2])) ** rng.choice([1, 1, 2])
    e = sp.expand(expr)
    fast = _integer_polynomial_factor(e)
    if e.is_Add:
        assert fast is not None
        assert sp.srepr(fast) == sp.srepr(sp.factor(e))
    else:
        assert fast is None
    # not over ZZ, or not a polynomial: left to sympy
    assert _integer_polynomial_factor(e / 2 + GENS[0] / 3) is None
    assert _integer_polynomial_factor(sp.Float(0.5) * GENS[0] + GENS[1]) is None
    assert _integer_polynomial_factor(sp.sqrt(GENS[-1]) + GENS[1]) is None
