"""The one simplification policy of robosolve: named variants, one memo, op-count budgets.

Every simplification in robosolve goes through a variant below (tests/test_simplify_policy.py
fails on a `simplify`, `trigsimp`, `fu`, `factor`, ... call anywhere else). Each variant says
what it is for and how much work it may do; the work is measured deterministically by
sympy's `count_ops` (an expression above its variant's budget is left as it is), so the same
input gives the same output on every machine. Budgets come from `SimplifyBudgets` (the
solve context carries one: `ctx.budgets.simplify`); engines use the defaults.

| variant | for | budget |
| --- | --- | --- |
| `chain_product` (alias `tidy`) | entries of chain products M, W, H, L (c1 c2 - s1 s2 -> cos(q1 + q2)) | `chain_ops` (+ `chain_seconds` safety net) |
| `tidy_products` | chain products of long arms (5+ joints): addition formulas, trigsimp only when a power of sin/cos is left | as `chain_product` |
| `congruence_entry`, `congruence_entries` | entries of M J Mᵀ (a pseudo-inertia in frame 0): the shorter of the canonical form and the expanded product of tidied factors (d² m s1², not d² m - d² m c1²) | one expand an entry; `congruence_entries` stops expanding once the entries done exceed the count the matrix is shown within (the rest keep their canonical forms) |
| `jacobian_entry` | Jacobian entries: trigsimp, then factor if shorter | none (entries are small) |
| `small_trig` | small pieces: the dynamics engine's sympy fallback, twists L = dM/dq M^-1 | none |
| `exact_geometry` | rotation / displacement quantities (angles, axes, quaternions) | `geometry_ops` |
| `full` | a blanket `simplify` on the few small exact expressions of one helical axis or one atan2 branch | none (callers pass small inputs) |
| `bounded_full` | `full` below `root_ops`, else unchanged (roots of a singular factor) | `root_ops` |
| `ik_fraction` | IK closed forms: one fraction, numerator expanded, no -(...) around a sum | none |
| `determinant_factors`, `factored_determinant` | factors of det J and of the minors of a wide J (trig identities may reveal products) | `factor_ops` (a factor above it is not tidied) |
| `coefficient` | parameter coefficients of the equations of motion: factored when small | `coefficient_ops` |
| `factored` | a polynomial shown factored (profile derivatives, radicands, the ratios of a singular value in closed form) | none |
| `radicals` | exact numbers with radicals: the shortest of expand / sqrtdenest / radsimp | none |
| `eigenvalue` | an exact eigenvalue: simplify, then radicals collected | none |
| `rational` | a float written as the rational it stands for (nsimplify) | none |
| `is_zero` | equivalence checks: simplify(a - b) == 0 | none |

`memoised` keeps every complete result in one table keyed by (variant, expression).
"""

from __future__ import annotations

import sys
import types
from dataclasses import dataclass
from functools import wraps

import sympy as sp
from sympy.simplify.fu import TR8, TR10i

from robosolve.core.timing import time_limit
from robosolve.core.trigring import pythagorean_reduced
from robosolve.errors import SymbolicTimeout
from robosolve.core.opcount import count_ops
from robosolve.core.linear_factors import factor_list_zz

__all__ = [
    "SimplifyBudgets", "DEFAULT_BUDGETS", "chain_product", "tidy", "tidy_matrix", "jacobian_entry",
    "congruence_entry", "congruence_entries",
    "small_trig", "exact_geometry", "full", "bounded_full", "ik_fraction", "determinant_factors",
    "factored_determinant", "coefficient", "factored", "radicals", "eigenvalue", "rational",
    "is_zero",
]


