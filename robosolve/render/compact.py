"""Big results readable: the course's compact trigonometric notation and long formulas broken up.

* `CompactTrig`: cos/sin of a revolute joint, or of a sum of revolute joints, is written
  the course's way, c₁ = cos θ₁, s₂₃ = sin(θ₂ + θ₃); each report defines the ones it uses
  once, after its conventions (`definitions`).
* `display_lines`: a display equation whose LaTeX is too long to read is laid out
  entry by entry (a matrix: `M[1,4] = …`, zero entries summarised) or, for a long sum,
  as an `array` with a few terms per line, so that no line of report.md runs to
  thousands of characters and GitHub and report.html show it without endless scrolling.
"""

from __future__ import annotations

import sympy as sp

from robosolve.core.printing import ordered_terms, latex

# A display formula longer than this (LaTeX characters) is broken up.
MATRIX_LIMIT = 1400
SCALAR_LIMIT = 450
# A matrix whose widest entries add up to more LaTeX characters than this is too wide
# for a page or a phone: it is shown entry by entry.
WIDTH_LIMIT = 300
# Characters of LaTeX per line of a broken-up sum.
LINE_CHARS = 170


class CompactTrig:
    """Replaces cos/sin of (sums of) revolute joints by c_{ij}/s_{ij} symbols, recording uses."""

    def __init__(self, problem):
        joints = [j for j in getattr(problem, "joints", []) if j.is_revolute]
        wide = len(getattr(problem, "joints", [])) > 9
        self.index = {j.symbol: j.index + 1 for j in joints}
        self.sep = "," if wide else ""
        self.names: dict = {}               # compact symbol -> LaTeX name
        self.meaning: dict = {}             # compact symbol -> (func, argument)
        self._cache: dict = {}

    def _label(self, arg):
        terms = sp.Add.make_args(arg)
        if not terms or any(t not in self.index for t in terms) or len(set(terms)) != len(terms):
            return None
        return self.sep.join(str(i) for i in sorted(self.index[t] for t in terms))

    def _symbol(self, func, arg):
        key = (func, arg)
        if key not in self._cache:
            label = self._label(arg)
            if label is None:
                self._cache[key] = None
            else:
                letter = "c" if func is sp.cos else "s"
                sym = sp.Symbol(f"rs_{letter}_{label.replace(',', '_')}")
                self._cache[key] = sym
                self.names[sym] = f"{letter}_{{{label}}}"
                self.meaning[sym] = (func, arg)
        return self._cache[key]

    def __call__(self, obj):
        if not self.index or not isinstance(obj, (sp.Basic, sp.MatrixBase)):
            return obj
        if isinstance(obj, sp.MatrixBase):
            return obj.applyfunc(self)
        if not obj.has(sp.cos, sp.sin):
            return obj

        def query(e):
            return isinstance(e, (sp.cos, sp.sin)) and self._symbol(type(e), e.args[0]) is not None

        return obj.replace(query, lambda e: self._symbol(type(e), e.args[0]))

    def definitions(self, used_latex: str, names: dict) -> str | None:
        """'Notation: c_{1} = cos θ₁, …' for the compact symbols that appear in the report."""
        used = [s for s in self.names if self.names[s] in used_latex]
        if not used:
            return None

        def order(s):
            func, arg = self.meaning[s]
            return (len(sp.Add.make_args(arg)), self.names[s][2:], func is sp.sin)

        parts = []
        for s in sorted(used, key=order):
            func, arg = self.meaning[s]
            inner = latex(arg, symbol_names=names)
            inner = inner if len(sp.Add.make_args(arg)) == 1 else f"({inner})"
            parts.append(f"${self.names[s]} = \\{func.__name__}{inner if inner.startswith('(') else ' ' + inner}$")
        return ("Notation (the course's): " + ", ".join(parts) + ".")


def _is_matrix(value) -> bool:
    if isinstance(value, sp.MatrixBase):
        return True
    return isinstance(value, (list, tuple)) and bool(value) and all(isinstance(r, (list, tuple)) for r in value)


def _rows(value):
    if isinstance(value, sp.MatrixBase):
        return [list(value.row(i)) for i in range(value.rows)]
    return [list(r) for r in value]


def _width(value, tex) -> int:
    """A rough printed width: the sum over columns of the longest entry's LaTeX."""
    rows = _rows(value)
    return sum(max(len(tex(r[j])) for r in rows) for j in range(len(rows[0])))


