"""Expressions in plain text as a user writes them in a problem or answers file: sympy's `str`
with the names of the expression language (`abs(x)`, not sympy's `Abs(x)`)."""

from __future__ import annotations

from sympy.printing.str import StrPrinter


class _UserPrinter(StrPrinter):
    def _print_Abs(self, expr):
        return f"abs({self._print(expr.args[0])})"


_PRINTER = _UserPrinter()


def plain(expr) -> str:
    """`expr` in the words of the expression language (load/expressions.py)."""
    return _PRINTER.doprint(expr)
