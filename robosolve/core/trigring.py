"""The one trig-polynomial ring of robosolve: polynomials in sᵢ = sin θᵢ, cᵢ = cos θᵢ (and
polynomial symbols), reduced modulo sᵢ² + cᵢ² = 1.

Every entry of a pose, L matrix or energy of a serial robot is such a polynomial, with
coefficients in the parameters. sympy's sparse polynomial rings multiply and differentiate
these in microseconds, and the reduction (a division by the Gröbner basis {sᵢ² + cᵢ² − 1})
gives a canonical form, so every cancellation that `trigsimp` would find through
cos² + sin² = 1 happens at once. Two ways in, one algebra:

* `TrigAlgebra`: the ring over a robot's joints (the dynamics engine, the structured
  determinant): built once from all inputs (`from_inputs`, None when a joint is used in a way
  that is not a polynomial in cos qᵢ, sin qᵢ, qᵢ, e.g. sin(qᵢ/2)), then products, derivatives,
  inverses of poses, all reduced (sin² → 1 − cos²); `fourier_terms` / `product_terms` read an
  element back as sines and cosines of sums of angles;
* `pythagorean_reduced(expr)`: one expression's normal form, over the angles found in it
  (core/simplify.py's chain entries and `is_zero`), each angle eliminated in the direction
  that leaves fewer operations.

Both reduce with `pythagorean_basis` (sin² eliminated) or `eliminate_cos_squared`. A fixed
rotation by an exact angle sympy keeps as it is (Rx(1/3), Rz(pi/7)) puts sin a and cos a among
the coefficients' generators; the coefficients are reduced modulo sin²a + cos²a = 1 as well
(`_fixed_angle_reducer`).
Nothing here calls a simplifier (core/simplify.py owns the policy and imports this module).
"""

from __future__ import annotations

import heapq
import math

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.orderings import lex
from sympy.polys.rings import ring as poly_ring
from sympy.polys.rings import sring
from robosolve.core.opcount import count_ops

__all__ = ["TrigAlgebra", "eliminate_cos_squared", "fourier_dict", "fourier_terms",
           "product_terms", "pythagorean_basis", "pythagorean_reduced"]


def pythagorean_basis(pairs) -> list:
    """sᵢ² + cᵢ² − 1 for each (s, c) pair of ring generators: dividing by it (`p.rem(basis)`,
    lex order with s before c) eliminates sin² (sin² -> 1 - cos²)."""
    return [s ** 2 + c ** 2 - 1 for s, c in pairs]