@dataclass(frozen=True)
class SimplifyBudgets:
    """Work budgets of the variants, in `count_ops` of the input (deterministic)."""

    chain_ops: int = 300            # above: trigsimp costs seconds and rarely pays
    chain_seconds: float = 5.0      # safety net only: the op count decides first
    canonical_ops: int = 24         # above: the Pythagorean-reduced form is the answer (no trigsimp)
    geometry_ops: int = 60          # above: trigsimp on rotation entries takes minutes
    coefficient_ops: int = 60       # above: factor_terms only
    root_ops: int = 40              # above: a root is shown as solve gave it
    factor_ops: int = 160           # above: a determinant's factor is kept as factor() gave it (TR10i
                                    # on a 7-joint arm's minors takes minutes)
    product_to_sum_ops: int = 120   # above: the shortest trig form has no product-to-sum candidate
                                    # (TR8 makes 2^(k-1) terms of a product of k sines and cosines:
                                    # 10 s on a 4-joint arm's minor of 4,000 ops; it is the shortest
                                    # only on short entries, sin θ cos θ -> sin(2θ)/2, 20 ops at most
                                    # on the bundled problems and benchmarks)


DEFAULT_BUDGETS = SimplifyBudgets()

# Above this size trigsimp costs seconds and rarely pays: the entry is left as is. The size is
# counted (sympy operations), so the decision is the same on every machine; the time limit of
# `tidy` is only a safety net.
MAX_TIDY_OPS = DEFAULT_BUDGETS.chain_ops


def expression_nodes(obj) -> int:
    """The number of expression-tree nodes in a sympy object, a matrix, or nested lists,
    tuples and dicts of them: the deterministic measure of symbolic work (spec §2)."""
    if isinstance(obj, sp.MatrixBase):
        return sum(expression_nodes(e) for e in obj)
    if isinstance(obj, sp.Basic):
        return sum(1 for _ in sp.preorder_traversal(obj))
    if isinstance(obj, dict):
        return sum(expression_nodes(v) for v in obj.values())
    if isinstance(obj, (list, tuple)):
        return sum(expression_nodes(e) for e in obj)
    return 0


_MEMO: dict = {}
_MEMO_SIZE = 50_000


class _Incomplete(Exception):
    """Raised inside a variant whose work was cut short: its result is not memoised."""

    def __init__(self, value):
        self.value = value


def memoised(fn=None, *, fixed_point: bool = False):
    """One memo for every variant: (variant, expression, budget) -> result.

    A `seconds` keyword is not part of the key (it only decides whether the work
    completes; an incomplete result is never stored). `fixed_point`: the result is also
    stored as its own result (a tidied entry needs no second pass).
    """
    if fn is None:
        return lambda f: memoised(f, fixed_point=fixed_point)
    name = fn.__name__

    @wraps(fn)
    def wrapper(expr, *args, **kw):
        expr = sp.sympify(expr)
        budget = (args, tuple(sorted((k, v) for k, v in kw.items() if k != "seconds")))
        hit = _MEMO.get((name, expr, budget))
        if hit is not None:
            return hit
        try:
            out = fn(expr, *args, **kw)
        except _Incomplete as inc:
            return inc.value
        if len(_MEMO) < _MEMO_SIZE:
            _MEMO[(name, expr, budget)] = out
            if fixed_point:
                _MEMO[(name, out, budget)] = out
        return out

    return wrapper


# ---------------------------------------------------------------------------- chains

def tidy(expr, seconds: float | None = None, budgets: SimplifyBudgets = DEFAULT_BUDGETS):
    """`chain_product` (the model's name for it)."""
    return chain_product(expr, budgets.chain_ops,
                         seconds=budgets.chain_seconds if seconds is None else seconds)


