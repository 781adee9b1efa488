"""core/ring_factor against sympy's own factor_list (the reference): the same constant, the same
irreducible factors with the same multiplicities, on random products and on the arms' det J."""

from __future__ import annotations

import random

import pytest
from sympy import QQ, ZZ
from sympy.polys.rings import ring

from robosolve.core import ring_factor
from robosolve.core.ring_factor import factor_list_by_contents


def _random_poly(rng, gens, terms):
    out = gens[0] * 0
    for _ in range(terms):
        mono = rng.randint(-3, 3) or 1
        for g in gens:
            mono *= g ** rng.choice((0, 0, 1, 2))
        out += mono
    return out


def _same(a, b):
    return a[0] == b[0] and sorted(map(str, a[1])) == sorted(map(str, b[1]))


@pytest.mark.parametrize("seed", range(12))
def test_random_products_over_the_integers(seed):
    rng = random.Random(seed)
    _, *gens = ring("s1,c1,s2,c2,s3,c3", ZZ)
    p = rng.randint(1, 6) * rng.choice((1, -1))
    for _ in range(rng.randint(2, 4)):
        sub = gens[: rng.randint(1, len(gens))]
        p *= _random_poly(rng, sub, rng.randint(1, 4)) ** rng.choice((1, 1, 2))
    p *= gens[rng.randrange(len(gens))] ** rng.randint(0, 2)
    if p.is_ground:
        return
    # below the size where the contents pay, the module hands over to sympy: the route itself too
    assert _same(ring_factor._flat_factor_list(p), p.factor_list())
    if len(p.terms()) >= ring_factor.SMALL:
        assert _same(factor_list_by_contents(p), p.factor_list())


@pytest.mark.parametrize("seed", range(6))
def test_parameters_in_the_coefficients(seed):
    """The robot's parameters in the domain (ZZ[a2, a3, d5], QQ[...]), as the trig ring has them."""
    rng = random.Random(100 + seed)
    for domain in (ZZ, QQ):
        pring, *params = ring("a2,a3,d5", domain)
        r, *gens = ring("s2,c2,s3,c3,s5", pring.to_domain())
        p = r(1)
        for _ in range(3):
            term = r(0)
            for _ in range(rng.randint(2, 5)):
                mono = r(rng.choice(params) * rng.randint(1, 3) + rng.randint(-2, 2))
                for g in gens:
                    mono *= g ** rng.choice((0, 1))
                term += mono
            p *= term
        p *= params[0] * gens[4]
        if p.is_ground:
            continue
        assert _same(ring_factor._over_polynomial_domain(p), p.factor_list())


@pytest.mark.parametrize("seed", range(16))
def test_a_polynomial_linear_in_a_generator_is_proved_irreducible_as_sympy_finds_it(seed):
    """ring_factor._certified_irreducible: a trig-ring polynomial (each sine of degree at most 1),
    a product of such pieces or one alone, over ZZ, QQ and QQ[parameters]: exactly sympy's
    factor_list (the same constant, factors and multiplicities), whether the gcd proves it
    irreducible or splits off a common factor."""
    rng = random.Random(300 + seed)
    domain = (ZZ, QQ, QQ)[seed % 3]
    if seed % 3 == 2:
        pring, *params = ring("a2,a3,d5", QQ)
        r, *gens = ring("s1,c1,s2,c2,s3", pring.to_domain())
        coeffs = [r(x) for x in params] + [r(1), r(2), r(QQ(1, 2))]
    else:
        r, *gens = ring("s1,c1,s2,c2,s3", domain)
        coeffs = [r(1), r(-1), r(2), r(3)] + ([r(QQ(1, 3))] if domain is QQ else [])
    sines = (0, 2, 4)

    def piece():
        out = r(0)
        for _ in range(rng.randint(2, 6)):
            mono = rng.choice(coeffs)
            for i, g in enumerate(gens):
                mono *= g ** rng.choice((0, 1) if i in sines else (0, 1, 2))
            out += mono
        return out

    p = piece()
    for _ in range(rng.randint(0, 2)):
        p *= piece()
    if p.is_ground:
        return
    assert _same(factor_list_by_contents(p), p.factor_list())