# ---------------------------------------------------------------------- the robot's ring
class TrigAlgebra:
    def __init__(self, ring, q, trig, poly, elements, half):
        self.ring = ring
        self.half = half
        self.q = q
        self.trig = trig  # joint index -> (s, c) ring generators
        self.poly = poly  # joint index -> q ring generator
        self.zero = ring.zero
        self.one = ring.one
        self._basis = pythagorean_basis(trig.values())
        index = {g: k for k, g in enumerate(ring.gens)}
        self._slots = [(index[s], index[c]) for s, c in trig.values()]
        ground = getattr(ring.domain, "domain", ring.domain)
        self.term_by_term = bool(ground.is_Exact)
        self._back = {}
        syms = dict(zip(ring.gens, ring.symbols))
        for i, (s, c) in trig.items():
            self._back[syms[s]] = sp.sin(q[i])
            self._back[syms[c]] = sp.cos(q[i])
        self._reduce_coefficient = _fixed_angle_reducer(ring.domain)
        self.elements = [self.reduce(e) for e in elements] if self._reduce_coefficient else elements
        # the ring's generators as the expressions they stand for (sin qᵢ, cos qᵢ, the others
        # themselves): an element is written out in them directly, not written in the ring's
        # symbols and substituted afterwards (the same expression, built once)
        self._gens_back = tuple(self._back.get(g, g) for g in ring.symbols)

    @classmethod
    def from_inputs(cls, q, exprs):
        """Build the ring over all input expressions; `None` if one is not polynomial."""
        exprs = [sp.sympify(e) for e in exprs]
        qset = set(q)
        trig_used, poly_used = set(), set()
        sc = {i: sp.symbols(f"s{i}_ c{i}_", real=True) for i in range(len(q))}
        rep = {}
        for i, qi in enumerate(q):
            rep[sp.sin(qi)] = sc[i][0]
            rep[sp.cos(qi)] = sc[i][1]
        converted = []
        for e in exprs:
            if e.has(*qset):
                e2 = e.xreplace(rep)
                if any(f.has(*qset) for f in e2.atoms(sp.Function)) or any(
                        p.has(*qset) for p in e2.atoms(sp.Pow) if not p.exp.is_Integer):
                    e = sp.expand_trig(e)
                    e2 = e.xreplace(rep)
                    if any(f.has(*qset) for f in e2.atoms(sp.Function)):
                        return None
                e = e2
            converted.append(e)
        for e in converted:
            fs = e.free_symbols
            for i, qi in enumerate(q):
                if sc[i][0] in fs or sc[i][1] in fs:
                    trig_used.add(i)
                if qi in fs:
                    poly_used.add(i)
        gens = []
        for i in range(len(q)):
            if i in trig_used:
                gens += [sc[i][0], sc[i][1]]
            if i in poly_used:
                gens.append(q[i])
        # polynomial in the generators? (joint symbols in denominators are not)
        if gens and not all(e.is_polynomial(*gens) for e in converted):
            return None
        if not gens:
            gens = [sc[0][1]] if q else [sp.Symbol("c0_")]
        # the extra 1/2 makes the coefficient domain a field over QQ (Christoffel halves)
        ring, elements = sring([*converted, sp.Rational(1, 2)], *gens)
        if ring.domain.is_EX:
            # a fixed angle whose sine sympy takes for an algebraic number (cos(pi/7)) makes the
            # coefficients bare expressions, whose every sum simplifies (minutes for a 2R arm);
            # as generators of the coefficients' ring they are reduced by `_fixed_angle_reducer`
            ring, elements = sring([*converted, sp.Rational(1, 2)], *gens, composite=True)
        half = elements.pop()
        gmap = dict(zip(gens, ring.gens))
        trig = {i: (gmap[sc[i][0]], gmap[sc[i][1]]) for i in sorted(trig_used)}
        poly = {i: gmap[q[i]] for i in sorted(poly_used)}
        return cls(ring, list(q), trig, poly, elements, half)

    def element(self, k):
        return self.elements[k]

    def from_expr(self, expr):
        """A new sympy expression (over the input symbols) as a ring element."""
        expr = sp.sympify(expr)
        rep = {}
        syms = dict(zip(self.ring.gens, self.ring.symbols))
        for i, (s, c) in self.trig.items():
            rep[sp.sin(self.q[i])] = syms[s]
            rep[sp.cos(self.q[i])] = syms[c]
        return self.reduce(self.ring.from_expr(sp.expand(expr.xreplace(rep))))

    # ---------------------------------------------------------------- arithmetic
    def reduce(self, p):
        """p modulo sᵢ² + cᵢ² − 1, sin² eliminated (lex order, s before c).

        With exact coefficients (or `term_by_term` set), term by term: sᵢᵉ = sᵢ^(e mod 2)·
        (1 − cᵢ²)^⌊e/2⌋ expanded, the same normal form as the division ``p.rem(basis)`` without
        its bookkeeping (a few times faster). Decimal coefficients keep the division unless
        asked: its sums are rounded in another order, and the reports of the robots with decimal
        masses are compared byte for byte."""
        if self._reduce_coefficient is not None and p != 0:
            fix = self._reduce_coefficient
            p = p.new({m: c for m, c in ((m, fix(c)) for m, c in p.items()) if c})
        if not self._basis or p == 0:
            return p
        if not self.term_by_term:
            return _division_remainder(p, self._basis)
        slots = self._slots
        if all(m[si] < 2 for m in p for si, _ in slots):
            return p
        out: dict = {}
        for m, coef in p.items():
            terms = [(m, coef)]
            for si, ci in slots:
                if any(mm[si] >= 2 for mm, _ in terms):
                    terms = [t for mm, cc in terms for t in _eliminate_sin_squared(mm, cc, si, ci)]
            for mm, cc in terms:
                prev = out.get(mm)
                out[mm] = cc if prev is None else prev + cc
        return p.new({m: c for m, c in out.items() if c})

    def diff(self, p, i):
        """∂p/∂qᵢ with d cᵢ = −sᵢ dqᵢ, d sᵢ = cᵢ dqᵢ."""
        out = self.zero
        if i in self.poly:
            out += p.diff(self.poly[i])
        if i in self.trig:
            s, c = self.trig[i]
            out += c * p.diff(s) - s * p.diff(c)
        return self.reduce(out)

    def depends(self, p, i) -> bool:
        gens = list(self.trig.get(i, ())) + ([self.poly[i]] if i in self.poly else [])
        if not gens:
            return False
        idx = [self.ring.gens.index(g) for g in gens]
        return any(m[k] for m in p.keys() for k in idx)

    def matmul(self, a, b):
        n, m, p = len(a), len(b), len(b[0])
        out = []
        for r in range(n):
            row = []
            for c in range(p):
                acc = self.zero
                for k in range(m):
                    x, y = a[r][k], b[k][c]
                    if x and y:
                        acc += x * y
                row.append(self.reduce(acc))
            out.append(row)
        return out

    def rigid_inverse(self, m):
        """[Rᵀ, −Rᵀt; 0 1] of a 4x4 pose given as lists."""
        out = [[self.zero] * 4 for _ in range(4)]
        for r in range(3):
            for c in range(3):
                out[r][c] = m[c][r]
            out[r][3] = self.reduce(-sum((m[k][r] * m[k][3] for k in range(3)), self.zero))
        out[3][3] = self.one
        return out

    def mdiff(self, m, i):
        return [[self.diff(x, i) for x in row] for row in m]

    def madd(self, a, b):
        return [[x + y for x, y in zip(ra, rb)] for ra, rb in zip(a, b)]

    def zeros(self, n, m=None):
        return [[self.zero] * (m or n) for _ in range(n)]

    def eye(self, n):
        return [[self.one if r == c else self.zero for c in range(n)] for r in range(n)]

    # ---------------------------------------------------------------- conversion
    def to_expr(self, p):
        return p.as_expr(*self._gens_back)

    def expanded_expr(self, p):
        """sp.expand(self.to_expr(p)), built from its terms (`expanded_pairs`)."""
        return sp.Add(*[c * t for c, t in self.expanded_pairs(p)])

    def expanded_pairs(self, p):
        """[(coefficient, trig factor)] of the terms of sp.expand(self.to_expr(p)), as each term's
        as_independent(sin, cos) splits it. With coefficients that are polynomials in the
        parameters, read off the ring's monomials (each term is one trig monomial times one term
        of its coefficient: what expand's distribution makes, without building the product first
        and walking it); other coefficient domains go through expand."""
        inner = getattr(self.ring.domain, "ring", None)
        if inner is None or not hasattr(inner, "symbols"):
            return [t.as_independent(sp.sin, sp.cos) for t in sp.Add.make_args(sp.expand(self.to_expr(p)))]
        to_sympy, psyms, gens = inner.domain.to_sympy, inner.symbols, self._gens_back
        if p == 0:
            return [(sp.S.Zero, sp.S.Zero)]              # as 0.as_independent(sin, cos)
        is_trig = [isinstance(g, (sp.sin, sp.cos)) for g in gens]
        pairs = []
        for monom, coef in p.items():
            # a prismatic joint's variable is a generator of the ring but not a trig factor
            trig = sp.Mul(*[sp.Pow(g, e) for g, e, t in zip(gens, monom, is_trig) if e and t])
            joint = [sp.Pow(g, e) for g, e, t in zip(gens, monom, is_trig) if e and not t]
            for pm, c in coef.items():
                pairs.append((sp.Mul(to_sympy(c), *[sp.Pow(x, e) for x, e in zip(psyms, pm) if e], *joint), trig))
        return pairs

    def to_matrix(self, m):
        return sp.Matrix([[self.to_expr(x) for x in row] for row in m])


