"""Polynomials in cᵢ = cos qᵢ, sᵢ = sin qᵢ (and prismatic qᵢ), reduced modulo sᵢ² + cᵢ² = 1.

This is the engine's fast algebra: every entry of a pose, L matrix or energy of a serial
robot is such a polynomial, with coefficients in the parameters. sympy's sparse polynomial
rings multiply and differentiate these in microseconds, and the reduction sᵢ² → 1 − cᵢ²
(a division by the Gröbner basis {sᵢ² + cᵢ² − 1}) gives a canonical form, so every
cancellation that `trigsimp` would find through cos² + sin² = 1 happens at once, for free.

`TrigAlgebra.from_inputs` returns None when an input uses a joint in a way that is not a
polynomial in cos qᵢ, sin qᵢ, qᵢ (e.g. sin(qᵢ/2)); the engine then falls back to sympy
expressions with small-piece `trigsimp`.
"""

from __future__ import annotations

import sympy as sp
from sympy.polys.rings import sring

__all__ = ["TrigAlgebra"]


class TrigAlgebra:
    def __init__(self, ring, q, trig, poly, elements, half):
        self.ring = ring
        self.half = half
        self.q = q
        self.trig = trig  # joint index -> (s, c) ring generators
        self.poly = poly  # joint index -> q ring generator
        self.zero = ring.zero
        self.one = ring.one
        self._basis = [s ** 2 + c ** 2 - 1 for s, c in trig.values()]
        self._back = {}
        for i, (s, c) in trig.items():
            self._back[s.as_expr()] = sp.sin(q[i])
            self._back[c.as_expr()] = sp.cos(q[i])
        self.elements = elements

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
        half = elements.pop()
        gmap = dict(zip(gens, ring.gens))
        trig = {i: (gmap[sc[i][0]], gmap[sc[i][1]]) for i in sorted(trig_used)}
        poly = {i: gmap[q[i]] for i in sorted(poly_used)}
        return cls(ring, list(q), trig, poly, elements, half)

    def element(self, k):
        return self.elements[k]

    # ---------------------------------------------------------------- arithmetic
    def reduce(self, p):
        if not self._basis or p == 0:
            return p
        return p.rem(self._basis)

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
        return p.as_expr().xreplace(self._back)

    def to_matrix(self, m):
        return sp.Matrix([[self.to_expr(x) for x in row] for row in m])


class SympyAlgebra:
    """The same interface on plain sympy expressions (fallback, small-piece trigsimp)."""

    zero = sp.S.Zero
    one = sp.S.One
    half = sp.S.Half

    def __init__(self, q, exprs, simplify=True):
        from robosolve.dynamics.engine import tsimp

        self.q = list(q)
        self.elements = [sp.sympify(e) for e in exprs]
        self._simp = tsimp if simplify else (lambda e: e)

    def element(self, k):
        return self.elements[k]

    def reduce(self, p):
        return self._simp(p)

    def diff(self, p, i):
        return self._simp(sp.diff(p, self.q[i]))

    def depends(self, p, i) -> bool:
        return sp.sympify(p).has(self.q[i])

    def to_expr(self, p):
        return p

    def to_matrix(self, m):
        return sp.Matrix(m)


for _name in ("matmul", "rigid_inverse", "mdiff", "madd", "zeros", "eye"):
    setattr(SympyAlgebra, _name, getattr(TrigAlgebra, _name))


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


def fourier_terms(alg: TrigAlgebra, p):
    """p as Σ coeff · {cos|sin}(k·q) · (prismatic monomial): list of (coeff_expr, trig_expr).

    Products of cosines and sines become cosines and sines of sums of angles (the form
    `trigsimp` reaches, e.g. cos(2θ₂ + θ₃)), at the cost of a dictionary walk.
    """
    from fractions import Fraction

    ring = alg.ring
    n = len(alg.q)
    pos = {}
    for i, (s, c) in alg.trig.items():
        pos[i] = (ring.gens.index(s), ring.gens.index(c))
    poly_pos = {i: ring.gens.index(g) for i, g in alg.poly.items()}
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
        pkey = tuple(monom[k] for k in poly_pos.values())
        for (kind, k), r in series.items():
            key = (kind, k, pkey)
            acc[key] = acc.get(key, dom.zero) + coeff * dom.convert(
                sp.Rational(r.numerator, r.denominator))
    out = []
    for (kind, k, pkey), coeff in acc.items():
        if not coeff:
            continue
        arg = sp.Add(*[kk * alg.q[i] for i, kk in enumerate(k)])
        trig = sp.S.One if not any(k) else (sp.cos(arg) if kind == "cos" else sp.sin(arg))
        mono = sp.Mul(*[alg.q[i] ** e for i, e in zip(poly_pos, pkey)])
        out.append((dom.to_sympy(coeff), trig * mono))
    return out