def _is_zero(x) -> bool:
    # the assumptions' is_zero only for numbers: on a big symbolic entry it costs a tenth
    # of a report's time, and a symbolic entry that is zero has already become 0
    try:
        return bool(x == 0) or (isinstance(x, sp.Basic) and not x.free_symbols and x.is_zero is True)
    except TypeError:
        return False


def _lines(expr, tex, budget: int = LINE_CHARS) -> list[str]:
    """LaTeX of `expr` cut into lines of about `budget` characters, at the terms of its sums
    (recursively: a factor times a long sum becomes `factor·⟮ … ⟯` over several lines)."""
    whole = tex(expr)
    if len(whole) <= budget or not isinstance(expr, (sp.Add, sp.Mul)):
        return [whole]
    if isinstance(expr, sp.Mul):
        adds = [a for a in expr.args if isinstance(a, sp.Add)]
        if not adds:
            return [whole]
        body = max(adds, key=lambda a: len(tex(a)))
        factor = sp.Mul(*[a for a in expr.args if a is not body])
        inner = _lines(body, tex, budget)
        head = "" if factor == 1 else ("-" if factor == -1 else tex(factor) + " \\cdot")
        if len(inner) == 1:
            return [f"{head} \\Bigl( {inner[0]} \\Bigr)".strip()]
        return [f"{head} \\Bigl( {inner[0]}".strip(), *inner[1:-1], f"{inner[-1]} \\Bigr)"]
    out, line = [], ""
    for k, term in enumerate(ordered_terms(expr)):          # the printers' order of the terms
        negative = term.could_extract_minus_sign()
        pieces = _lines(-term if negative else term, tex, budget)
        sign = "-" if negative else ("+" if k else "")
        pieces[0] = f"{sign} {pieces[0]}".strip()
        for piece in pieces:
            if line and len(line) + len(piece) > budget:
                out.append(line)
                line = piece
            else:
                line = f"{line} {piece}".strip()
    out.append(line)
    return out


def _sum_lines(lhs: str, expr, tex) -> str | None:
    """A long expression as an `array`, its lines cut at the terms of its sums."""
    lines = _lines(expr, tex)
    if len(lines) < 2:
        return None
    head = f"{lhs} =" if lhs else ""
    rows = [f"{head} & {lines[0]}"] + [f" & \\quad {ln}" for ln in lines[1:]]
    return "\\begin{array}{rl}\n" + " \\\\\n".join(rows) + "\n\\end{array}"


def display_lines(lhs: str, value, tex) -> tuple[str | None, list[str]]:
    """(an introductory sentence or None, the display formulas) for one equation. `lhs` is
    LaTeX, or a `Text` whose numbers the one number policy writes (a decimal interval's bounds)."""
    if not isinstance(lhs, str):
        lhs = tex(lhs)
    whole = f"{lhs} = {tex(value)}" if lhs else tex(value)
    if _is_matrix(value) and (len(whole) > MATRIX_LIMIT or _width(value, tex) > WIDTH_LIMIT):
        rows = _rows(value)
        name = lhs.split(" = ")[0].split("\\;")[0] if lhs else "M"
        shown, zeros = [], []
        column = len(rows[0]) == 1
        for i, row in enumerate(rows, 1):
            for j, x in enumerate(row, 1):
                index = f"[{i}]" if column else f"[{i},{j}]"
                if _is_zero(x):
                    zeros.append(index)
                else:
                    entry = f"{name}{index}"
                    long = isinstance(x, sp.Basic) and len(tex(x)) > SCALAR_LIMIT and _sum_lines(entry, x, tex)
                    shown.append(long or f"{entry} = {tex(x)}")
        shape = f"vector of {len(rows)}" if column else f"{len(rows)}×{len(rows[0])} matrix"
        intro = (f"${lhs}$, a {shape} too large to print whole, entry by entry"
                 + (f" (entries {', '.join(zeros)} are 0)" if zeros else "") + ":") if lhs else None
        return intro, shown
    if isinstance(value, sp.Basic) and not _is_matrix(value) and len(whole) > SCALAR_LIMIT:
        broken = _sum_lines(lhs, value, tex)
        if broken is not None:
            return None, [broken]
    return None, [whole]