def _fixed_angle_reducer(domain):
    """The reduction of the coefficients modulo sin²a + cos²a = 1 for each fixed angle a sympy
    keeps as it is (a pose's Rx(1/3), Rz(2), a DH twist of pi/7: the coefficient domain holds
    sin(1/3) and cos(1/3) as symbols), or None when there is none. Without it Rx(1/3)ᵀ·Rx(1/3)
    is not I in the ring, and a joint's axis in its own frame seems to turn with the joint."""
    gens_of = getattr(domain, "ring", None) or getattr(getattr(domain, "field", None), "ring", None)
    if gens_of is None or not hasattr(gens_of, "symbols"):
        return None
    fixed: dict = {}
    for g, sym in zip(gens_of.gens, gens_of.symbols):
        if isinstance(sym, (sp.sin, sp.cos)) and not sym.args[0].free_symbols:
            fixed.setdefault(sym.args[0], {})[type(sym)] = g
    basis = [pair[sp.sin] ** 2 + pair[sp.cos] ** 2 - 1 for pair in fixed.values() if len(pair) == 2]
    if not basis:
        return None

    def reduced(c):
        if hasattr(c, "numer") and hasattr(c, "denom"):          # a fraction of the parameters
            num, den = c.numer.rem(basis), c.denom.rem(basis)
            return c.new(num, den) if num else c.field.zero
        return c.rem(basis)
    return reduced


