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


def test_expanded_pairs_are_the_terms_split_by_as_independent():
    """expanded_pairs against each term of sympy's expand split by as_independent(sin, cos): a
    prismatic joint's variable (a generator of the ring, not a trig factor) on the coefficient's
    side, as sympy puts it."""
    from collections import Counter

    d = sp.Symbol("d")
    rng = random.Random(5)
    for decimal in (False, True):
        exprs = [_random_poly(rng, decimal) * d ** rng.randint(0, 2) + rng.randint(0, 2) * d
                 for _ in range(20)]
        alg = TrigAlgebra.from_inputs(list(q) + [d], exprs)
        assert alg is not None
        for k in range(len(exprs)):
            p = alg.element(k)
            for x in (p, alg.reduce(p * alg.element((k + 3) % len(exprs))), alg.zero):
                ref = [t.as_independent(sp.sin, sp.cos) for t in sp.Add.make_args(sp.expand(alg.to_expr(x)))]
                assert Counter(alg.expanded_pairs(x)) == Counter(ref)


def test_division_remainder_is_sympys_rem_term_for_term():
    """trigring._division_remainder against PolyElement.rem (the reference): the same terms, the
    same decimal coefficients to the last bit, in the same order, on random products of decimal
    trig polynomials with parameters."""
    from robosolve.core.trigring import _division_remainder

    rng = random.Random(11)
    exprs = [_random_poly(rng, True) for _ in range(12)]
    alg = TrigAlgebra.from_inputs(list(q), exprs)
    assert alg is not None and not alg.term_by_term
    for k in range(len(exprs)):
        p = alg.element(k) * alg.element((k + 5) % len(exprs)) * alg.element((k + 7) % len(exprs))
        got = _division_remainder(p, alg._basis)
        want = p.rem(alg._basis)
        assert list(got.items()) == list(want.items())
        assert all(list(a.items()) == list(b.items()) if hasattr(a, "items") else a == b
                   for a, b in zip(got.values(), want.values()))
