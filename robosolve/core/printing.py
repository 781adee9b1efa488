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


class PrintsEachOnce:
    """The memo of the shared printers; `_key` is what the text of an expression depends on."""

    def _key(self, expr):
        return expr

    def _print(self, expr, **kwargs) -> str:
        if kwargs or not isinstance(expr, sp.Basic):
            return super()._print(expr, **kwargs)
        key = self._key(expr)
        out = self._printed.get(key)
        if out is None:
            out = self._printed[key] = super()._print(expr)
        return out


class SharedStrPrinter(PrintsEachOnce, StrPrinter):
    """`str(expr)` of sympy expressions (not of matrices: results.json prints them entry by
    entry). A Float is printed differently at the top and inside another expression: that is
    part of the key."""

    def __init__(self):
        super().__init__({"order": None})       # what Basic.__str__ asks for
        self._printed: dict = {}

    def _key(self, expr):
        return expr, self._print_level == 0