def _division_remainder(p, basis):
    """p.rem(basis), sympy's division algorithm step for step — the same subtractions of the same
    coefficients in the same order, the remainder's terms in the same order (decimal coefficients
    round the same) — with the terms left kept in a heap instead of searched for the leading one at
    every step (the division of a long polynomial is quadratic in sympy). The leading term of
    what is left only decreases: a step replaces it by smaller terms (sᵢ² by cᵢ² and 1, sᵢ before
    cᵢ in the lex order), so a term sent to the remainder never returns."""
    ring = p.ring
    if ring.order != lex or not basis:
        return p.rem(basis)
    zero = ring.domain.zero
    monomial_mul = ring.monomial_mul
    term_div = p._term_div()
    divisors = [(g.LT, list(g.iterterms())) for g in basis]
    left = dict(p)
    heap = [tuple(-e for e in m) for m in left]
    heapq.heapify(heap)
    r = ring.zero
    while heap:
        m = tuple(-e for e in heapq.heappop(heap))
        if m not in left:
            continue            # cancelled, or pushed again and already done
        lt = (m, left[m])
        for g_lt, g_terms in divisors:
            tq = term_div(lt, g_lt)
            if tq is not None:
                mq, c = tq
                for mg, cg in g_terms:
                    m1 = monomial_mul(mg, mq)
                    c1 = left.get(m1, zero) - c * cg
                    if not c1:
                        del left[m1]
                    else:
                        if m1 not in left:
                            heapq.heappush(heap, tuple(-e for e in m1))
                        left[m1] = c1
                break
        else:
            r[m] = lt[1]
            del left[m]
    return r


def _eliminate_sin_squared(monom, coef, si: int, ci: int):
    """The terms of coef·monom with sᵉ (e ≥ 2) replaced by s^(e mod 2)·(1 − c²)^⌊e/2⌋."""
    e = monom[si]
    if e < 2:
        return [(monom, coef)]
    k = e // 2
    out = []
    for j in range(k + 1):
        mon = list(monom)
        mon[si] = e % 2
        mon[ci] += 2 * j
        b = math.comb(k, j) * (-1) ** j
        out.append((tuple(mon), coef * b))
    return out


