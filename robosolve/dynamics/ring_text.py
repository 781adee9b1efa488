"""The text of a big robot's equations of motion, straight from the trig ring.

A 7-joint arm's mass matrix has thousands of terms (the Franka Panda's: 5 549 monomials in
cos qᵢ, sin qᵢ and the parameters, its velocity terms 27 000): building sympy expressions of
them and printing those takes minutes. Here the reduced polynomials of the dynamics engine
(`core/trigring.TrigAlgebra`) are written out directly, in a form sympy reads back
(`sympy.sympify`) to the same polynomial:

* nested by joint, first joint outermost: the terms that share sin q₁ (cos q₁, neither) are
  written once as ``sin(q1)*(…)``, inside them the same with q₂, and so on, so every trig
  factor is printed once per group instead of once per term;
* the innermost factor is the coefficient, a polynomial in the parameters with exact
  (rational) or decimal numbers (decimals as Python's shortest round-trip `repr`).

The text depends only on the polynomial (terms sorted by their exponents): deterministic.
`term_count` is the number of terms of the expanded polynomial (what a report says of an
entry too long to show).
"""

from __future__ import annotations

__all__ = ["RingText"]


def _number(c) -> tuple[bool, str]:
    """(negative, |c| as text) of a ground-domain number (rational, integer or float)."""
    if hasattr(c, "numerator") and hasattr(c, "denominator") and not isinstance(c, float):
        num, den = int(c.numerator), int(c.denominator)
        text = str(abs(num)) if den == 1 else f"{abs(num)}/{den}"
        return num < 0, text
    x = float(c)
    return x < 0, repr(abs(x))


def _join(terms: list[tuple[bool, str]]) -> str:
    """A sum of signed terms: 'a - b + c'."""
    out = []
    for k, (neg, t) in enumerate(terms):
        if k == 0:
            out.append(("-" if neg else "") + t)
        else:
            out.append((" - " if neg else " + ") + t)
    return "".join(out) or "0"


def _times(factor: str, terms: list[tuple[bool, str]]) -> tuple[bool, str]:
    """factor · (sum of terms) as one signed term."""
    if len(terms) == 1:
        neg, t = terms[0]
        return neg, factor if t == "1" else f"{t}*{factor}"
    return False, f"{factor}*({_join(terms)})"


def _power(name: str, e: int) -> str:
    return name if e == 1 else f"{name}**{e}"


class RingText:
    """Writes elements of a `TrigAlgebra` as nested sums (see the module's doc)."""

    def __init__(self, alg):
        self.alg = alg
        ring = alg.ring
        index = {g: k for k, g in enumerate(ring.gens)}
        # one level per joint, in joint order: [(exponent slot, name)], sin before cos
        self.levels = []
        for i, qi in enumerate(alg.q):
            level = []
            if i in alg.trig:
                s, c = alg.trig[i]
                level += [(index[s], f"sin({qi})"), (index[c], f"cos({qi})")]
            if i in alg.poly:
                level.append((index[alg.poly[i]], str(qi)))
            if level:
                self.levels.append(level)
        domain = ring.domain
        self.params = [str(s) for s in getattr(domain, "symbols", ())]
        self.nested = bool(self.params)
        self._memo: dict = {}       # id(element) -> (element, its signed terms)

    # ------------------------------------------------------------ counts
    def term_count(self, p) -> int:
        if not self.nested:
            return len(p)
        return sum(len(c) for c in p.values())

    # ------------------------------------------------------------ text
    def _coefficient(self, c) -> list[tuple[bool, str]]:
        if not self.nested:
            return [_number(c)]
        out = []
        for monom, num in sorted(c.terms(), reverse=True):
            neg, text = _number(num)
            factors = [_power(self.params[k], e) for k, e in enumerate(monom) if e]
            if factors:
                text = "*".join(factors) if text in ("1", "1.0") else text + "*" + "*".join(factors)
            out.append((neg, text))
        return out

    def _terms(self, items, level: int) -> list[tuple[bool, str]]:
        if level == len(self.levels):
            (_, coef), = items
            return self._coefficient(coef)
        slots = self.levels[level]
        groups: dict = {}
        for monom, coef in items:
            groups.setdefault(tuple(monom[k] for k, _ in slots), []).append((monom, coef))
        out = []
        for key in sorted(groups, reverse=True):
            inner = self._terms(groups[key], level + 1)
            factor = "*".join(_power(name, e) for (_, name), e in zip(slots, key) if e)
            if factor:
                out.append(_times(factor, inner))
            else:
                out.extend(inner)
        return out

    def signed_terms(self, p) -> list[tuple[bool, str]]:
        """The terms of p's text (remembered: the left sides of the equations repeat M and c)."""
        if p == 0:
            return []
        hit = self._memo.get(id(p))
        if hit is None or hit[0] is not p:
            hit = self._memo[id(p)] = (p, self._terms(sorted(p.items()), 0))
        return hit[1]

    def text(self, p) -> str:
        return _join(self.signed_terms(p))

    def weighted_sum(self, pairs) -> str:
        """Σ factor·p over (factor text, element) pairs, each product written once: the
        velocity terms Σ q̇ⱼq̇ₖ·Γ, the kinetic energy, the left side of an equation."""
        terms = []
        for factor, p in pairs:
            inner = self.signed_terms(p)
            if not inner:
                continue
            if factor:
                terms.append(_times(factor, inner))
            else:
                terms.extend(inner)
        return _join(terms)
