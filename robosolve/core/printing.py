"""sympy's `str` printer with a memo: each subexpression printed once per printer.

Big expressions share their subexpressions (the equations of motion of a 6-joint arm repeat
the entries of M in every row), and sympy's printer sorts and prints each sum again wherever it
occurs. A printing method depends only on the expression and the printer's settings (and, for
`str`, on the level: a Float prints differently at the top), so the text of a subexpression
printed without keyword arguments is kept and reused: the same text as `str(expr)` (tested in
tests/render/test_shared_latex.py). render/printers.py builds its LaTeX printer on the same memo.

The order of a sum's terms is sympy's (`ordered_terms`), made independent of the hash seed:
sympy sorts a sum's generators out of a set by their sort keys, and two different generators
can have equal keys (L1 + L2 and 1.0*L1 + 1.0*L2: a decimal coefficient equal to an integer
does not count in sympy's key), which then came out in the set's order — a PYTHONHASHSEED of
its own. Here they are taken in sympy's structural order first (`Basic.compare`), and the sort
keys of sums are built with the same order of terms (`sort_key`).
"""

from __future__ import annotations

from functools import cmp_to_key

import sympy as sp
from sympy.printing.latex import LatexPrinter
from sympy.printing.str import StrPrinter


# The order of a sum's terms (sympy sorts them for every printer, the str of results.json and
# the LaTeX of the report alike): by the sum and the order asked for, kept for every printer.
_ORDERED_TERMS: dict = {}
_MAX_ORDERED = 100_000


# The str printer's texts, for every SharedStrPrinter of the process (bounded: a batch of many
# problems keeps at most this many per printer memo).
_STR_PRINTED: dict = {}
_MAX_PRINTED = 200_000


# `ordered_terms` follows sympy's code of these versions (tested equal to it); other versions
# sort with sympy's own
_SAME_AS_TERMS = tuple(int(x) for x in sp.__version__.split(".")[:2]) in ((1, 12), (1, 13), (1, 14))

# sort keys of the generators of sums (sin q₂, m₁, sin(q₂ + q₃)): a sum's sort key sorts
# its terms again, and the same generators occur in most sums of a report
_SORT_KEYS: dict = {}

_STRUCTURAL = cmp_to_key(sp.Basic.compare)


def _sort_key(e):
    hit = _SORT_KEYS.get(e)
    if hit is None:
        hit = sort_key(e)
        if len(_SORT_KEYS) < _MAX_ORDERED:
            _SORT_KEYS[e] = hit
    return hit


def sort_key(e):
    """sympy's default_sort_key(e) (Expr.sort_key of 1.14, line for line), with the terms of
    every sum inside in the order of `ordered_terms`: the same key as sympy's wherever sympy's
    does not depend on the hash seed (tested equal), and the same key in every process."""
    if not isinstance(e, sp.Expr) or e.is_Atom:
        return sp.default_sort_key(e)
    coeff, expr = e.as_coeff_Mul()
    exp = sp.S.One
    if expr.is_Pow:
        expr, exp = expr.as_base_exp()
        if expr is sp.S.Exp1:
            expr, exp = sp.Function("exp")(exp), sp.S.One
    if expr.is_Dummy:
        args = (expr.sort_key(),)
    elif expr.is_Atom:
        args = (str(expr),)
    else:
        if expr.is_Add:
            parts = ordered_terms(expr)
        elif expr.is_Mul:
            commutative, other = expr.args_cnc()
            parts = sorted(commutative, key=_sort_key) + other
        else:
            parts = expr.args
        args = tuple(_sort_key(a) for a in parts)
    return expr.class_key(), (len(args), args), _sort_key(exp), coeff


def _sorted_generators(gens: set) -> list:
    """The generators of a sum by their sort keys, as sympy sorts them; generators whose keys
    are equal (an exact and a decimal form of one sum) in sympy's structural order, not in the
    set's (which follows the hash seed)."""
    return sorted(sorted(gens, key=_STRUCTURAL), key=_sort_key)