@memoised(fixed_point=True)
def chain_product(expr, max_ops: int = DEFAULT_BUDGETS.chain_ops, *,
                  seconds: float = DEFAULT_BUDGETS.chain_seconds):
    """Trig products collapsed entry by entry (c1*c2 - s1*s2 -> cos(theta1 + theta2)),
    never a blanket `simplify`; an entry above `max_ops` is left as it is. Chain products
    and points re-tidy the same entries many times: memoised, fixed points included."""
    if expr.is_Atom or not expr.has(sp.sin, sp.cos):
        return sp.expand(expr) if expr.is_Add or expr.is_Mul else expr
    if count_ops(expr) > max_ops:
        return expr
    floats, back = _float_placeholders(expr)
    if floats:
        # inexact coefficients (a DH twist of 0.3 rad): the same route with each float as a
        # symbol, put back at the end (trigsimp on float entries took seconds each)
        return chain_product(expr.xreplace(floats), max_ops, seconds=seconds).xreplace(back)
    try:
        with time_limit(seconds) as token:
            expanded = sp.expand(expr)
            large = count_ops(expanded) > DEFAULT_BUDGETS.canonical_ops
            # A large entry: its canonical form first (TR10i on the unreduced sum, which
            # may be 10x longer, costs more than the ring reduction).
            canonical = _canonical_trig(expanded) if large else None
            if canonical is not None and count_ops(canonical) > DEFAULT_BUDGETS.canonical_ops:
                return canonical
            # Addition formulas first (c1 c2 - s1 s2 -> cos(q1 + q2)): fast, and it
            # leaves trigsimp, slow on long chains, little or nothing to do.
            collapsed = _addition_formulas(expanded)
            if not _has_trig_products(collapsed) or count_ops(collapsed) > max_ops:
                return collapsed
            if not large:
                canonical = _canonical_trig(expanded)
                if canonical is not None and count_ops(canonical) > DEFAULT_BUDGETS.canonical_ops:
                    return canonical
            if canonical is not None:
                return _shortest_trig_form(canonical)
            return sp.trigsimp(collapsed)
    except SymbolicTimeout as exc:
        if exc.token is not token:
            raise          # an enclosing step's time is up
        raise _Incomplete(expr) from None


def float_placeholders(expr) -> tuple[dict, dict]:
    """(Float -> ±symbol, symbol -> Float) for exact algebra on inexact coefficients (the rank
    search: float round-off leaves 1e-13 terms that no factoring takes apart); the symbols are
    positive Dummies, one per magnitude; ({}, {}) when there is no float or one sits in an angle."""
    return _float_placeholders(expr)


def _float_placeholders(expr) -> tuple[dict, dict]:
    """(Float -> ±Dummy, Dummy -> Float): one positive symbol per float magnitude of expr (so
    that 0.3 and -0.3 cancel as symbols do); ({}, {}) when there is no float, or when a float is
    inside an angle (sin(θ + 0.3): kept as it is, on trigsimp's route)."""
    floats = expr.atoms(sp.Float)
    if not floats or any(t.args[0].atoms(sp.Float) for t in expr.atoms(sp.sin, sp.cos)):
        return {}, {}
    sizes = sorted({abs(f) for f in floats if f != 0})
    symbol = {m: sp.Dummy(f"f{k}", positive=True) for k, m in enumerate(sizes)}
    to = {f: symbol[f] if f > 0 else -symbol[-f] for f in floats if f != 0}
    return to, {d: m for m, d in symbol.items()}


def _canonical_trig(expanded):
    """The entry reduced modulo sin² + cos² = 1 in a polynomial ring over its sines and
    cosines, then the addition formulas (TR10i); None when it is not a polynomial in
    sin/cos of plain symbols. Every cancellation through cos² + sin² = 1 happens in the
    ring at once, so a large entry (the translation column of H of a 3R arm) needs no
    trigsimp: on those, trigsimp costs seconds and returns this very form."""
    reduced = pythagorean_reduced(expanded, expanded=True)
    return None if reduced is None else _addition_formulas(sp.expand(reduced))


def _addition_formulas(expanded):
    """TR10i (c1 c2 - s1 s2 -> cos(q1 + q2)) applied to each group of terms with the same
    factor outside sin/cos (up to sign), and the groups added. Only such terms can combine
    (TR10i pairs A cos a cos b with ±A sin a sin b, and so on), so the result is TR10i's; its
    pairwise search is quadratic in the terms it looks at, and a group is a few of them.
    A sum with √n factors goes to TR10i whole (it pairs coefficients in the ratio √3)."""
    if not expanded.is_Add or any(p.exp == sp.S.Half and p.base.is_Integer
                                  for p in expanded.atoms(sp.Pow)):
        return TR10i(expanded)
    groups: dict = {}
    for term in expanded.args:
        outside, trig = term.as_independent(sp.sin, sp.cos, as_Add=False)
        groups.setdefault(-outside if outside.could_extract_minus_sign() else outside, []).append((term, trig))
    out = []
    for members in groups.values():
        if len(members) == 1:
            out.append(members[0][0])
            continue
        keys = [_trig_arguments(trig) for _term, trig in members]
        if any(k is None for k in keys):        # not all plain products: TR10i on them all
            out.append(TR10i(sp.Add(*[t for t, _ in members])))
            continue
        by_args: dict = {}
        for (term, _trig), k in zip(members, keys):
            by_args.setdefault(k, []).append(term)
        out += [TR10i(sp.Add(*g)) if len(g) > 1 else g[0] for g in by_args.values()]
    return sp.Add(*out)


