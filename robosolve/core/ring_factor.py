"""Factoring a ring polynomial by its contents first, then sympy's factor_list on the pieces.

A Jacobian's determinant or minor in the trig ring (robosolve.core.trigring) is usually a few
small factors — a parameter (a₂), a sine (s₃, s₅), a short sum (a₂c₂ + a₃c₂₃ + d₅s₂₃₄) —
multiplied out into hundreds of terms. sympy's `factor_list` takes the content with respect to
the leading generator only, then runs Wang's multivariate algorithm (evaluation points, Hensel
lifting) on the rest: seconds on a UR5's 6×6 det J. Here the polynomial is first split by its
content with respect to every generator in turn (the gcd of its coefficients as a polynomial in
that generator: a polynomial gcd, much cheaper than a factorisation), until no piece has a
content left; each piece is then factored by sympy, and the factors are merged.

Before any of that, a polynomial of degree 1 in some generator (in the trig ring every sine has
degree at most 1) is proved irreducible by one gcd — p = a·x + b with gcd(a, b) = 1 cannot split —
or split by that gcd into the gcd and an irreducible cofactor, so most minors of a Jacobian need
no factorisation at all (`_certified_irreducible`).

By unique factorisation the result is the same as `p.factor_list()`: the same irreducible
factors, each normalised by sympy as it normalises them (primitive, positive leading
coefficient), with the same multiplicities and the same constant. Only the order of the list
may differ; callers multiply the factors (a sympy Mul: the order does not show).
`tests/engines/test_ring_factor.py` compares both on random products and on the UR5's det J.
"""

from __future__ import annotations

__all__ = ["factor_list_by_contents"]

# below this many terms sympy alone is as fast (the contents cost their gcds)
SMALL = 100


def factor_list_by_contents(p):
    """(coefficient, [(factor, multiplicity)]) of a PolyElement, as `p.factor_list()`."""
    domain = p.ring.domain
    if domain.is_PolynomialRing and not (domain.dom.is_ZZ or domain.dom.is_QQ):
        # over RR[a, cos(π/7), ...] (a float in a pose beside symbols) sympy's factor_list fails
        # (dmp_factor_list multiplies the domain's elements as ground numbers); over the flat
        # ring, the parameters as generators, it factors as sympy's factor of the expression does
        return _back(p, *_flat(p).factor_list())
    if p.is_ground:
        return p.factor_list()
    certified = _certified_irreducible(p)
    if certified is not None:
        return certified
    if len(p.terms()) < SMALL:
        return p.factor_list()
    if domain.is_PolynomialRing and (domain.dom.is_ZZ or domain.dom.is_QQ):
        return _over_polynomial_domain(p)
    if not (domain.is_ZZ or domain.is_QQ):
        return p.factor_list()
    return _flat_factor_list(p)


def _certified_irreducible(p):
    """`p.factor_list()` of a p proved irreducible without factoring it, else None. A polynomial
    of degree 1 in some generator x, p = a·x + b, whose a and b have no common factor, is
    irreducible: of any two factors one is free of x and divides both a and b. In the trig ring
    every sine has degree at most 1 (sin² is written 1 − cos²), so most minors of a Jacobian are
    such (Wang's algorithm spent 0.1–1.6 s on each of a 5R arm's minors to find nothing to split);
    the proof costs one gcd. Over K[parameters] the parameters are generators too, as there."""
    ring, domain = p.ring, p.ring.domain
    if domain.is_PolynomialRing and (domain.dom.is_ZZ or domain.dom.is_QQ):
        done = _certified_irreducible(_flat(p))
        return None if done is None else _back(p, *done)
    if not (domain.is_ZZ or domain.is_QQ):
        return None
    degrees = [max(m[i] for m in p.itermonoms()) for i in range(ring.ngens)]
    for i, deg in enumerate(degrees):
        if deg != 1:
            continue
        a = ring.from_dict({m[:i] + (0,) + m[i + 1:]: c for m, c in p.items() if m[i] == 1})
        b = p - a * ring.gens[i]
        if b == 0:
            return None        # x·a: the monomial split of the usual way
        g = a.gcd(b)
        if g.is_ground:
            return _normalised(p)
        # p = g · (p / g), the second factor irreducible by the same argument, g free of x
        # and factored the usual way (it is smaller)
        coeff, factors = factor_list_by_contents(g)
        c2, rest = _normalised(p.exquo(g))
        return coeff * c2, list(factors) + rest
    return None