# ---------------------------------------------------------------------- one expression
def pythagorean_reduced(expr, expanded: bool = False):
    """expr as a polynomial in sin θ, cos θ of its angles reduced modulo sin²θ + cos²θ = 1,
    each angle's square eliminated in the direction that leaves fewer operations
    (sin² -> 1 - cos² or cos² -> 1 - sin²); None when an argument of sin/cos is not a
    plain symbol after the addition formulas are expanded (sin(θ/2), sin(ω t))."""
    if expr.atoms(sp.Float):
        return None     # inexact coefficients: reducing them would add round-off terms
    built = _trig_ring_fast(expr if expanded else sp.expand(expr))
    if built is None:
        built = _trig_ring(expr)
    if built is None:
        return None
    poly, pairs, back = built
    # one angle at a time: eliminate sin² (lex order s > c) or cos² (the ring with c > s)
    for s, c in pairs:
        si, ci = poly.ring.gens.index(s), poly.ring.gens.index(c)
        if all(m[si] < 2 and m[ci] < 2 for m in poly.keys()):
            continue            # nothing to eliminate: both normal forms are poly itself
        options = [poly.rem(pythagorean_basis([(s, c)])), eliminate_cos_squared(poly, s, c)]
        exprs = [p.as_expr() for p in options]
        ops = [count_ops(e) for e in exprs]
        # fewer operations, then the text (only compared on a tie)
        pick = 0 if ops[0] < ops[1] or (ops[0] == ops[1] and str(exprs[0]) <= str(exprs[1])) else 1
        poly = options[pick]
    return poly.as_expr().xreplace(back)


def _angle_generators(angles):
    """One (s, c) pair of Dummy generators per angle, and the map sin(a) -> s, cos(a) -> c."""
    pairs = [(sp.Dummy(f"s{k}"), sp.Dummy(f"c{k}")) for k in range(len(angles))]
    to_ring = {}
    for a, (s, c) in zip(angles, pairs):
        to_ring[sp.sin(a)], to_ring[sp.cos(a)] = s, c
    return pairs, to_ring


def _trig_ring(expr):
    """(ring element, [(s, c) generators per angle], generator -> sin/cos) through sympy's
    expand_trig and sring (any coefficient domain), or None."""
    e = sp.expand(sp.expand_trig(expr))
    args = sorted({a.args[0] for a in e.atoms(sp.sin, sp.cos)}, key=sp.default_sort_key)
    if not args or not all(a.is_Symbol for a in args):
        return None
    pairs, to_ring = _angle_generators(args)
    try:
        ring, poly = sring(sp.expand(e.xreplace(to_ring)), *[g for pair in pairs for g in pair])
    except Exception:       # not a polynomial (a sine in a denominator): leave it to trigsimp
        return None
    gmap = dict(zip(ring.symbols, ring.gens))
    back = {gmap[v]: k for k, v in to_ring.items()}
    return poly, [(gmap[s], gmap[c]) for s, c in pairs], {g.as_expr(): f for g, f in back.items()}


def _trig_ring_fast(e):
    """The same ring element built term by term over QQ (the usual chain entry: rational
    coefficients times powers of symbols, sines and cosines), without expanding the
    addition formulas of the whole sum; None for anything else (floats, radicals, a symbol
    in a denominator), which `_trig_ring` handles."""
    terms, others, atoms = [], set(), set()
    for t in sp.Add.make_args(e):
        coeff, factors = t.as_coeff_mul()
        if not coeff.is_Rational:
            return None
        parts = []
        for f in factors:
            b, x = f.as_base_exp()
            if not (x.is_Integer and x > 0):
                return None
            if isinstance(b, (sp.sin, sp.cos)):
                atoms.add(b)
            elif b.is_Symbol:
                others.add(b)
            else:
                return None
            parts.append((b, int(x)))
        terms.append((coeff, parts))
    if not atoms:
        return None
    expanded = {a: sp.expand(sp.expand_trig(a)) for a in atoms}
    angles = sorted({x.args[0] for v in expanded.values() for x in v.atoms(sp.sin, sp.cos)},
                    key=sp.default_sort_key)
    if not angles or not all(a.is_Symbol for a in angles):
        return None
    pairs, to_ring = _angle_generators(angles)
    # the other symbols are the coefficient domain (as sring makes it): the key that picks
    # each angle's elimination counts the operations of that grouped form
    symbols = [g for pair in pairs for g in pair]
    domain = QQ.poly_ring(*sorted(others, key=sp.default_sort_key)) if others else QQ
    ring, *gens = poly_ring(symbols, domain)
    gmap = dict(zip(symbols, gens))
    try:
        value = {a: ring.from_expr(v.xreplace(to_ring)) for a, v in expanded.items()}
    except Exception:
        return None
    value.update({o: ring.ground_new(domain.from_sympy(o)) for o in others})
    poly = ring.zero
    for coeff, parts in terms:
        term = ring(QQ(int(coeff.p), int(coeff.q)))
        for b, x in parts:
            term *= value[b] ** x
        poly += term
    back = {s: sp.sin(a) for a, (s, _) in zip(angles, pairs)}
    back.update({c: sp.cos(a) for a, (_, c) in zip(angles, pairs)})
    return poly, [(gmap[s], gmap[c]) for s, c in pairs], back


