"""The LaTeX names of a robot's symbols and of its poses' factors (presentation only).

`ChainNames(problem)`: `symbols` (theta1_dot -> \\dot{\\theta}_{1}, multi-letter names upright,
a point's coordinate placeholders E.x -> E_{x}) and `factors(frame)` (R_z(\\theta_1),
DH(...), one name per matrix of `model.description.factor_matrices`). Built by the run layer
and handed to the solvers through `SolveContext(names=...)`; the report and the paper build
their own.
"""

from __future__ import annotations

import sympy as sp
from sympy.printing.conventions import split_super_sub

from robosolve.load.expressions import point_symbol
from robosolve.core.printing import latex

__all__ = ["ChainNames", "elementary_latex", "symbol_latex", "upright_name"]


def elementary_latex(op: str, arg, names: dict | None = None) -> str:
    """LaTeX of one factor of a pose string, e.g. R_z(\\theta_1)."""
    return f"{'T' if op[0] == 'T' else 'R'}_{{{op[1]}}}\\left({latex(arg, symbol_names=names or {})}\\right)"


def upright_name(name: str) -> str | None:
    """The LaTeX of a name whose letters before its subscript are several and not a Greek
    letter (`ma`, `Jg2`, `Kp`): upright, \\mathrm{ma}, so that it does not read as a product of
    italic one-letter symbols (m·a); None for the names sympy prints well (L1, m_p, theta1)."""
    base, sups, subs = split_super_sub(name)
    if len(base) < 2 or latex(sp.Symbol(base)).startswith("\\"):
        return None
    out = f"\\mathrm{{{base}}}"
    if subs:
        out += "_{" + " ".join(subs) + "}"
    if sups:
        out += "^{" + " ".join(sups) + "}"
    return out


def _accent(base: str, accent: str) -> str:
    """\\theta_{1} -> \\dot{\\theta}_{1}."""
    head, _, sub = base.partition("_")
    return f"\\{accent}{{{head}}}_{sub}"


def symbol_latex(problem) -> dict:
    """LaTeX names of the problem's symbols: theta1_dot -> \\dot{\\theta}_{1}."""
    out = {s: upright_name(s.name) for s in problem.parameters if upright_name(s.name)}
    for j in problem.joints:
        if upright_name(j.name):
            out[j.symbol] = upright_name(j.name)
        base = out.get(j.symbol) or latex(j.symbol)
        out[j.dot] = f"\\dot{{{base}}}" if "_" not in base else _accent(base, "dot")
        out[j.ddot] = f"\\ddot{{{base}}}" if "_" not in base else _accent(base, "ddot")
    for name in problem.points:
        for axis in "xyz":
            out[point_symbol(name, axis)] = f"{name}_{{{axis}}}"
    return out


class ChainNames:
    """The LaTeX names of one problem's symbols and poses."""

    def __init__(self, problem):
        self.problem = problem
        self.symbols = symbol_latex(problem)

    def factors(self, frame: str) -> list[str]:
        """The LaTeX of each factor of the frame's pose in its parent (one for a DH row or a
        matrix)."""
        f = self.problem.frames[frame]
        names = self.symbols

        def tex(e):
            return latex(e, symbol_names=names)

        if f.kind == "pose":
            return [elementary_latex(op, arg, names) for op, arg in f.factors]
        if f.kind == "matrix":
            return ["M"]
        if f.kind == "dh":
            th, d, a, al = f.factors
            return [f"DH({tex(th)}, {tex(d)}, {tex(a)}, {tex(al)})"]
        al, a, th, d = f.factors
        return [f"MDH({tex(al)}, {tex(a)}, {tex(th)}, {tex(d)})"]