def _trig_arguments(trig):
    """The arguments of a product of sines and cosines with their multiplicities (sorted), or
    None for another factor. The terms TR10i pairs (cos a cos b·X with sin a sin b·X, sin a cos b·X
    with cos a sin b·X) have the same, and so have the sums it makes (cos(a + b)·X from those),
    so terms with the same factor outside need TR10i only among those with the same."""
    args = []
    for f in sp.Mul.make_args(trig):
        base, exp = f.as_base_exp()
        if isinstance(base, (sp.sin, sp.cos)) and exp.is_Integer and exp > 0:
            args += [base.args[0]] * int(exp)
        elif f != 1:
            return None
    return tuple(sorted(args, key=sp.default_sort_key))


def _shortest_trig_form(canonical):
    """The shortest (sympy operations, then number of sines and cosines) of a small
    canonical entry and what trigsimp would make of it: the common factors taken out
    (cos θ₁ (L₂ cos θ₂ + L₃ cos(θ₂ + θ₃))), products turned into sums
    (sin θ cos θ -> sin(2θ)/2), the polynomial factored (-(θ̇₂ + θ̇₃)²); a bare sign
    before a sum is not taken out. On every chain entry of the problems and benchmarks
    it is trigsimp's result, at a third of the cost."""
    if canonical.is_Mul and _distinct_trig_factors(canonical):
        # one product of sines and cosines of different angles: a product of sums is not
        # shorter, nor a sum of products (TR8 doubles the terms), nor a factored form
        return canonical
    candidates = [canonical]
    if canonical.has(sp.sin, sp.cos) and count_ops(canonical) <= DEFAULT_BUDGETS.product_to_sum_ops:
        candidates.append(_addition_formulas(sp.expand(TR8(canonical))))
    candidates += [sp.factor_terms(canonical), _memo_factor(canonical)]

    def negated_sum(c):
        return c.is_Mul and len(c.args) == 2 and c.args[0] == -1 and c.args[1].is_Add

    def size(c):
        return count_ops(c), sum(1 for a in sp.preorder_traversal(c) if isinstance(a, (sp.sin, sp.cos)))

    return min([c for c in candidates if not negated_sum(c)] or [canonical], key=size)


def _distinct_trig_factors(term) -> bool:
    """A product whose sines and cosines all have exponent 1 and different arguments."""
    args = []
    for f in term.args:
        if isinstance(f, (sp.sin, sp.cos)):
            args.append(f.args[0])
        elif f.is_Pow and isinstance(f.base, (sp.sin, sp.cos)):
            return False
        elif f.has(sp.sin, sp.cos):
            return False
    return len(set(args)) == len(args)


def _has_trig_products(expr) -> bool:
    """True when a product or power of sin/cos is left (something trigsimp may reduce)."""
    for node in sp.preorder_traversal(expr):
        if node.is_Pow and isinstance(node.base, (sp.sin, sp.cos)):
            return True
        if node.is_Mul and sum(1 for a in node.args if isinstance(a, (sp.sin, sp.cos))
                               or (a.is_Pow and isinstance(a.base, (sp.sin, sp.cos)))) > 1:
            return True
    return False


def tidy_matrix(m: sp.Matrix, seconds: float | None = None) -> sp.Matrix:
    return m.applyfunc(lambda e: tidy(e, seconds))


def congruence_entry(canonical, product):
    """One entry of a congruence M J Mᵀ (a pseudo-inertia moved to frame 0), given two
    equal forms: `canonical` (a trig-ring form, each sin² written 1 - cos²) and `product`
    (the entry of the product of the tidied factors, which holds the compact squares:
    d² m s1², m (L1 s1 + L2 s12)²). The shorter by count_ops; `canonical` on a tie."""
    expanded = sp.expand(product)
    return expanded if count_ops(expanded) < count_ops(canonical) else canonical