def _as_terms(expr):
    """sympy's Expr.as_terms (1.14) line for line, with the sort keys of the generators kept
    (`_sort_key`), generators with equal keys in a fixed order (`_sorted_generators`) and a
    rational or decimal coefficient converted by float() (what complex() gives for it, without
    evalf)."""
    from sympy.core.exprtools import decompose_power

    gens, terms = set(), []
    for term in sp.Add.make_args(expr):
        coeff, rest = term.as_coeff_Mul()
        coeff = complex(float(coeff)) if isinstance(coeff, (sp.Rational, sp.Float)) else complex(coeff)
        cpart, ncpart = {}, []
        if rest is not sp.S.One:
            for factor in sp.Mul.make_args(rest):
                if factor.is_number:
                    try:
                        coeff *= complex(factor)
                    except (TypeError, ValueError):
                        pass
                    else:
                        continue
                if factor.is_commutative:
                    base, exp = decompose_power(factor)
                    cpart[base] = exp
                    gens.add(base)
                else:
                    ncpart.append(factor)
        terms.append((term, ((coeff.real, coeff.imag), cpart, tuple(ncpart))))
    gens = _sorted_generators(gens)
    indices = {g: i for i, g in enumerate(gens)}
    result = []
    for term, (coeff, cpart, ncpart) in terms:
        monom = [0] * len(gens)
        for base, exp in cpart.items():
            monom[indices[base]] = exp
        result.append((term, (coeff, tuple(monom), ncpart)))
    return result, gens


def ordered_terms(expr, order=None) -> list:
    """expr.as_ordered_terms(order) (sympy 1.14's, line for line, through `_as_terms`): the order
    the str and LaTeX printers print a sum's terms in."""
    from sympy.core.numbers import Number, NumberSymbol

    if order is None and expr.is_Add:
        def key(x):
            return not isinstance(x, (Number, NumberSymbol))

        add_args = sorted(sp.Add.make_args(expr), key=key)
        if (len(add_args) == 2 and isinstance(add_args[0], (Number, NumberSymbol))
                and isinstance(add_args[1], sp.Mul)):
            mul_args = sorted(sp.Mul.make_args(add_args[1]), key=key)
            if (len(mul_args) == 2 and isinstance(mul_args[0], Number)
                    and add_args[0].is_positive and mul_args[0].is_negative):
                return add_args
    key, reverse = sp.Expr._parse_order(order)
    terms, _gens = _as_terms(expr)
    if not any(term.is_Order for term, _ in terms):
        ordered = sorted(terms, key=key, reverse=reverse)
    else:
        plain = [(t, r) for t, r in terms if not t.is_Order]
        big_o = [(t, r) for t, r in terms if t.is_Order]
        ordered = sorted(plain, key=key, reverse=True) + sorted(big_o, key=key, reverse=True)
    return [term for term, _ in ordered]


class OrderedTerms:
    """A printer's order of a sum's terms: `ordered_terms` (sympy's order, the same whatever the
    hash seed), kept for every printer of the process."""

    def _as_ordered_terms(self, expr, order=None):
        key = (expr, order or self.order)       # the order sympy's printer would use
        if key[1] in ("old", "none") or not isinstance(expr, sp.Expr):   # the printer's own ways
            return super()._as_ordered_terms(expr, order=order)
        hit = _ORDERED_TERMS.get(key)
        if hit is None:
            hit = ordered_terms(expr, key[1]) if _SAME_AS_TERMS else super()._as_ordered_terms(expr, order=order)
            if len(_ORDERED_TERMS) < _MAX_ORDERED:
                _ORDERED_TERMS[key] = hit
        return list(hit)


class PrintsEachOnce(OrderedTerms):
    """The memo of the shared printers; `_key` is what the text of an expression depends on."""

    def _key(self, expr):
        return expr

    def _print(self, expr, **kwargs) -> str:
        if kwargs or not isinstance(expr, sp.Basic):
            return super()._print(expr, **kwargs)
        key = self._key(expr)
        out = self._printed.get(key)
        if out is None:
            out = super()._print(expr)
            if len(self._printed) < _MAX_PRINTED:
                self._printed[key] = out
        return out


class SharedStrPrinter(PrintsEachOnce, StrPrinter):
    """`str(expr)` of sympy expressions (not of matrices: results.json prints them entry by
    entry). A Float is printed differently at the top and inside another expression: that is
    part of the key."""

    def __init__(self):
        super().__init__({"order": None})       # what Basic.__str__ asks for
        # one memo for every instance: the text depends only on the expression and the level,
        # and the equations of motion printed by their solver share their entries with the
        # matrices results.json prints afterwards
        self._printed = _STR_PRINTED

    def _key(self, expr):
        return expr, self._print_level == 0


class _LatexPrinter(OrderedTerms, LatexPrinter):
    pass


class _StrPrinter(OrderedTerms, StrPrinter):
    pass


def latex(expr, **settings) -> str:
    """sympy.latex(expr, **settings), a sum's terms in the order of `ordered_terms`: the text
    robosolve writes wherever it prints LaTeX outside the report's shared printer."""
    return _LatexPrinter(settings).doprint(expr)


def sstr(expr, **settings) -> str:
    """sympy.sstr(expr, **settings) (str(expr)), a sum's terms in the order of `ordered_terms`."""
    return _StrPrinter(settings).doprint(expr)
