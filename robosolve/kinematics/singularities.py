"""Singular configurations of a Jacobian, found symbolically.

Method (what a teacher does by hand, made systematic):

* square J: factor det J; every factor that contains a joint is solved for a joint;
* non-square J: J loses rank when all its maximal minors vanish (Cauchy–Binet:
  det(J Jᵀ) is the sum of their squares). The smallest minor is factored and each
  factor solved for a joint; the value is substituted into the other minors and the
  search goes on with the remaining joints, so a condition may fix several joints
  (a planar 3R arm is singular only when θ2 and θ3 are both 0 or π).

Values: a revolute joint gets every value in (−π, π] (complete: a factor in sin/cos
of one joint is also solved as a polynomial system in c = cos q, s = sin q with
c² + s² = 1, whose solutions map one-to-one onto (−π, π] through atan2); a
prismatic joint every real value. A factor in which no joint can be isolated
(its solution would depend non-linearly on other joints) becomes an equation
string ``"expr = 0"``. Parameters are assumed generic (non-zero): a factor free of
joints, such as L1*L2, never vanishes.

The functions here never time themselves. The work of the search is counted instead
(`SearchBudget`: the expression nodes handed to the factoring, the same on every machine):
past its budget the search stops with `SearchTooLong`, and the caller answers numerically. A
caller's time limit is only a safety net above that count.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import sympy as sp

from robosolve.core.angles import wrap_angle
from robosolve.core.simplify import (bounded_full, determinant_factors, factored, factored_determinant,
                                     float_placeholders, full, is_zero, jacobian_entry)
from robosolve.kinematics.jacobian_math import rank_measure
from robosolve.core.opcount import count_ops
from robosolve.core.printing import latex as print_latex

__all__ = ["Condition", "SearchBudget", "SearchTooLong", "SingularityResult", "find_singularities",
           "wrap_angle"]


def _text(expr) -> str:
    """str(expr) (sympy's sstr), each expression printed once per process: a condition's
    equations are printed for its sort key, its duplicates' key and its mapping (the 9 minors
    of a 6R flange's rank condition, some hundred terms each)."""
    from robosolve.core.printing import SharedStrPrinter

    return SharedStrPrinter().doprint(expr)


# A factor of one joint longer than this (sympy operations, in c = cos q, s = sin q) is not solved
# as a polynomial system (its radicals with symbolic parameters take minutes): it stays an equation.
SOLVE_OPS = 30


class SearchTooLong(Exception):
    """The search needed more work (expression nodes factored) than its budget."""


class SearchBudget:
    """The count of the search's work: the expression nodes of every distinct expression it
    factors (up to sign: the branches q = 0 and q = π often leave the same minors, which the
    memo of the factoring answers at once). `nodes=None`: unbounded (the count is still kept).
    The count depends only on the search's own history, never on what an earlier problem left
    in the memo, so the outcome is the same on every machine and in every batch."""

    def __init__(self, nodes: int | None = None):
        self.nodes, self.spent = nodes, 0
        self._seen: set = set()

    def spend(self, expr):
        from robosolve.core.simplify import expression_nodes

        expr = sp.sympify(expr)
        if expr in self._seen or -expr in self._seen:
            return
        self._seen.add(expr)
        self.spent += expression_nodes(expr)
        if self.nodes is not None and self.spent > self.nodes:
            raise SearchTooLong(f"the search for the rank conditions needs more than {self.nodes:,} expression "
                                "nodes of factoring (a count, so the outcome is the same on every machine)")


@dataclass(frozen=True)
class Condition:
    """One singular condition: joint values (in joint order) and/or equations."""

    values: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()
    equations: tuple[sp.Expr, ...] = ()
    factor: sp.Expr | None = None
    names: tuple[str, ...] = ()

    def mapping(self) -> dict[str, str] | str:
        """The spec's layout: {joint: "value"} or an equation string."""
        if self.equations:
            eqs = [f"{_text(e)} = 0" for e in self.equations]
            eqs += [f"{q} = {_text(v)}" for q, v in self.values]
            return ", ".join(eqs)
        return {str(q): _text(v) for q, v in self.values}

    def latex(self) -> str:
        parts = [f"{print_latex(q)} = {print_latex(v)}" for q, v in self.values]
        parts = [f"{print_latex(e)} = 0" for e in self.equations] + parts
        return r",\ ".join(parts)


@dataclass
class SingularityResult:
    kind: str                      # 'det' (square J) or 'gram' (det(J Jᵀ) / det(Jᵀ J))
    measure: sp.Expr               # det J, or det(J Jᵀ), simplified and factored
    conditions: list[Condition]
    minors: list[sp.Expr] = field(default_factory=list)   # non-square only
    notes: list[str] = field(default_factory=list)


# ---------------------------------------------------------------------------
# angles

def _wrap_linear(value, joints):
    """θ = (linear combination of joints) + constant: wrap the constant part."""
    v = sp.expand(value)
    const = v.subs({q: 0 for q in joints})
    if const.free_symbols:
        return v
    return (v - const) + wrap_angle(const)


def _is_linear_in(expr, joints) -> bool:
    try:
        poly = sp.Poly(expr, *joints)
    except sp.PolynomialError:
        return False
    return poly.total_degree() <= 1 and all(not c.free_symbols for c in poly.coeffs())


# ---------------------------------------------------------------------------
# numeric helpers

def _numeric(expr, subs) -> complex | None:
    try:
        val = complex(sp.sympify(expr).evalf(30, subs=subs))
    except (TypeError, ValueError):
        return None
    if not (math.isfinite(val.real) and math.isfinite(val.imag)):
        return None
    return val


def _vanishes_with_the_values(expr, joints, params: Mapping) -> bool:
    """True when a factor of expr free of the joints is 0 with the given parameter values: d3 − d5
    of a KUKA iiwa (d3 = d5 = 0.4) makes a minor vanish whatever the joints, so the configurations
    it leaves singular are singular on this arm (a search for generic parameters missed them)."""
    for f in sp.Mul.make_args(expr):
        base = f.base if f.is_Pow else f
        if not base.free_symbols or any(base.has(q) for q in joints) or base.free_symbols - set(params):
            continue
        terms = [_numeric(t, dict(params)) for t in sp.Add.make_args(base)]
        if len(terms) < 2 or any(t is None for t in terms):
            continue
        if abs(sum(terms)) <= 1e-12 * sum(abs(t) for t in terms):
            return True
    return False


def _is_real_value(value, params: Mapping) -> bool | None:
    """True/False when the value can be evaluated with the parameters, else None."""
    value = sp.sympify(value)
    if value.free_symbols - set(params):
        return None
    val = _numeric(value, dict(params))
    if val is None:
        return None
    return abs(val.imag) <= 1e-9 * max(1.0, abs(val.real))


def _sample_params(symbols, params: Mapping) -> dict:
    """Given parameter values, plus distinct positive samples for the others."""
    out = {}
    for i, s in enumerate(sorted(symbols, key=sp.default_sort_key)):
        out[s] = params.get(s) if params.get(s) is not None else 0.7 + 0.13 * i
    return out


# ---------------------------------------------------------------------------
# solving one factor for one joint

def _pretty_atan2(s_val, c_val, sample):
    """atan2(s, c) as acos/asin where the branch is clear, else atan2."""
    s_val, c_val = full(s_val), full(c_val)
    direct = sp.atan2(s_val, c_val)
    if not direct.has(sp.atan2):
        return direct
    syms = (s_val.free_symbols | c_val.free_symbols)
    sub = _sample_params(syms, sample)
    sn, cn = _numeric(s_val, sub), _numeric(c_val, sub)
    if sn is None or cn is None or abs(sn.imag) > 1e-12 or abs(cn.imag) > 1e-12:
        return direct
    sn, cn = sn.real, cn.real
    root_c = math.sqrt(max(0.0, 1 - cn * cn))
    if abs(abs(sn) - root_c) < 1e-9:
        return sp.acos(c_val) if sn >= 0 else -sp.acos(c_val)
    return direct


def _solve_revolute(f, q, sample):
    """Every q in (−π, π] with f(q) = 0 (f a function of q and parameters), or None."""
    sol = None
    if not (f.is_Add and f.free_symbols - {q}):
        # solveset on a sum with symbolic coefficients (a3 sin q3 + d4 cos q3) spends
        # seconds before giving up: such factors go straight to the polynomial system
        try:
            sol = sp.solveset(f, q, sp.Interval.Lopen(-sp.pi, sp.pi))
        except (NotImplementedError, ValueError, TypeError):
            sol = None
    if isinstance(sol, sp.FiniteSet) and all(not v.has(q) for v in sol):
        return [wrap_angle(v) for v in sol]
    # polynomial system in c = cos q, s = sin q
    c, s = sp.Dummy("c"), sp.Dummy("s")
    g = sp.expand_trig(sp.expand(f.rewrite(sp.cos, sp.sin) if f.has(sp.tan) else f))
    g = g.subs({sp.cos(q): c, sp.sin(q): s})
    if g.has(q):
        return None
    g = sp.together(g)
    g = sp.numer(g)
    linear = _solve_linear_trig(g, c, s, sample)
    if linear is not None:
        return linear
    if count_ops(g) > SOLVE_OPS:
        return None          # kept as an equation: solve's radicals of a long factor take minutes
    try:
        sols = sp.solve([g, c**2 + s**2 - 1], [c, s], dict=True)
    except (NotImplementedError, ValueError, TypeError):
        return None
    out = []
    for d in sols:
        if c not in d or s not in d:
            return None      # a free branch: f vanishes identically along a family
        out.append(wrap_angle(_pretty_atan2(d[s], d[c], sample)))
    return out


def _in_range(value, sample):
    """value, or value ∓ 2π, in (−π, π] with the given parameters (value unchanged when it
    cannot be evaluated)."""
    val = _numeric(value, _sample_params(value.free_symbols, sample))
    if val is None or abs(val.imag) > 1e-12:
        return value
    if val.real > math.pi + 1e-12:
        return value - 2 * sp.pi
    if val.real <= -math.pi + 1e-12:
        return value + 2 * sp.pi
    return value


def _solve_linear_trig(g, c, s, sample):
    """The roots of A cos q + B sin q + K = 0 (g in c = cos q, s = sin q, of degree 1) in closed
    form, the course's way: tan q = −A/B when K = 0; sin q = −K/B when A = 0; cos q = −K/A when
    B = 0; else q = atan2(B, A) ± acos(−K/√(A² + B²)). None when g is not of that form or a
    coefficient the formula divides by vanishes for the given parameters. (sympy's solve of the
    system with c² + s² = 1 spends seconds on such an equation when A, B hold roots, and writes
    its roots nested.)"""
    try:
        poly = sp.Poly(g, c, s)
    except sp.PolynomialError:
        return None
    if poly.total_degree() != 1:
        return None
    a, b = poly.coeff_monomial(c), poly.coeff_monomial(s)
    k = poly.coeff_monomial(1)

    def nonzero(x):
        val = _numeric(x, _sample_params(x.free_symbols, sample))
        return val is not None and abs(val) > 1e-12

    if k == 0:
        if b == 0:
            return [-sp.pi / 2, sp.pi / 2] if nonzero(a) else None
        if not nonzero(b):
            return None
        first = sp.atan(factored(-a / b))
        return [first, _in_range(first + sp.pi, sample)]
    if a == 0:
        if not nonzero(b):
            return None
        first = sp.asin(factored(-k / b))
        return [first, _in_range(sp.pi - first, sample)]
    if b == 0:
        if not nonzero(a):
            return None
        first = sp.acos(factored(-k / a))
        return [first, -first]
    r = sp.sqrt(factored(a**2 + b**2))
    if not nonzero(r):
        return None
    phi, delta = sp.atan2(b, a), sp.acos(factored(-k / r))
    if delta == 0 or delta == sp.pi:         # |K| = √(A² + B²): one (double) root
        return [_in_range(phi + delta, sample)]
    return [_in_range(phi + delta, sample), _in_range(phi - delta, sample)]


def _solve_prismatic(f, q):
    try:
        sols = sp.solve(f, q)
    except (NotImplementedError, ValueError, TypeError):
        return None
    out = []
    for v in sols:
        if v.is_number and not v.is_real:
            continue
        out.append(bounded_full(v))
    return out


def _isolate(f, joints, kinds, sample):
    """(joint, [values]) solving factor f = 0, or None when no joint can be isolated."""
    present = [q for q in joints if f.has(q)]
    if len(present) == 1:
        q = present[0]
        vals = (_solve_revolute(f, q, sample) if kinds[q] == "revolute"
                else _solve_prismatic(f, q))
        if vals is not None:
            return q, vals
        return None
    # a prismatic joint appearing linearly: q = expression of the others
    for q in reversed(present):
        if kinds[q] != "prismatic":
            continue
        try:
            poly = sp.Poly(f, q)
        except sp.PolynomialError:
            continue
        if poly.degree() == 1:
            a, b = poly.all_coeffs()
            return q, [jacobian_entry(-b / a)]
    # revolute joints through a single angle α = linear combination of joints:
    # solve g(α) = 0 in (−π, π], then isolate the last joint of α
    args = {a.args[0] for a in f.atoms(sp.sin, sp.cos, sp.tan)}
    if len(args) == 1:
        alpha = args.pop()
        if _is_linear_in(alpha, present) and all(kinds[q] == "revolute" for q in present):
            u = sp.Dummy("u")
            g = f.subs(alpha, u)
            if not any(g.has(q) for q in present):
                vals = _solve_revolute(g, u, sample)
                q = [p for p in present if alpha.has(p)][-1]
                coeff = sp.Poly(alpha, *present).coeff_monomial(q)
                if vals is not None and coeff in (1, -1):
                    rest = alpha - coeff * q
                    return q, [_wrap_linear(sp.expand((v - rest) / coeff), present) for v in vals]
    return None


# ---------------------------------------------------------------------------
# the search

def _joint_factors(expr, joints, work=None):
    """Distinct factors of expr that contain a joint, in a deterministic order."""
    if work is not None:
        work.spend(expr)
    out = [f for f in determinant_factors(expr) if any(f.has(q) for q in joints)]
    return sorted(out, key=lambda e: (count_ops(e), sp.default_sort_key(e)))


def _search(exprs, joints, kinds, fixed, sample, depth=0, work=None):
    """All conditions making every expression of exprs vanish (given fixed values); `work`
    (a SearchBudget) counts the factoring."""
    work = work if work is not None else SearchBudget()
    live = []
    for e in exprs:
        if fixed:
            e1 = _clean_values(sp.sympify(e).subs(fixed), sample)
            if not e1.is_polynomial() and any(p.exp.is_negative for p in e1.atoms(sp.Pow)):
                # a joint value with a denominator of parameters: the zeros are the numerator's
                # (only then: together() on a long sum with roots costs more than its factoring)
                e1 = sp.numer(sp.together(e1))
            work.spend(e1)
        e2 = factored_determinant(e1) if fixed else e
        if fixed and e2.has(sp.Abs):
            e3 = _signed_abs(e2, sample)
            e2 = factored_determinant(e3) if e3 is not e2 else e2
        if e2 == 0 or _vanishes_with_the_values(e2, joints, sample):
            continue
        if not any(e2.has(q) for q in joints):
            return []                # a non-zero parameter expression: never singular here
        live.append(e2)
    if not live:
        return [Condition(values=tuple(fixed.items()))]
    live.sort(key=lambda e: (count_ops(e), sp.default_sort_key(e)))
    first, rest = live[0], live[1:]
    free = [q for q in joints if q not in fixed]
    results = []
    for fac in _joint_factors(first, free, work):
        iso = _isolate(fac, free, kinds, sample)
        if iso is None or depth > len(joints):
            # the other expressions, but those the factor already makes vanish (its multiples)
            eqs = (fac,) + tuple(r for r in rest if not _multiple_of(r, fac))
            results.append(Condition(values=tuple(fixed.items()), equations=eqs, factor=fac))
            continue
        q, vals = iso
        branches = [({**fixed, q: v}, rest) for v in vals]
        # a·q + b = 0 solved as q = −b/a misses where a and b vanish together (q free there)
        branches += [(fixed, both + rest) for both in [_vanishing_coefficient(fac, q, free, kinds)] if both]
        for sub, left in branches:
            for cond in _search(left, joints, kinds, sub, sample, depth + 1, work):
                results.append(Condition(values=cond.values, equations=cond.equations,
                                         factor=cond.factor if cond.factor is not None else fac))
    return results


def _vanishing_coefficient(f, q, free, kinds) -> list:
    """[a, b] when f = a·q + b is linear in the prismatic joint q with a coefficient a that
    holds other joints (a·d4 + b = 0 with a = cos(q2 + q3): the configurations where a = b = 0
    are singular for every d4), else []."""
    if kinds[q] != "prismatic":
        return []
    try:
        poly = sp.Poly(f, q)
    except sp.PolynomialError:
        return []
    if poly.degree() != 1:
        return []
    a, b = poly.all_coeffs()
    return [a, b] if any(a.has(p) for p in free if p != q) else []


_INVERSE_TRIG = (sp.acos, sp.asin, sp.atan, sp.atan2)


def _clean_values(expr, params):
    """After a joint value is substituted: sin/cos of a sum holding an inverse trig function
    (sin(q2 + acos(x))) expanded and evaluated, the roots split and the |·| of the parameters
    resolved (`_signed_abs`) before the factoring, which otherwise writes sin(acos x) as a
    nested root it cannot factor (PolynomialError: the whole search lost)."""
    if expr.has(*_INVERSE_TRIG):
        expr = expr.replace(lambda x: isinstance(x, (sp.sin, sp.cos)) and x.args[0].is_Add
                            and x.args[0].has(*_INVERSE_TRIG), lambda x: sp.expand_trig(x))
    if expr.has(sp.Pow, sp.Abs):
        expr = _signed_abs(expr, params)
    return expr


def _split_root(root, params):
    """√(N/D) (or its inverse) with N/D factored, as √N/√D when D > 0 with the given parameters
    (so that the root leaves the denominators: numer(together(·)) is then a polynomial)."""
    num, den = sp.fraction(factored(sp.together(root.base)))
    if den != 1 and not (den.free_symbols - set(params)):
        val = _numeric(den, dict(params))
        if val is not None and abs(val.imag) < 1e-12 and val.real > 0:
            return sp.Pow(num, root.exp) / sp.Pow(den, root.exp)
    return sp.Pow(num / den, root.exp)


def _signed_abs(expr, params):
    """|x| of a parameter expression x written ±x by the sign of its value with the given
    parameters, and the square roots' arguments factored first (√(1 − a²/(a² + b²)) is |b|/√(a² + b²)):
    a joint value such as acos(-a4/sqrt(a4² + dt²)) (its branch chosen with the given
    parameters) brings sin = |dt|/r into the other minors, and the factoring cannot split a
    factor through |dt| or a nested root (a family lost, or the search stopped)."""
    if expr.has(sp.Pow):
        expr = expr.replace(lambda x: x.is_Pow and x.exp in (sp.S.Half, -sp.S.Half) and bool(x.base.free_symbols),
                            lambda x: _split_root(x, params))
    if not expr.has(sp.Abs):
        return expr
    rep = {}
    for a in expr.atoms(sp.Abs):
        arg = a.args[0]
        if arg.free_symbols - set(params):
            continue
        val = _numeric(arg, dict(params))
        if val is not None and abs(val.imag) < 1e-12 and val.real != 0:
            rep[a] = arg if val.real > 0 else -arg
    return expr.xreplace(rep) if rep else expr


def _never_zero(expr, joints, kinds, params) -> bool:
    """True when expr (a polynomial in sines and cosines of revolute joints) cannot vanish for
    the given parameters: |constant term| > Σ |coefficient| of the other terms, each term a
    product of sines and cosines, at most 1 in size. A sufficient test only (False: unknown)."""
    expr = sp.sympify(expr)
    if not expr.free_symbols or expr.free_symbols - set(joints) - set(params):
        return False
    values = {s: v for s, v in params.items() if v is not None and s in expr.free_symbols}
    if len(values) < len(expr.free_symbols - set(joints)):
        return False
    qs = [q for q in joints if expr.has(q)]
    if any(kinds.get(q) != "revolute" for q in qs):
        return False
    const, bound = 0.0, 0.0
    for term in sp.Add.make_args(sp.expand(expr.xreplace(values))):
        coeff, rest = term.as_independent(*qs, as_Add=False)
        try:
            coeff = complex(coeff)
        except TypeError:
            return False
        if rest == 1:
            const += coeff.real
            continue
        trig = all(isinstance(f, (sp.sin, sp.cos)) or (f.is_Pow and isinstance(f.base, (sp.sin, sp.cos))
                                                         and f.exp.is_Integer and f.exp > 0)
                   for f in sp.Mul.make_args(rest))
        if not trig or abs(coeff.imag) > 1e-12:
            return False
        bound += abs(coeff.real)
    return abs(const) > bound * (1 + 1e-9) + 1e-12


def _multiple_of(expr, fac) -> bool:
    """expr is fac times something (expr a product of factors, one of them ±fac)."""
    return any(_same_up_to_sign(f, fac) for f in sp.Mul.make_args(expr)
               if not f.is_number and f.free_symbols >= fac.free_symbols)


# a point where two different factors differ (rational, so that its value is exact enough)
_PROBE = (sp.Rational(3, 7), sp.Rational(-5, 11), sp.Rational(7, 13), sp.Rational(2, 17), sp.Rational(-9, 19))


def _same_up_to_sign(f, fac) -> bool:
    """f = ±fac, proved by is_zero; f − fac and f + fac both non-zero at one point settles it
    at once (then neither is identically zero), which is most pairs."""
    if f == fac or f == -fac:
        return True
    point = {s: _PROBE[i % len(_PROBE)] + i for i, s in enumerate(sorted(f.free_symbols | fac.free_symbols,
                                                                          key=sp.default_sort_key))}
    minus, plus = _numeric(f - fac, point), _numeric(f + fac, point)
    if minus is not None and plus is not None and abs(minus) > 1e-12 and abs(plus) > 1e-12:
        return False
    return is_zero(f - fac) or is_zero(f + fac)


def _maximal_minors(j: sp.Matrix):
    r, c = j.shape
    k = min(r, c)
    minors = []
    for rows in itertools.combinations(range(r), k):
        for cols in itertools.combinations(range(c), k):
            minors.append(j.extract(list(rows), list(cols)).det(method="berkowitz"))
    return minors


def _order_key(cond: Condition, joints, sample):
    key = [1 if cond.equations else 0]
    idx = {q: i for i, q in enumerate(joints)}
    for q, v in sorted(cond.values, key=lambda qv: idx[qv[0]]):
        val = _numeric(v, _sample_params(sp.sympify(v).free_symbols, sample))
        num = val.real if val is not None else math.inf
        key.append((idx[q], round(num, 9), _text(v)))
    key.append(tuple(_text(e) for e in cond.equations))
    return (key[0], tuple(key[1:-1]), key[-1])


def _canonical(cond: Condition, joints):
    idx = {q: i for i, q in enumerate(joints)}
    vals = tuple(sorted(cond.values, key=lambda qv: idx[qv[0]]))
    return Condition(values=vals, equations=cond.equations, factor=cond.factor, names=cond.names)


def _subsumed(small: Condition, big: Condition) -> bool:
    """True when `big` is a special case of `small` (same values on small's joints)."""
    if small.equations or big.equations or small is big:
        return False
    sv, bv = dict(small.values), dict(big.values)
    if len(sv) >= len(bv):
        return False
    return all(q in bv and is_zero(bv[q] - v) for q, v in sv.items())


def _exact_floats(j: sp.Matrix, params: dict):
    """J with each float coefficient as a positive symbol (a tool offset of 0.02 m), the sample
    values with them, and the way back: the search then factors exactly (with the floats, a
    substituted minor kept round-off terms, 1e-13·c²·cos θ2, that no factoring takes apart)."""
    to, back = float_placeholders(j)
    if not to:
        return j, params, {}
    return j.xreplace(to), {**params, **back}, back


def _put_back(cond: Condition, back: dict) -> Condition:
    return Condition(values=tuple((q, v.xreplace(back)) for q, v in cond.values),
                     equations=tuple(e.xreplace(back) for e in cond.equations),
                     factor=None if cond.factor is None else cond.factor.xreplace(back), names=cond.names)


def find_singularities(j: sp.Matrix, joints: Sequence[sp.Symbol], kinds: Mapping,
                       params: Mapping | None = None, det=None, minors=None,
                       work: SearchBudget | None = None) -> SingularityResult:
    """Singular configurations of J(q).

    ``kinds`` maps each joint symbol to 'revolute' or 'prismatic'; ``params`` maps
    parameter symbols to numbers (or None) and is used only to choose between
    equivalent closed forms, to order the results and to drop values that are not
    real for the given parameters (with a note). ``det``: det J of a square J, already
    factored by structure (robosolve.kinematics.structured_det), used instead of expanding;
    ``minors``: the maximal minors of a wide J, already factored by structure
    (robosolve.kinematics.wide_rank). ``work``: the counted budget of the search (SearchTooLong
    past it).
    """
    j = sp.Matrix(j) if j is not None else None
    joints = list(joints)
    params = dict(params or {})
    j, sample, back = _exact_floats(j, params) if det is None and minors is None else (j, params, {})
    if det is not None and j is not None and j.shape[0] == j.shape[1]:
        kind, measure = "det", det
    elif minors is not None:
        kind, measure = "gram", None      # the sum of the minors' squares, below
    elif j.shape[0] == j.shape[1]:
        kind, measure = rank_measure(j)
    else:
        # det(J Jᵀ) itself is not needed: the sum of the minors' squares below is the measure
        kind, measure = "gram", None
    notes: list[str] = []
    given, minors = minors, []
    if kind == "det":
        measure = factored_determinant(measure) if det is None else measure
        exprs = [measure] if measure != 0 else []   # det J ≡ 0: rank lost everywhere, as below
    else:
        # det(J Jᵀ) (or det(Jᵀ J)) = sum of the squares of the maximal minors
        minors = list(given) if given is not None else [factored_determinant(m) for m in _maximal_minors(j)]
        exprs = [m for m in minors if m != 0]
        measure = sp.Add(*[m**2 for m in exprs])
    conds = _search(exprs, joints, kinds, {}, sample, work=work) if exprs else [Condition()]
    if back:
        conds = [_put_back(c, back) for c in conds]
        measure, minors = measure.xreplace(back), [m.xreplace(back) for m in minors]
    if not exprs:
        notes.append("J has rank below full in every configuration (all maximal minors vanish).")
    conds = [_canonical(c, joints) for c in conds]
    # drop duplicates and special cases of more general conditions
    unique: list[Condition] = []
    seen = set()
    for c in conds:
        key = (tuple((q, _text(v)) for q, v in c.values), tuple(map(_text, c.equations)))
        if key not in seen:
            seen.add(key)
            unique.append(c)
    unique = [c for c in unique if not any(_subsumed(o, c) for o in unique)]
    # values that are not real for the given parameters
    kept = []
    for c in unique:
        bad = [(q, v) for q, v in c.values if _is_real_value(v, params) is False]
        if bad:
            notes.append("no real configuration for the given parameters: "
                         + ", ".join(f"{q} = {_text(v)}" for q, v in bad))
            continue
        never = [e for e in c.equations if _never_zero(e, joints, kinds, params)]
        if never:
            notes.append("no real configuration for the given parameters: "
                         + ", ".join(f"{_text(e)} = 0" for e in never)
                         + " (its constant term exceeds the sum of the other terms' coefficients, "
                         "each multiplying sines and cosines)")
            continue
        kept.append(c)
    kept.sort(key=lambda c: _order_key(c, joints, params))
    return SingularityResult(kind=kind, measure=measure, conditions=kept, minors=minors, notes=notes)