def congruence_entries(canonicals, products, limit: int | None = None) -> list:
    """`congruence_entry` of each pair, in order. With a `limit` (the count of operations a
    matrix is shown within): once the entries done count more than `limit` together, the matrix
    is too long to show whatever the rest become, and the rest keep their canonical forms
    without being expanded (expanding a long product with radicals and decimals, a twist of
    pi/4 beside one of pi/6, takes seconds an entry)."""
    out, done = [], 0
    for canonical, product in zip(canonicals, products):
        if limit is not None and done > limit:
            out.append(canonical)
            continue
        out.append(congruence_entry(canonical, product))
        done += count_ops(out[-1])
    return out


def _has_trig_squares(expr) -> bool:
    """True when a power of sin/cos is left (room for cos² + sin² = 1)."""
    return any(node.is_Pow and isinstance(node.base, (sp.sin, sp.cos))
               for node in sp.preorder_traversal(expr))


def tidy_products(expr, seconds: float | None = None):
    """Named variant for the chain products of long arms (5+ joints): expand and apply
    the addition formulas (TR10i); trigsimp only when a power of sin/cos is left. An entry
    of a 6R pose is a sum of products of sines and cosines of different angles, with no
    cos² + sin² = 1 to use: trigsimp spends seconds per entry on it and finds only the
    factored look (a common factor pulled out), which the short arms' reports keep (they
    use `tidy`)."""
    expr = sp.sympify(expr)
    if expr.is_Atom or not expr.has(sp.sin, sp.cos):
        return tidy(expr, seconds)
    collapsed = _addition_formulas(sp.expand(expr))
    return tidy(collapsed, seconds) if _has_trig_squares(collapsed) else collapsed


def tidy_products_matrix(m: sp.Matrix, seconds: float | None = None) -> sp.Matrix:
    return m.applyfunc(lambda e: tidy_products(e, seconds))


# ---------------------------------------------------------------------------- kinematics

@memoised
def _memo_factor(expr):
    """sympy's factor, memoised: a Jacobian entry's tidy form is factored inside jacobian_entry and
    again by the determinant routes that take it (the same expression, the same result); also
    `factored`'s. A polynomial over ZZ goes through `_integer_polynomial_factor`."""
    fast = _integer_polynomial_factor(expr)
    return fast if fast is not None else sp.factor(expr)


def _integer_polynomial_factor(expr):
    """sp.factor(expr) for a sum that is a polynomial over ZZ (in symbols, sines and cosines):
    what sympy's factor makes of it — the coefficient kept in front of the product of the factors
    of Poly(expr).factor_list() (`_keep_coeff`), the factors by core.linear_factors (the same as
    sympy's). None for anything else (floats, denominators, roots, I, a product): sympy's own."""
    from sympy.core.mul import _keep_coeff
    from sympy.polys.polyerrors import GeneratorsNeeded, PolynomialError

    if not expr.is_Add or expr.atoms(sp.Float) or expr.has(sp.I, sp.exp) or any(
            not (p.exp.is_Integer and p.exp > 0) for p in expr.atoms(sp.Pow)):
        return None
    try:
        poly = sp.Poly(expr)
    except (GeneratorsNeeded, PolynomialError):
        return None
    if not poly.domain.is_ZZ:
        return None
    coeff, factors = factor_list_zz(poly)
    return _keep_coeff(poly.domain.to_sympy(coeff), sp.Mul(*[f.as_expr() ** k for f, k in factors]))