def test_the_ur5_determinant_factors_as_sympy_factors_it():
    """The UR5's 6×6 det J (420 ring terms): the content route and sympy's give the same factors."""
    from pathlib import Path

    import robosolve.kinematics.structured_det as sd
    from robosolve.load.loader import load_problem
    from robosolve.model import RobotModel

    problem = load_problem(Path(__file__).parents[2] / "problems" / "ur5.yaml")
    model = RobotModel(problem)
    seen = []
    original = sd._factored

    def spy(alg, p, joints):
        seen.append(p)
        return original(alg, p, joints)

    sd._factored = spy
    try:
        j = sd.geometric_jacobian_ring(model, problem.last_frame, [0, 0, 0], problem.last_frame)
        sd.structured_det(j, model.q)
    finally:
        sd._factored = original
    big = [p for p in seen if len(p.terms()) >= 100]
    assert big, "the UR5's det J should be one large ring polynomial"
    for p in big:
        assert _same(factor_list_by_contents(p), p.factor_list())


@pytest.mark.parametrize("seed", range(16))
def test_polynomial_factor_list_is_sympys_factor_list_of_factor(seed):
    """core/simplify's factoring of a substituted minor piece by piece, without sympy's passes of
    together(): exactly sympy's factor_list(factor(e)) — the same coefficient and the same list in
    the same order (the order shows in the product: sympy's Mul distributes a number over the
    first sum) — on random products of sums in sines, cosines, parameters and a root, some
    factors repeated, some pieces multiplied out."""
    import sympy as sp

    from robosolve.core.simplify import _polynomial_factor_list

    rng = random.Random(seed)
    a, b, d = sp.symbols("a b d", real=True)
    q2, q3 = sp.symbols("q2 q3", real=True)
    atoms = [a, b, d, sp.sin(q2), sp.cos(q2), sp.sin(q2 + q3), sp.cos(q3), sp.sqrt(a**2 + d**2)]

    def piece():
        out = 0
        for _ in range(rng.randint(1, 4)):
            t = rng.choice([1, -1, 2, -3, sp.Rational(1, 2)])
            for _ in range(rng.randint(1, 3)):
                t *= rng.choice(atoms)
            out += t
        return out

    factors = [piece() ** rng.choice([1, 1, 2]) for _ in range(rng.randint(1, 4))]
    expr = rng.choice([-1, 1, 6, sp.Rational(-2, 3)]) * sp.Mul(*factors)
    if rng.random() < 0.5:
        expr = sp.expand(expr)
    fast = _polynomial_factor_list(expr)
    if fast is None:
        # a root as a factor of its own (sympy lists it as (a² + d², 1/2)): left to sympy
        assert any(f.is_Pow and not f.exp.is_Integer for f in sp.Mul.make_args(expr))
        return
    assert fast == sp.factor_list(sp.factor(expr))


def test_polynomial_factor_list_leaves_the_rest_to_sympy():
    """Floats, denominators and fractional powers of a piece: None (sympy's route)."""
    import sympy as sp

    from robosolve.core.simplify import _polynomial_factor_list

    a, b = sp.symbols("a b", real=True)
    assert _polynomial_factor_list(0.5 * a + b) is None
    assert _polynomial_factor_list(a / b + 1) is None
    assert _polynomial_factor_list(sp.sqrt(a + b) * a) is None


def test_over_a_real_polynomial_domain_as_sympy_factors_the_expression():
    """A decimal in a pose beside parameters (a tool Tz(0.12) after d6) puts the coefficients in
    RR[d6, cos(π/7), …], where sympy's own factor_list fails (TypeError: PolyElement * PolyElement
    inside dmp_factor_list: the jacobian question ended in an internal error). The reference is
    sympy's factor_list of the expression with every symbol a generator."""
    import sympy as sp
    from sympy import RR

    R, s1, c1, c2 = ring("s1,c1,c2", RR[sp.Symbol("d6"), sp.cos(sp.pi / 7)])
    d6, cp = (R.domain.convert(g) for g in R.domain.gens)
    p = (s1 * (d6 + 0.12) + c1 * cp * 0.5) * (c2 * 2.0 + d6) * s1
    coeff, factors = factor_list_by_contents(p)
    product = R.domain.to_sympy(coeff) * sp.Mul(*[f.as_expr() ** k for f, k in factors])
    assert sp.expand(product - p.as_expr()) == 0
    gens = (*sp.symbols("s1 c1 c2 d6"), sp.cos(sp.pi / 7))
    ref = sp.factor_list(p.as_expr(), *gens)
    assert len(factors) == len(ref[1]) == 3
    assert sorted(k for _, k in factors) == sorted(k for _, k in ref[1])