def eliminate_cos_squared(poly, s, c):
    """poly with cos² -> 1 - sin²: each c^(2k+r) becomes c^r (1 - s²)^k (r = 0, 1), the
    normal form of degree at most 1 in c."""
    ring = poly.ring
    ci = ring.gens.index(c)
    out = ring.zero
    for monom, coeff in poly.terms():
        m = list(monom)
        k, m[ci] = divmod(m[ci], 2)
        out += ring({tuple(m): coeff}) * (1 - s ** 2) ** k
    return out


# ---------------------------------------------------------------------- Fourier form
def _norm(kind, k):
    """Canonical key of cos(k·q) / sin(k·q): first non-zero entry of k positive."""
    for x in k:
        if x != 0:
            if x < 0:
                return kind, tuple(-y for y in k), (-1 if kind == "sin" else 1)
            return kind, k, 1
    return kind, k, (0 if kind == "sin" else 1)


def _fmul(a: dict, b: dict) -> dict:
    """Product of two real Fourier series {(kind, k): Fraction}."""
    from fractions import Fraction

    out: dict = {}
    half = Fraction(1, 2)
    for (ka, va), ca in a.items():
        for (kb, vb), cb in b.items():
            c = ca * cb * half
            plus = tuple(x + y for x, y in zip(va, vb))
            minus = tuple(x - y for x, y in zip(va, vb))
            if ka == "cos" and kb == "cos":
                parts = (("cos", minus, c), ("cos", plus, c))
            elif ka == "sin" and kb == "sin":
                parts = (("cos", minus, c), ("cos", plus, -c))
            elif ka == "sin":  # sin a cos b
                parts = (("sin", plus, c), ("sin", minus, c))
            else:  # cos a sin b = sin b cos a
                parts = (("sin", plus, c), ("sin", tuple(-x for x in minus), c))
            for kind, k, coef in parts:
                kind, k, sign = _norm(kind, k)
                if sign == 0:
                    continue
                key = (kind, k)
                out[key] = out.get(key, 0) + sign * coef
    return {k: v for k, v in out.items() if v != 0}


def fourier_dict(alg: TrigAlgebra, p) -> dict:
    """p as {(kind, k, prismatic exponents): domain coefficient}, kind cos|sin of k·q.

    Once per element (the report's readable form asks for both the Fourier and the
    product form of each entry); callers only read the dictionary."""
    memo = alg.__dict__.setdefault("_fourier_dict_memo", {})
    out = memo.get(p)
    if out is None:
        out = memo[p] = _fourier_dict(alg, p)
    return out