@memoised
def jacobian_entry(expr):
    """Light, predictable simplification of one Jacobian entry: trigsimp, then factor if
    shorter (the singularity search meets the same factors many times)."""
    if expr.is_number or not expr.free_symbols:
        return sp.nsimplify(expr) if expr.is_Float else expr
    floats, back = _float_placeholders(expr)
    if floats:
        # float coefficients (a point at [0.1, 0.2, 0]): as chain_product does, each float as a
        # symbol, put back at the end (trigsimp on floats writes -1.0*L1*sin(q1) for -L1*sin(q1))
        return jacobian_entry(expr.xreplace(floats)).xreplace(back)
    # the canonical form and the shortest of trigsimp's moves; for an entry given with
    # products of sums, only when that is no longer than the entry (trigsimp keeps a sum
    # squared). On every Jacobian entry of the problems and benchmarks where it applies,
    # this is trigsimp's own result, at a fifth of the cost.
    expanded = sp.expand(expr)
    canonical = _canonical_trig(expanded)
    out = None if canonical is None else _shortest_trig_form(canonical)
    if out is not None and expr != expanded and count_ops(out) > count_ops(expr):
        out = None
    if out is None:
        out = sp.trigsimp(expr)
    fac = _memo_factor(out)
    if count_ops(fac) < count_ops(out):
        out = fac
    return out


def determinant_factors(expr) -> list:
    """Factors of expr (with multiplicity dropped): factor the raw expression, tidy each
    factor (trig identities may reveal products, as in det J of a 2R arm), factor again."""
    out = []
    _, raw = _factor_list(expr)
    for fac, _mult in raw:
        _, again = _factor_list(jacobian_entry(fac))
        for f2, _m2 in again:
            if f2.could_extract_minus_sign():
                f2 = -f2
            if f2 not in out:
                out.append(f2)
    return out


def _polynomial_factor_list(expr):
    """factor_list(factor(expr)) for a product of powers of polynomials (in symbols, sines,
    cosines and roots, exact coefficients): each piece factored as sympy's factor_list factors
    it, without the two passes of together() over the whole expression that factor and
    factor_list make first (most of their time on a substituted minor, where nothing is over a
    denominator). The same factors, multiplicities, coefficient and order. None for anything
    else (floats, denominators, fractional powers of a piece, I): sympy's own route then."""
    if expr.atoms(sp.Float) or expr.has(sp.I, sp.exp) or any(p.exp.is_negative for p in expr.atoms(sp.Pow)):
        return None
    coeff, merged = sp.S.One, {}
    for arg in sp.Mul.make_args(expr):
        if arg.is_Number:
            coeff *= arg
            continue
        base, exp = arg.args if arg.is_Pow else (arg, sp.S.One)
        if not (exp.is_Integer and exp > 0) or base.is_Number:
            return None
        piece = _piece_factors(base)
        if piece is None:
            return None
        c, factors = piece
        coeff *= c ** exp
        for e, k in factors:
            merged[e] = merged.get(e, 0) + k * int(exp)
    # sympy's order (its _sorted_factors, each factor a polynomial in its own generators): the
    # callers multiply the list out, and sympy's Mul distributes a numeric coefficient over the
    # first sum it meets, so the order shows in the product (-L1(-L2 s2 - L3 s23) or not)
    # (ties kept in the order of the arguments of sympy's product of the factors, as there)
    from functools import cmp_to_key

    items = sorted(merged.items(), key=cmp_to_key(lambda x, y: sp.Basic.compare(x[0] ** x[1], y[0] ** y[1])))
    polys = [(sp.Poly(e), k) for e, k in items]
    polys.sort(key=lambda fk: (len(fk[0].rep.to_list()), len(fk[0].gens), fk[1], str(fk[0].domain),
                               fk[0].rep.to_list()))
    return coeff, [(f.as_expr(), k) for f, k in polys]


@memoised
def _piece_factors(base):
    """(coefficient, [(factor as an expression, multiplicity)]) of one polynomial piece over
    ZZ or QQ, as its Poly's factor_list; None when it is not one. Memoised: the rank search meets
    the same pieces again and again (the same minor after q = 0 and q = π, a factored minor taken
    apart to pick its factors: 255 of the Panda's 301 factorisations)."""
    from sympy.polys.polyerrors import GeneratorsNeeded, PolynomialError

    try:
        poly = sp.Poly(base)
    except (GeneratorsNeeded, PolynomialError):
        return None
    if not (poly.domain.is_ZZ or poly.domain.is_QQ):
        return None
    c, factors = factor_list_zz(poly)
    return poly.domain.to_sympy(c), tuple((f.as_expr(), k) for f, k in factors)


