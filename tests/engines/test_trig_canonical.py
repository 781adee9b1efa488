"""The fast paths of core/simplify.py (issue 15) against sympy's own simplifiers and numbers.

* `pythagorean_reduced`: the normal form modulo sin² + cos² = 1 equals the input at random
  points and is unique (two different writings of one function give one form);
* `_addition_formulas` (TR10i group by group) gives exactly TR10i's result on random sums;
* chain and Jacobian entries through the canonical route equal the input at random points,
  and on the 3R arm's entries they are what trigsimp gives;
* `is_zero` by the normal form agrees with evaluation at random points.
"""

from __future__ import annotations

import random

import sympy as sp
from sympy.simplify.fu import TR10i

from robosolve.core import simplify as S

q1, q2, q3 = sp.symbols("theta1 theta2 theta3", real=True)
L1, L2, qd = sp.symbols("L1 L2 qd", real=True)
SYMS = (q1, q2, q3, L1, L2, qd)


def _equal_at_random_points(a, b, n=8, seed=1):
    rng = random.Random(seed)
    for _ in range(n):
        pt = {s: rng.uniform(-2, 2) for s in SYMS}
        if abs(complex(sp.N((a - b).xreplace(pt)))) > 1e-9:
            return False
    return True


def _random_trig_sum(rng, terms=8):
    atoms = [sp.sin(q1), sp.cos(q1), sp.sin(q2), sp.cos(q2), sp.sin(q2 + q3), sp.cos(q2 + q3),
             sp.cos(q3)]
    out = 0
    for _ in range(terms):
        t = rng.choice([1, -1, 2, sp.Rational(1, 2)]) * rng.choice([L1, L2, L1 * qd, qd ** 2, 1])
        for _ in range(rng.randint(1, 3)):
            t *= rng.choice(atoms)
        out += t
    return sp.expand(out)


def test_normal_form_is_the_same_function_and_unique():
    e = L1 * sp.sin(q1) ** 2 * sp.cos(q2) + L1 * sp.cos(q1) ** 2 * sp.cos(q2) - L2 * sp.sin(q2 + q3)
    r = S.pythagorean_reduced(sp.expand(e))
    assert _equal_at_random_points(e, r)
    # another writing of the same function: L1 cos q2 (sin² + cos² = 1), sin(q2 + q3) expanded
    other = L1 * sp.cos(q2) - L2 * (sp.sin(q2) * sp.cos(q3) + sp.cos(q2) * sp.sin(q3))
    assert sp.expand(S.pythagorean_reduced(sp.expand(other)) - r) == 0
    assert not r.has(sp.sin(q1)) and not r.has(sp.cos(q1))


def test_not_a_polynomial_in_sin_cos_of_symbols():
    assert S.pythagorean_reduced(sp.sin(q1 / 2) * sp.cos(q1)) is None
    assert S.pythagorean_reduced(L1 + L2) is None


def test_addition_formulas_group_by_group_is_tr10i():
    rng = random.Random(7)
    for _ in range(40):
        e = _random_trig_sum(rng)
        assert S._addition_formulas(e) == TR10i(e)


def test_addition_formulas_on_products_turned_into_sums_is_tr10i():
    """The shortest-form candidate TR10i(expand(TR8(e))) is computed group by group: the same
    expression as TR10i's own (TR8 brings halves and sums of angles into the groups)."""
    from sympy.simplify.fu import TR8

    rng = random.Random(17)
    for _ in range(30):
        e = sp.expand(TR8(_random_trig_sum(rng, terms=rng.randint(2, 9))))
        assert S._addition_formulas(e) == TR10i(e)


def test_chain_entries_keep_their_value():
    rng = random.Random(3)
    for _ in range(12):
        e = _random_trig_sum(rng, terms=rng.randint(3, 12))
        S._MEMO.clear()
        assert _equal_at_random_points(S.chain_product(e), e)
        assert _equal_at_random_points(S.jacobian_entry(e), e)


