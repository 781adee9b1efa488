"""core.printing.ordered_terms against sympy's Expr.as_ordered_terms (the reference it follows):
the order of a sum's terms in every printed text, on random sums with integer, rational,
decimal, irrational and complex coefficients, powers, roots, functions of sums, and in every
order the printers use; core.printing.sort_key, latex and sstr against sympy's default_sort_key,
latex and sstr; generators whose
sympy keys are equal (L1 + L2 and 1.0*L1 + 1.0*L2) in one order however they are met (sympy
took them in the order of a set: the hash seed's)."""
import itertools
import random

import pytest
import sympy as sp

from robosolve.core.printing import _SAME_AS_TERMS, _sorted_generators, latex, ordered_terms, sort_key, sstr

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


def _random_nested(rng, depth=2):
    """A random expression with sums inside products, powers and functions (the shapes of the
    equations of motion: m*(L1 + L2)**2*cos(2*q), sin(q1 + q2)*(x + y/3))."""
    if depth == 0:
        return _random_sum(rng)
    parts = [_random_nested(rng, depth - 1) if rng.random() < 0.4 else rng.choice(ATOMS)
             for _ in range(rng.randint(1, 3))]
    shape = rng.choice(["mul", "add", "pow", "func"])
    if shape == "mul":
        return sp.Mul(sp.sympify(rng.choice(COEFFS)), *parts)
    if shape == "add":
        return sp.Add(*parts, sp.Mul(rng.choice(COEFFS), _random_sum(rng)))
    if shape == "pow":
        return sp.Pow(sp.Add(*parts), rng.choice([2, 3, -1, sp.Rational(1, 2)]))
    return rng.choice([sp.sin, sp.cos, sp.exp])(sp.Add(*parts))


@pytest.mark.skipif(not _SAME_AS_TERMS, reason="this sympy sorts with its own code")
@pytest.mark.parametrize("seed", range(40))
def test_sort_key_is_sympys(seed):
    rng = random.Random(seed)
    e = _random_nested(rng)
    for sub in sp.preorder_traversal(e):
        assert sort_key(sub) == sp.default_sort_key(sub), sub


L1, L2, q = sp.symbols("L1 L2 q")
# generators that sympy's sort key cannot tell apart: an exact and a decimal form of one sum
TIED = [L1 + L2, sp.Float(1.0) * L1 + sp.Float(1.0) * L2, q + sp.S.Half, q + sp.Float(0.5)]


def test_generators_with_equal_sympy_keys_are_sorted_the_same_however_met():
    for a, b in (TIED[:2], TIED[2:]):              # sympy's keys: neither before the other
        assert not sp.default_sort_key(a) < sp.default_sort_key(b)
        assert not sp.default_sort_key(b) < sp.default_sort_key(a)
    orders = {tuple(_sorted_generators(list(p))) for p in itertools.permutations(TIED + [L1, sp.sin(q)])}
    assert len(orders) == 1



@pytest.mark.skipif(not _SAME_AS_TERMS, reason="this sympy sorts with its own code")
@pytest.mark.parametrize("seed", range(30))
def test_latex_and_sstr_are_sympys(seed):
    rng = random.Random(1000 + seed)
    e = _random_nested(rng)
    names = {x: "x_{a}", m: r"\mathrm{m}"}
    assert latex(e) == sp.latex(e)
    assert latex(e, symbol_names=names) == sp.latex(e, symbol_names=names)
    assert sstr(e) == sp.sstr(e) == str(e)
