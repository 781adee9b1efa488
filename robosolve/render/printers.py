"""sympy's printers, each subexpression printed once per document.

The entries of a report's matrices share their subexpressions (the same sums of products of
c_{1}, s_{23}, … in M, W, H and their numbers), and sympy's printers sort and print each sum
again wherever it occurs. Their printing methods depend only on the expression and the
printer's settings (and, for `str`, on the level: see `SharedStrPrinter`), so the text of a
subexpression printed without keyword arguments (`exp=` of a power of a function changes the
text) is kept and reused: the same text (tested against `sympy.latex` and `str`), in about
half of a report's printing time. The memo and the `str` printer are in core/printing.py
(solvers print with it too).
"""

from __future__ import annotations

import math

import sympy as sp
from sympy.printing.latex import LatexPrinter

from robosolve.core.printing import PrintsEachOnce as _PrintsEachOnce, SharedStrPrinter
from robosolve.render.numbers import REPORT_DIGITS

__all__ = ["SharedLatexPrinter", "SharedStrPrinter"]


class SharedLatexPrinter(_PrintsEachOnce, LatexPrinter):
    """`sympy.latex(expr, symbol_names=...)`, for report.md. The printer reads `symbol_names`
    when it prints a symbol: names added to that dict later are seen."""

    def __init__(self, symbol_names: dict):
        super().__init__({"symbol_names": symbol_names})
        self._printed: dict = {}

    # The report's number policy (render/numbers.py: REPORT_DIGITS significant digits) for the
    # decimals inside expressions too (a decimal `from` gives T = 1.41421 √π, not 1.4142135623731),
    # and no "1.0 t²" for a decimal coefficient that prints as ±1.
    def _print_Float(self, expr):
        x = float(expr)
        if not math.isfinite(x) or (x == int(x) and abs(x) < 1e15):
            return super()._print_Float(expr)      # 18.0 stays a visible decimal
        return super()._print_Float(sp.Float(f"{x:.{REPORT_DIGITS}g}"))   # sympy's layout, 6 digits

    def _print_Mul(self, expr):
        coeff, rest = expr.as_coeff_Mul()
        if coeff.is_Float and f"{abs(float(coeff)):.{REPORT_DIGITS}g}" == "1" and rest != 1:
            return self._print(-rest if coeff < 0 else rest)
        return super()._print_Mul(expr)