def test_large_entry_is_what_trigsimp_gives():
    # the x entry of the 3R arm's acceleration column, before tidying: trigsimp (the
    # reference) takes seconds on it and returns the canonical form
    e = sp.expand(sp.diff(sp.cos(q1) * (L1 * sp.cos(q2) + L2 * sp.cos(q2 + q3)), q1, 2)
                  + sp.sin(q1) ** 2 * sp.cos(q1) * L1 + sp.cos(q1) ** 3 * L1)
    S._MEMO.clear()
    fast = S.chain_product(e)
    assert fast == sp.trigsimp(TR10i(e))


def test_is_zero_by_the_normal_form():
    rng = random.Random(11)
    for _ in range(20):
        e = _random_trig_sum(rng, terms=4)
        ident = sp.expand(sp.expand_trig(e))        # the same function, another writing
        assert S.is_zero(e - ident)
        assert S.is_zero(e + 1 - ident) is False
    assert S.is_zero(L1 * (sp.sin(q1) ** 2 + sp.cos(q1) ** 2) - L1)
    assert not S.is_zero(sp.sin(q1) * sp.cos(q2) - sp.sin(q2) * sp.cos(q1))


def test_entries_with_float_coefficients_keep_their_value_and_lose_their_products():
    """A float DH twist (alpha: 0.3) gives entries with float coefficients: they take the ring
    route with each float as a symbol (not trigsimp), keep their value, and come out without
    products of sines and cosines of one angle that the addition formulas can collapse."""
    rng = random.Random(7)
    c, s = sp.Float(0.955336489125606), sp.Float(0.29552020666134)
    for _ in range(6):
        entry = sp.expand(c * _random_trig_sum(rng) + s * _random_trig_sum(rng))
        tidied = S.chain_product(entry)
        assert _equal_at_random_points(entry, tidied) and not tidied.has(sp.Dummy)
    entry = sp.expand(s * L1 * (sp.cos(q1) * sp.cos(q2) - sp.sin(q1) * sp.sin(q2)) + c * L2 * sp.cos(q3))
    assert S.chain_product(entry) == s * L1 * sp.cos(q1 + q2) + c * L2 * sp.cos(q3)
    # a float inside an angle stays there (trigsimp's route, as before)
    offset = sp.expand(sp.sin(q1 + sp.Float(0.3)) * L1 + sp.Float(0.5) * sp.cos(q2))
    assert _equal_at_random_points(offset, S.chain_product(offset))


def test_addition_formulas_by_groups_are_tr10i_of_the_whole_sum():
    """core/simplify._addition_formulas applies TR10i to groups of terms (the same factor
    outside, the same sines' and cosines' arguments) and adds them: sympy's TR10i on the whole
    sum is the reference, on random sums of expanded products (chain-like: angle sums expanded,
    coefficients shared and not)."""
    import random

    from sympy.simplify.fu import TR10i

    from robosolve.core.simplify import _addition_formulas

    qs = sp.symbols("q1:5")
    a, b = sp.symbols("a b", positive=True)
    rng = random.Random(41)
    for _ in range(60):
        e = 0
        for _ in range(rng.randint(1, 4)):
            k = rng.sample(qs, rng.randint(1, 3))
            f = rng.choice([sp.cos, sp.sin])(sum(k))
            g = rng.choice([1, sp.cos(rng.choice(qs)), sp.sin(rng.choice(qs))])
            e += rng.choice([1, -1, a, 2 * b, a * b, sp.Rational(1, 2)]) * f * g
        expanded = sp.expand(sp.expand_trig(e))
        assert _addition_formulas(expanded) == TR10i(expanded), e


def test_a_jacobian_entry_with_float_coefficients_gains_no_one_point_zero_factors():
    # the centre-of-mass Jacobian of a body whose point is given with float coordinates
    # ([0.1, 0.2, 0]) came out as "-1.0*L1*sin(q1) - ..." (trigsimp on a float expression);
    # the entry must stay the same function, with the symbols' coefficients left exact
    e = (-L1 * sp.sin(q1) - L2 * sp.sin(q1 + q2) - sp.Float(0.1) * sp.sin(q1 + q2)
         - sp.Float(0.2) * sp.cos(q1 + q2))
    out = S.jacobian_entry(e)
    assert _equal_at_random_points(out, e)
    assert "1.0*" not in str(out)
    assert sp.Float(1.0) not in out.atoms(sp.Float) and sp.Float(-1.0) not in out.atoms(sp.Float)
