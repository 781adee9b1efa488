"""Piecewise answers (motion and torque profiles, piecewise in t): compared piece by piece.

grading.md: a profile is right when it equals the reference as a function of t on the
profile's [0, T]. The breakpoints of both sides (where a condition of either changes, at the
problem's values of the parameters) cut [0, T] into intervals; breakpoints closer than the
tolerance (atol + rtol·T) count as one, so a rounded 0.886 for √π/2 makes no interval of its
own. On each interval, the piece each side has there (chosen at the interval's middle) is
compared as an expression — for every value of the parameters, as any expression is — with t
sampled inside that interval. So what a profile does before 0 or after T does not count, nor
which side of a breakpoint owns it (t < 1 or t <= 1), and a wrong piece is wrong.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from robosolve.grading.values import Pieces, ValueProblem

CONDITION_NODES = 200            # above: a condition is not read as a comparison of t with a value


def has_piecewise(tree) -> bool:
    """A leaf of the tree is (or holds) a piecewise expression."""
    if isinstance(tree, dict):
        return any(has_piecewise(v) for v in tree.values())
    if isinstance(tree, (list, tuple)):
        return any(has_piecewise(v) for v in tree)
    return isinstance(tree, sp.Basic) and tree.has(sp.Piecewise)


def split_pieces(g, e, t, subs: dict, t_range: tuple, tol):
    """(g', e'): the aligned trees g (given) and e (expected) with every pair of leaves of which
    one is piecewise replaced by two `Pieces` on the same intervals of `t_range` = (0, T), t
    rescaled in each part so that t sampled over (0, T) runs over that part's interval.
    Leaves whose layouts differ are left for the comparison to report."""
    if isinstance(g, dict) and isinstance(e, dict):
        pairs = {k: split_pieces(g[k], e[k], t, subs, t_range, tol) if k in e else (g[k], None)
                 for k in g}
        return ({k: p[0] for k, p in pairs.items()},
                {k: pairs[k][1] if k in pairs else v for k, v in e.items()})
    if isinstance(g, list) and isinstance(e, list) and len(g) == len(e):
        pairs = [split_pieces(a, b, t, subs, t_range, tol) for a, b in zip(g, e)]
        return [p[0] for p in pairs], [p[1] for p in pairs]
    if isinstance(g, sp.Basic) and isinstance(e, sp.Basic) and (g.has(sp.Piecewise) or e.has(sp.Piecewise)):
        return _split_leaf(g, e, t, subs, t_range, tol)
    return g, e


def _split_leaf(a, b, t, subs, t_range, tol):
    lo, hi = (float(x) for x in t_range)
    width = tol.atol + tol.rtol * (hi - lo)
    intervals = _intervals(_breakpoints(a, t, subs) + _breakpoints(b, t, subs), lo, hi, width)
    parts_a, parts_b = [], []
    for x, y in intervals:
        middle = {**subs, t: sp.Float((x + y) / 2)}
        stretch = {t: sp.Float(x) + sp.Float((y - x) / (hi - lo)) * (t - sp.Float(lo))}
        parts_a.append(_active(a, middle).xreplace(stretch))
        parts_b.append(_active(b, middle).xreplace(stretch))
    return Pieces(tuple(parts_a), intervals), Pieces(tuple(parts_b), intervals)


def _intervals(cuts, lo: float, hi: float, width: float) -> tuple:
    """The intervals of [lo, hi] between the breakpoints `cuts` (those within `width` of each
    other, or of lo or hi, taken as one)."""
    points = sorted([lo, hi] + [c for c in cuts if lo < c < hi])
    clusters = [[points[0]]]
    for p in points[1:]:
        if p - clusters[-1][-1] <= width:
            clusters[-1].append(p)
        else:
            clusters.append([p])
    intervals = tuple((c[-1], d[0]) for c, d in zip(clusters, clusters[1:]))
    return intervals or ((lo, hi),)


def _breakpoints(expr, t, subs) -> list:
    """The values of t (at the problem's values) where a condition of a piecewise part of `expr`
    changes: the real roots of lhs − rhs of each comparison, a polynomial in t."""
    out = []
    for pw in sorted(expr.atoms(sp.Piecewise), key=sp.default_sort_key):
        for _, condition in pw.args:
            for rel in sorted(condition.atoms(sp.core.relational.Relational), key=sp.default_sort_key):
                out += _roots(rel, t, subs)
    return out


def _roots(rel, t, subs) -> list:
    r = (rel.lhs - rel.rhs).xreplace(subs)
    if not r.has(t):
        return []
    other = r.free_symbols - {t}
    why = ""
    if other:
        why = f"it depends on {', '.join(sorted(s.name for s in other))}"
    elif sp.count_ops(r) > CONDITION_NODES:
        why = "it is too long"
    else:
        try:
            coefficients = [complex(sp.N(c)) for c in sp.Poly(r, t).all_coeffs()]
        except (sp.PolynomialError, TypeError, ValueError):
            why = "it is not a polynomial in t"
    if why:
        raise ValueProblem(f"the condition {rel} of a piecewise answer does not compare t with a "
                           f"value ({why})")
    while coefficients and coefficients[0] == 0:
        coefficients.pop(0)
    if len(coefficients) < 2 or not all(np.isfinite(c) for c in coefficients):
        return []
    roots = np.roots(np.array(coefficients))
    return sorted(float(z.real) for z in roots if abs(z.imag) <= 1e-9 * (1 + abs(z.real)))


def _active(expr, values: dict):
    """`expr` with each piecewise part replaced by its piece where the conditions hold at
    `values` (t in an interval's middle, the parameters at their values); nan where none holds."""
    def pick(pw):
        for piece, condition in pw.args:
            holds = condition.xreplace(values) if isinstance(condition, sp.Basic) else condition
            if holds == sp.true:
                return piece
            if holds != sp.false:
                names = ", ".join(sorted(s.name for s in getattr(holds, "free_symbols", ())))
                raise ValueProblem(f"the condition {condition} of a piecewise answer cannot be decided "
                                   f"in t alone" + (f" (it depends on {names})" if names else ""))
        return sp.nan

    if not expr.has(sp.Piecewise):
        return expr
    return expr.replace(lambda x: isinstance(x, sp.Piecewise), pick)


def wrong_intervals(g: Pieces, e: Pieces, ok) -> list:
    """The intervals of a pair of Pieces (evaluated) on which the given part is wrong
    (`ok(given_part, expected_part)`)."""
    return [interval for interval, a, b in zip(e.intervals, g.parts, e.parts) if not ok(a, b)]
