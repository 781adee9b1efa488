"""sympy's `str` printer with a memo: each subexpression printed once per printer.

Big expressions share their subexpressions (the equations of motion of a 6-joint arm repeat
the entries of M in every row), and sympy's printer sorts and prints each sum again wherever it
occurs. A printing method depends only on the expression and the printer's settings (and, for
`str`, on the level: a Float prints differently at the top), so the text of a subexpression
printed without keyword arguments is kept and reused: the same text as `str(expr)` (tested in
tests/render/test_shared_latex.py). render/printers.py builds its LaTeX printer on the same memo.
"""

from __future__ import annotations

import sympy as sp
from sympy.printing.str import StrPrinter


# The order of a sum's terms (sympy sorts them for every printer, the str of results.json and
# the LaTeX of the report alike): by the sum and the order asked for, kept for every printer.
_ORDERED_TERMS: dict = {}
_MAX_ORDERED = 100_000


# The str printer's texts, for every SharedStrPrinter of the process (bounded: a batch of many
# problems keeps at most this many per printer memo).
_STR_PRINTED: dict = {}
_MAX_PRINTED = 200_000


class PrintsEachOnce:
    """The memo of the shared printers; `_key` is what the text of an expression depends on."""

    def _as_ordered_terms(self, expr, order=None):
        key = (expr, order or self.order)       # the order sympy's printer would use
        if key[1] == "old":                      # sorted by this printer's own comparison
            return super()._as_ordered_terms(expr, order=order)
        hit = _ORDERED_TERMS.get(key)
        if hit is None:
            hit = super()._as_ordered_terms(expr, order=order)
            if len(_ORDERED_TERMS) < _MAX_ORDERED:
                _ORDERED_TERMS[key] = hit
        return list(hit)

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
