"""Factoring a polynomial over the integers through a variable it holds to the first degree.

The rank search of a Jacobian factors hundreds of minors, polynomials in the sines and cosines
of up to seven joints (14 generators, 20–40 terms); most are irreducible, and sympy's
`Poly.factor_list` (square-free decomposition, then Wang's algorithm, on dense recursive
polynomials) spends most of the search's time proving it. Such a polynomial is nearly always of
degree one in some generator x: f = a·x + b, with a and b free of x. Over a unique factorisation
domain a primitive polynomial of degree one in x is irreducible, so

    f = gcd(a, b) · (f / gcd(a, b))

is the whole story but for the factors of gcd(a, b), a polynomial in fewer terms, factored the
same way in turn. The gcd is one sparse gcd (or, when a or b is one term, a monomial read off
the exponents); sympy's own factoring is kept for a piece of degree two or more in every
generator. The result is sympy's: the same factors (primitive, positive leading coefficient in
the generators' lex order), multiplicities and coefficient — tested against `factor_list` on
random products and on every polynomial the bundled problems factor.
"""
from __future__ import annotations

from math import gcd

import sympy as sp
from sympy.polys.domains import ZZ
from sympy.polys.orderings import lex
from sympy.polys.rings import PolyRing


def factor_list_zz(poly: sp.Poly):
    """(coefficient, [(factor Poly, multiplicity)]) equal to ``poly.factor_list()`` for a
    polynomial over ZZ (any other domain goes to sympy as it is). The factors' order is not
    sympy's: the callers sort them."""
    if not poly.domain.is_ZZ or poly.is_ground:
        return poly.factor_list()
    ring = PolyRing(poly.gens, ZZ, lex)
    coeff = ZZ(1)
    found: dict = {}
    todo = [(ring(dict(poly.terms())), 1)]
    while todo:
        p, k = todo.pop()
        c, p = _normalised(p)
        coeff *= c ** k
        if p.is_ground:
            continue
        split = _linear_split(ring, p)
        if split is None:        # of degree two or more in every generator: sympy's way
            c2, factors = sp.Poly.from_dict(dict(p.items()), *poly.gens, domain=ZZ).factor_list()
            coeff *= ZZ(c2) ** k
            for f, m in factors:
                key = ring(dict(f.terms()))
                found[key] = found.get(key, 0) + m * k
            continue
        content, primitive = split
        if content is None:      # p itself is primitive of degree one in a generator
            found[p] = found.get(p, 0) + k
            continue
        c3, primitive = _normalised(primitive)
        coeff *= c3 ** k
        found[primitive] = found.get(primitive, 0) + k
        todo.append((content, k))
    return coeff, [(sp.Poly.from_dict(dict(p.items()), *poly.gens, domain=ZZ), m) for p, m in found.items()]


def _normalised(p):
    """(integer content with the sign, primitive part with a positive leading coefficient)."""
    c, p = p.primitive()
    if p.LC < 0:
        c, p = -c, -p
    return c, p


def _linear_split(ring, p):
    """None when p has degree two or more in every generator; else, for the generator x of
    degree one whose coefficients a, b (p = a·x + b) have the fewest terms, (None, None) when
    gcd(a, b) is a constant — p irreducible — or (gcd(a, b), p / gcd(a, b))."""
    n = ring.ngens
    degrees = [0] * n
    for m in p.keys():
        for j in range(n):
            if m[j] > degrees[j]:
                degrees[j] = m[j]
    best = None
    for i in range(n):
        if degrees[i] != 1:
            continue
        a, b = {}, {}
        for m, c in p.items():
            if m[i] == 1:
                a[m[:i] + (0,) + m[i + 1:]] = c
            else:
                b[m] = c
        cost = min(len(a), len(b))
        if best is None or cost < best[0]:
            best = (cost, a, b)
    if best is None:
        return None
    _, a, b = best
    if not b:
        g = ring(a)                  # p = a·x
    elif len(a) == 1 or len(b) == 1:
        g = _monomial_gcd(ring, list(a.items()) + list(b.items()))
    else:
        g = ring(a).gcd(ring(b))
    if g.is_ground:
        return None, None
    return g, p.exquo(g)


def _monomial_gcd(ring, terms):
    """gcd of a one-term polynomial and another, given their terms together: a divisor of a
    monomial is a monomial, so the gcd is the common exponents' minimum times the coefficients'
    gcd."""
    exponents = tuple(min(m[j] for m, _ in terms) for j in range(ring.ngens))
    c = 0
    for _, x in terms:
        c = gcd(c, int(x))
    return ring({exponents: ZZ(c)})