def _normalised(p):
    """(coefficient, [(q, 1)]) for an irreducible p, as sympy's factor_list writes it: q with
    integer coefficients, primitive, a positive leading coefficient."""
    domain = p.ring.domain
    denom, q = p.clear_denoms() if domain.is_QQ else (domain.one, p)
    content = q.content()
    q = q.quo_ground(content)
    if not domain.is_positive(q.LC):
        q, content = -q, -content
    return domain.quo(content, denom) if domain.is_QQ else content, [(q, 1)]


def _over_polynomial_domain(p):
    """A polynomial over K[a, b, ...] (the robot's parameters in the coefficients): its
    parameters made generators after the ring's own, as sympy's factor_list does it, factored
    there, and each factor written back over K[a, b, ...]."""
    return _back(p, *_flat_factor_list(_flat(p)))


def _flat(p):
    """p over K[a, b, ...] as a polynomial over K in the ring's generators, then a, b, ..."""
    from sympy.polys.rings import PolyRing

    ring, domain = p.ring, p.ring.domain
    flat_ring = PolyRing(ring.symbols + domain.symbols, domain.dom, ring.order)
    return flat_ring.from_dict({m + cm: c for m, g in p.items() for cm, c in g.items()})


def _back(p, coeff, factors):
    """A factor list of _flat(p) written back over p's ring: factors of the parameters alone go
    into the coefficient."""
    ring, domain = p.ring, p.ring.domain
    n = ring.ngens
    coeff, back = domain.convert(coeff, domain.dom), []
    for f, k in factors:
        terms: dict = {}
        for m, c in f.items():
            terms.setdefault(m[:n], {})[m[n:]] = c
        if list(terms) == [(0,) * n]:       # a factor of the parameters alone: in the coefficient
            coeff *= domain.ring.from_dict(terms[(0,) * n]) ** k
            continue
        back.append((ring.from_dict({m: domain.ring.from_dict(g) for m, g in terms.items()}), k))
    return coeff, back


def _flat_factor_list(p):
    domain = p.ring.domain
    coeff = domain.one
    merged: dict = {}
    for piece in _pieces(p):
        c, factors = piece.factor_list()
        coeff *= c
        for f, k in factors:
            merged[f] = merged.get(f, 0) + k
    return coeff, list(merged.items())


def _pieces(p) -> list:
    """Polynomials whose product is p, none with a content with respect to any generator."""
    ring = p.ring
    done, todo = [], [p]
    while todo:
        f = todo.pop()
        for i in range(ring.ngens):
            c = _content_in(f, i)
            if c is None:
                continue
            rest = f.exquo(c)
            if not rest.is_ground:      # not f itself (a monomial x_i^k, up to a constant)
                todo += [c, rest]
                break
        else:
            done.append(f)
    return done


def _content_in(f, i: int):
    """The content of f as a polynomial in generator i (a polynomial free of it, with a positive
    leading coefficient), or None when it is a constant."""
    ring = f.ring
    groups: dict = {}
    for monom, c in f.terms():
        groups.setdefault(monom[i], {})[monom[:i] + (0,) + monom[i + 1:]] = c
    low = min(groups)
    if len(groups) == 1:
        # f = x_i^k · g: the monomial is the split (g has no content in x_i)
        if low == 0:
            return None
        return ring.gens[i] ** low
    g = None
    for terms in sorted(groups.values(), key=len):
        h = ring.from_dict(terms)
        g = h if g is None else g.gcd(h)
        if g.is_ground:
            break
    if low > 0:
        g = g * ring.gens[i] ** low
    if g.is_ground:
        return None
    return g if ring.domain.is_positive(g.LC) else -g
