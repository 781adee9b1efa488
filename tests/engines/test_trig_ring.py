"""core/trigring.py, the one trig-polynomial ring, tested directly against sympy and numbers:

* reduction modulo c² + s² = 1: the same function at random points, no square left in the
  eliminated direction, one normal form for two writings of a function, zero exactly when the
  function is (against sympy's trigsimp);
* `TrigAlgebra`: products, derivatives and rigid inverses against sympy's at random points;
* the Fourier and product forms add up to the element.
"""

from __future__ import annotations

import random

import sympy as sp

from robosolve.core import trigring as R
from robosolve.core.transforms import dh_standard as dh_matrix

q1, q2, q3 = sp.symbols("q1 q2 q3", real=True)
a2, a3, d1, m = sp.symbols("a2 a3 d1 m", positive=True)
Q = [q1, q2, q3]
SYMS = (q1, q2, q3, a2, a3, d1, m)


def _value(e, pt):
    return complex(sp.N(sp.sympify(e).xreplace(pt)))


def _same_function(a, b, n=6, seed=3):
    rng = random.Random(seed)
    for _ in range(n):
        pt = {s: rng.uniform(-2, 2) for s in SYMS}
        if abs(_value(a, pt) - _value(b, pt)) > 1e-9 * max(1.0, abs(_value(a, pt))):
            return False
    return True


def _random_trig_poly(rng, terms=6):
    atoms = [sp.sin(q1), sp.cos(q1), sp.sin(q2), sp.cos(q2), sp.cos(q2 + q3), sp.sin(q3)]
    out = sp.Integer(0)
    for _ in range(terms):
        t = rng.choice([1, -2, sp.Rational(1, 2), 3]) * rng.choice([a2, a3 * m, d1, 1])
        for _ in range(rng.randint(1, 4)):
            t *= rng.choice(atoms)
        out += t
    return sp.expand(out)


def _degree(e, f) -> int:
    return max((p.exp for p in sp.expand(e).atoms(sp.Pow) if p.base == f), default=1)


def test_reduction_is_the_same_function_with_no_square_left():
    rng = random.Random(11)
    for _ in range(6):
        e = _random_trig_poly(rng)
        r = R.pythagorean_reduced(e)
        assert r is not None and _same_function(e, r)
        for q in (q1, q2, q3):       # each angle: sin² or cos² eliminated, never both left
            assert _degree(r, sp.sin(q)) < 2 or _degree(r, sp.cos(q)) < 2


def test_one_normal_form_and_zero_exactly_when_the_function_is():
    e = a2 * sp.cos(q2) * (sp.sin(q1) ** 2 + sp.cos(q1) ** 2) - a3 * sp.sin(q2 + q3)
    other = a2 * sp.cos(q2) - a3 * (sp.sin(q2) * sp.cos(q3) + sp.cos(q2) * sp.sin(q3))
    assert sp.expand(R.pythagorean_reduced(sp.expand(e)) - R.pythagorean_reduced(sp.expand(other))) == 0
    rng = random.Random(5)
    for _ in range(4):
        p = _random_trig_poly(rng, 3)
        zero = sp.expand(p * (sp.sin(q1) ** 2 + sp.cos(q1) ** 2 - 1))
        assert R.pythagorean_reduced(zero) == 0 and sp.trigsimp(zero) == 0
        assert R.pythagorean_reduced(sp.expand(zero + m * sp.sin(q3) ** 2)) != 0


def test_both_directions_of_the_basis():
    alg = R.TrigAlgebra.from_inputs(Q, [sp.cos(q1) ** 4 + sp.sin(q1) ** 3])
    (s, c), = [alg.trig[0]]
    p = alg.ring.from_dict({(0, 4): 1}) + alg.ring.from_dict({(3, 0): 1})   # c⁴ + s³ (gens s, c)
    by_sin = p.rem(R.pythagorean_basis([(s, c)]))
    by_cos = R.eliminate_cos_squared(p, s, c)
    si, ci = alg.ring.gens.index(s), alg.ring.gens.index(c)
    assert all(mono[si] < 2 for mono in by_sin.keys())
    assert all(mono[ci] < 2 for mono in by_cos.keys())
    for f in (by_sin, by_cos):
        assert _same_function(alg.to_expr(f), sp.cos(q1) ** 4 + sp.sin(q1) ** 3)


def _chain():
    return [dh_matrix(q1, d1, 0, sp.pi / 2), dh_matrix(q2, 0, a2, 0), dh_matrix(q3, 0, a3, 0)]


def test_products_derivatives_and_inverses_against_sympy():
    mats = _chain()
    alg = R.TrigAlgebra.from_inputs(Q, [e for M in mats for e in M])
    ring_mats = [[[alg.element(4 * 4 * k + 4 * r + c) for c in range(4)] for r in range(4)]
                 for k in range(3)]
    prod = alg.matmul(alg.matmul(ring_mats[0], ring_mats[1]), ring_mats[2])
    ref = mats[0] * mats[1] * mats[2]
    got = alg.to_matrix(prod)
    for i in range(16):
        assert _same_function(got[i], ref[i])
    for j, q in enumerate(Q):
        d = alg.to_matrix(alg.mdiff(prod, j))
        for i in range(16):
            assert _same_function(d[i], sp.diff(ref[i], q))
        assert alg.depends(prod[0][0], j)
    inv = alg.to_matrix(alg.matmul(alg.rigid_inverse(prod), prod))
    assert all(_same_function(inv[i], sp.eye(4)[i]) for i in range(16))
    # canonical: the product equals the element of its own expression, term for term
    assert alg.from_expr(alg.to_expr(prod[0][3])) == prod[0][3]
    # zero tests: an element that is zero as a function is the ring's zero
    one = alg.from_expr(sp.sin(q2) ** 2 + sp.cos(q2) ** 2)
    assert one == alg.one and alg.reduce(one - alg.one) == alg.zero


def test_fourier_and_product_forms_add_up_to_the_element():
    mats = _chain()
    alg = R.TrigAlgebra.from_inputs(Q, [e for M in mats for e in M] + [m])
    M = [[[alg.element(16 * k + 4 * r + c) for c in range(4)] for r in range(4)] for k in range(3)]
    p = alg.matmul(alg.matmul(M[0], M[1]), M[2])[0][3]
    energy = alg.reduce(p * p * alg.element(48) * alg.half)
    for e in (p, energy):
        ref = alg.to_expr(e)
        assert _same_function(sp.Add(*[c * t for c, t in R.fourier_terms(alg, e)]), ref)
        assert _same_function(sp.Add(*[c * t for c, t in R.product_terms(alg, e)]), ref)


def test_not_polynomial_inputs():
    assert R.TrigAlgebra.from_inputs(Q, [sp.sin(q1 / 2)]) is None
    assert R.TrigAlgebra.from_inputs(Q, [1 / sp.cos(q1)]) is None
    assert R.pythagorean_reduced(sp.sin(q1 / 2) * sp.cos(q1)) is None
    assert R.pythagorean_reduced(sp.Float(0.5) * sp.sin(q1) ** 2) is None
