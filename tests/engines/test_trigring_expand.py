"""TrigAlgebra.expanded_expr (written out term by term) against sympy's expand of the element's
expression (the reference), on random trig polynomials with parameters: rational and decimal."""

from __future__ import annotations

import random

import sympy as sp

from robosolve.core.trigring import TrigAlgebra

q = sp.symbols("q1:4")
a, b, m = sp.symbols("a b m", positive=True)


def _random_poly(rng: random.Random, decimal: bool):
    terms = []
    for _ in range(rng.randint(1, 6)):
        c = sp.Float(rng.uniform(-3, 3), 15) if decimal else sp.Rational(rng.randint(-5, 5), rng.randint(1, 3))
        f = c * rng.choice([1, a, b, a * b, m * a ** 2, a + b, m - 1])
        for qi in q:
            k = rng.randint(0, 2)
            f *= rng.choice([sp.sin(qi), sp.cos(qi)]) ** k
        terms.append(f)
    return sp.Add(*terms)


def test_expanded_expr_is_expand_of_to_expr():
    rng = random.Random(31)
    for decimal in (False, True):
        exprs = [_random_poly(rng, decimal) for _ in range(25)]
        alg = TrigAlgebra.from_inputs(list(q), exprs)
        assert alg is not None
        for k, e in enumerate(exprs):
            p = alg.element(k)
            for x in (p, alg.reduce(p * p), alg.reduce(p + alg.element((k + 1) % len(exprs)))):
                assert alg.expanded_expr(x) == sp.expand(alg.to_expr(x))