def _fourier_dict(alg: TrigAlgebra, p) -> dict:
    from fractions import Fraction

    ring = alg.ring
    n = len(alg.q)
    pos = {}
    for i, (s, c) in alg.trig.items():
        pos[i] = (ring.gens.index(s), ring.gens.index(c))
    poly_pos = [ring.gens.index(g) for g in alg.poly.values()]
    cache = alg.__dict__.setdefault("_fourier_cache", {})
    acc: dict = {}
    dom = ring.domain
    for monom, coeff in p.terms():
        tkey = tuple(monom[k] for ij in pos.values() for k in ij)
        series = cache.get(tkey)
        if series is None:
            series = {("cos", (0,) * n): Fraction(1)}
            for i, (si, ci) in pos.items():
                e_i = tuple(1 if t == i else 0 for t in range(n))
                for _ in range(monom[ci]):
                    series = _fmul(series, {("cos", e_i): Fraction(1)})
                for _ in range(monom[si]):
                    series = _fmul(series, {("sin", e_i): Fraction(1)})
            cache[tkey] = series
        pkey = tuple(monom[k] for k in poly_pos)
        for (kind, k), r in series.items():
            key = (kind, k, pkey)
            acc[key] = acc.get(key, dom.zero) + coeff * dom.convert(
                sp.Rational(r.numerator, r.denominator))
    return {k: v for k, v in acc.items() if v}


def _trig(alg, kind, k):
    if not any(k):
        return sp.S.One if kind == "cos" else sp.S.Zero
    arg = sp.Add(*[kk * alg.q[i] for i, kk in enumerate(k)])
    return sp.cos(arg) if kind == "cos" else sp.sin(arg)


def _mono(alg, pkey):
    return sp.Mul(*[q ** e for q, e in zip([alg.q[i] for i in alg.poly], pkey)])


def fourier_terms(alg: TrigAlgebra, p):
    """p as Σ coeff · {cos|sin}(k·q) · (prismatic monomial): list of (coeff, trig) pairs.

    Products of cosines and sines become cosines and sines of sums of angles (the form
    `trigsimp` reaches, e.g. cos(2θ₂ + θ₃)), at the cost of a dictionary walk.
    """
    dom = alg.ring.domain
    return [(dom.to_sympy(c) * _mono(alg, pkey), _trig(alg, kind, k))
            for (kind, k, pkey), c in fourier_dict(alg, p).items()]


def product_terms(alg: TrigAlgebra, p):
    """The Fourier form folded back into short products (the textbook look):

    * cos A + cos B with equal coefficients -> 2 cos((A+B)/2) cos((A−B)/2), and
      sin A + sin B -> 2 sin((A+B)/2) cos((A−B)/2), when the half sums are whole;
    * cos 2x -> 2 cos²x − 1 and sin 2x -> 2 sin x cos x.

    E.g. L2 L3 m3 (cos θ3 + cos(2θ2 + θ3))/2 -> L2 L3 m3 cos θ2 cos(θ2 + θ3).
    """
    dom = alg.ring.domain
    terms = fourier_dict(alg, p)
    out = []
    by_coef: dict = {}
    for key in sorted(terms):
        kind, k, pkey = key
        if any(k):
            by_coef.setdefault((kind, pkey, terms[key]), []).append(k)
    used = set()
    for (kind, pkey, coef), ks in sorted(by_coef.items(), key=lambda x: (x[0][0], x[0][1],
                                                                         str(x[0][2]))):
        free = list(ks)
        while len(free) >= 2:
            a = free.pop(0)
            partner = next((b for b in free if all((x + y) % 2 == 0 for x, y in zip(a, b))),
                           None)
            if partner is None:
                continue
            free.remove(partner)
            b = partner
            u = tuple((x + y) // 2 for x, y in zip(a, b))
            v = tuple((x - y) // 2 for x, y in zip(a, b))
            used.add((kind, a, pkey))
            used.add((kind, b, pkey))
            first = _trig(alg, kind, u)
            second = _trig(alg, "cos", v)
            out.append((2 * dom.to_sympy(coef) * _mono(alg, pkey), first * second))
    for (kind, k, pkey), coef in terms.items():
        if (kind, k, pkey) in used:
            continue
        c = dom.to_sympy(coef)
        mono = _mono(alg, pkey)
        if any(k) and all(x % 2 == 0 for x in k):
            h = tuple(x // 2 for x in k)
            if kind == "cos":
                out.append((2 * c * mono, _trig(alg, "cos", h) ** 2))
                out.append((-c * mono, sp.S.One))
            else:
                out.append((2 * c * mono, _trig(alg, "sin", h) * _trig(alg, "cos", h)))
        else:
            out.append((c * mono, _trig(alg, kind, k)))
    return out