def _factor_list(expr):
    """sympy's factor_list of factor(expr) (by `_polynomial_factor_list` where it applies); when
    sympy cannot build the polynomial (it fails on products of roots such as
    √(d6 − d4)·√(d4 + d6), PolificationFailed), the roots are named first and put back in the
    factors."""
    from sympy.polys.polyerrors import PolificationFailed

    fast = _polynomial_factor_list(expr)
    if fast is not None:
        return fast
    try:
        return sp.factor_list(sp.factor(expr))
    except PolificationFailed:
        roots = sorted((x for x in expr.atoms(sp.Pow) if not x.exp.is_Integer), key=sp.default_sort_key)
        if not roots:
            raise
        # plain symbols with fixed names (not Dummy, whose numbering depends on the process)
        names = {r: sp.Symbol(f"_root{i}") for i, r in enumerate(roots)}
        back = {v: k for k, v in names.items()}
        coeff, raw = sp.factor_list(sp.factor(expr.xreplace(names)))
        out = []
        for fac, mult in raw:
            fac = fac.xreplace(back)
            if fac.free_symbols:
                out.append((fac, mult))
            else:
                coeff *= fac ** mult
        return coeff, out


@memoised
def factored_determinant(expr, max_ops: int = DEFAULT_BUDGETS.factor_ops):
    """expr as a product of tidied factors (for display); a factor of more than `max_ops`
    operations is kept as factor() gave it."""
    coeff, raw = _factor_list(expr)
    out = coeff
    for fac, mult in raw:
        out *= (_memo_factor(jacobian_entry(fac)) if count_ops(fac) <= max_ops else fac) ** mult
    return out


@memoised
def small_trig(expr):
    """Trig-simplify a *small* expression (the dynamics engine's sympy fallback algebra:
    pieces of one link at a time); expressions without sin/cos are only expanded."""
    if expr.is_number or not expr.has(sp.sin, sp.cos):
        return sp.expand(expr)
    return sp.trigsimp(sp.expand(expr))


@memoised
def fixed_angles(expr):
    """An expression free of the joints with sines and cosines of fixed angles that sympy keeps
    as they are (a pose's Rz(2), a DH twist of 1/3): trigsimp, so that cos²2 + sin²2 is 1 (the
    dynamics engine divides by a joint axis' |w|², which must stay a constant it can read)."""
    return sp.trigsimp(expr) if expr.has(sp.sin, sp.cos) else expr


@memoised
def twist_entry(expr):
    """An entry of a local twist dM/dq M^-1: trigsimp of the expanded entry."""
    return sp.trigsimp(sp.expand(expr))


# ---------------------------------------------------------------------------- geometry

@memoised
def exact_geometry(e, max_ops: int = DEFAULT_BUDGETS.geometry_ops):
    """Rotation and displacement quantities: exact numbers fully, small symbolic
    expressions with trigsimp, large ones (above `max_ops`) untouched."""
    floats = e.atoms(sp.Float)
    if floats:  # inexact input: drop round-off terms (2.8e-17*h) before anything else
        e = e.xreplace({x: sp.Integer(0) for x in floats if abs(x) < 1e-13})
    if not e.free_symbols:
        return _simplify(e)
    if isinstance(e, sp.atan2):
        return sp.atan2(*(exact_geometry(a, max_ops) for a in e.args))
    if count_ops(e) > max_ops:
        return e
    return sp.trigsimp(sp.expand(e))


@memoised
def full(e):
    """A blanket `simplify`: only for the few small exact expressions of one helical axis
    or one atan2 branch, where it finds the shortest form."""
    return _simplify(e)


_UNITS = "sympy.physics.units"


class _NoQuantity(sp.Basic):
    """Stands for sympy's Quantity while `_simplify` runs: never instantiated."""


def _simplify(e):
    """sympy's `simplify`, without importing `sympy.physics.units`: simplify imports it on
    every call only to ask whether the expression holds a physical Quantity (robosolve's never
    do), and that import is a quarter of a second of CPU in every process, more than the
    simplifications of a usual exam together. A stand-in module answers that one question
    while simplify runs and is removed after, so anything that imports the real units later
    gets them; with the real module already imported, it is used."""
    if _UNITS in sys.modules:
        return sp.simplify(e)
    stand_in = types.ModuleType(_UNITS)
    stand_in.Quantity = _NoQuantity
    sys.modules[_UNITS] = stand_in
    try:
        return sp.simplify(e)
    finally:
        if sys.modules.get(_UNITS) is stand_in:
            del sys.modules[_UNITS]


def bounded_full(e, max_ops: int = DEFAULT_BUDGETS.root_ops):
    """`full` below `max_ops`, else the expression as it is."""
    e = sp.sympify(e)
    return full(e) if count_ops(e) < max_ops else e


def is_zero(e) -> bool:
    """True when e == 0 is proved (equivalence checks: a - b). A polynomial in sines and
    cosines of symbols with exact coefficients is decided by its normal form modulo
    sin² + cos² = 1 (unique: zero exactly when e is), in milliseconds; anything else by
    simplify (Floats at their own precision: 0.1 - 1/10 is 0). A number is evaluated first
    (30 digits away from 0: not zero, no simplify); the one fallback, where no proof can be
    had (equality of constants is undecidable in general): a number simplify does not reduce
    to 0 whose value is below 1e-50 on 60 digits is taken as zero."""
    e = sp.sympify(e)
    if not e.free_symbols:
        return _number_is_zero(e)
    if not e.atoms(sp.Float):
        expanded = sp.expand(e)
        if expanded == 0:
            return True
        reduced = pythagorean_reduced(expanded, expanded=True) if expanded.has(sp.sin, sp.cos) else None
        if reduced is not None:
            return sp.expand(reduced) == 0
    return full(e) == 0


def _number_is_zero(e) -> bool:
    if e.is_Number:
        return e == 0
    try:
        if abs(complex(e.evalf(30))) > 1e-20:
            return False
        if full(e) == 0:
            return True
        return abs(complex(e.evalf(60))) < 1e-50
    except (TypeError, ValueError):      # not a number sympy can evaluate (zoo, nan)
        return False


# ---------------------------------------------------------------------------- algebra

@memoised
def ik_fraction(e):
    """Light simplification for display and smaller expressions: one fraction, its numerator
    expanded, no -(...) around a sum (E.x**2 + E.y**2 - L1**2 - L2**2)/(2*L1*L2)."""
    try:
        t = sp.together(e)
        num, den = sp.fraction(t)
        if den != 1:
            return sp.expand(num) / den
        f = sp.factor_terms(t)
        if isinstance(f, sp.Mul) and f.args and f.args[0] == -1 and any(isinstance(a, sp.Add) for a in f.args):
            return sp.expand(t)
        return f
    except Exception:  # pragma: no cover
        return e


@memoised
def coefficient(coef, small: bool = True, max_ops: int = DEFAULT_BUDGETS.coefficient_ops):
    """A parameter coefficient of the equations of motion: factored when the robot is small
    and the coefficient within `max_ops`, else its common factors taken out."""
    return sp.factor(coef) if small and count_ops(coef) <= max_ops else sp.factor_terms(coef)


def common_factors(e):
    """Common factors taken out (no factoring of sums)."""
    return sp.factor_terms(e)


def factored(e):
    """A polynomial shown factored (profile derivatives, the radicand of a distance, the ratios
    of a singular joint value in closed form): sympy's factor, through the one memoised table."""
    return _memo_factor(e)


@memoised
def radicals(x):
    """Exact numbers with radicals: the shortest of expand / sqrtdenest / radsimp."""
    cands = [x, sp.expand(x), sp.sqrtdenest(x), sp.expand(sp.sqrtdenest(x)), sp.radsimp(x)]
    return min(cands, key=lambda c: (count_ops(c), sp.default_sort_key(c)))


@memoised
def collected_radicals(e):
    """An exact number with its radicals collected (radsimp: fast)."""
    return sp.radsimp(e)


@memoised
def eigenvalue(val):
    """An exact eigenvalue: simplify, then radicals collected."""
    return sp.radsimp(_simplify(val))


def rational(x):
    """A float written as the exact rational (or simple radical) it stands for."""
    return sp.nsimplify(x)
