"""The one number-formatting policy of robosolve's outputs.

results.json keeps 12 significant digits (enough for any exam, and it hides
the last-bit noise between machines), fewer where the answer schema says the value is
worth fewer (`AnswerKey.digits`, e.g. a simulation's errors); report.md shows 6.
Solvers put raw numbers in answers and steps, and raw `Num`s in prose
(`robosolve.core.prose`): `text()` formats prose, `json_number` / `report_number` numbers.
"""

from __future__ import annotations

import math

from robosolve.core.prose import Num, Text

JSON_DIGITS = 12
REPORT_DIGITS = 6
# Round-off of exact zeros (cos(pi/2) = 6.1e-17) is shown as 0.
ZERO = 1e-13


def json_number(x, digits: int | None = None):
    """A float for results.json with `digits` (default JSON_DIGITS) significant digits."""
    if isinstance(x, bool) or x is None:
        return x
    if isinstance(x, int):
        return x
    x = float(x)
    if not math.isfinite(x):
        return None
    if abs(x) < ZERO:
        return 0.0
    r = float(f"{x:.{digits or JSON_DIGITS}g}")
    return 0.0 if r == 0 else r


def json_angle(x, digits: int | None = None):
    """`json_number` for an angle wrapped into (−π, π] (or [0, π]): rounding to 12 digits must not
    carry a value next to ±π out of its interval (π = 3.14159265358979… rounds up to
    3.14159265359 > π), so such a value is written as π itself, the interval's end."""
    r = json_number(x, digits)
    if isinstance(r, float) and abs(r) > math.pi and abs(abs(float(x)) - math.pi) < 1e-9:
        return math.pi
    return r


def text(v, math: bool = False) -> str:
    """Prose with its numbers formatted: `Text` pieces joined, each `Num` as `prose_number`
    (or `report_number` when the prose sits in a formula: `math=True`)."""
    if isinstance(v, str):
        return v
    if isinstance(v, Num):
        s = report_number(v.value, v.digits) if math else prose_number(v.value, v.digits)
        return f"{s} {v.unit}" if v.unit else s
    if isinstance(v, Text):
        return "".join(text(p, math) for p in v)
    return str(v)


def prose_number(x, digits: int | None = None) -> str:
    """A number in running text or a table cell (no LaTeX: 8.839e-05), round-off shown as 0."""
    if isinstance(x, bool) or x is None or isinstance(x, int):
        return report_number(x)
    x = float(x)
    if not math.isfinite(x) or abs(x) < ZERO:
        return report_number(x)
    s = f"{x:.{digits or REPORT_DIGITS}g}"
    return "0" if s in ("-0", "-0.0") else s


def marks_number(x) -> str:
    """A question's marks (or their total) as a teacher writes them: an integer or an exact
    fraction as it is (2, 1/2), a decimal without float noise (1.5, not 1.50000000000000)."""
    import sympy as sp

    x = sp.sympify(x)
    if x.is_Integer or x.is_Rational:
        return str(x)
    return prose_number(float(x))


def report_number(x, digits: int | None = None) -> str:
    if isinstance(x, bool):
        return "true" if x else "false"
    if x is None:
        return "—"
    if isinstance(x, int):
        return str(x)
    x = float(x)
    if not math.isfinite(x):
        return "∞" if x > 0 else ("−∞" if x < 0 else "NaN")
    if abs(x) < ZERO:
        return "0"
    s = f"{x:.{digits or REPORT_DIGITS}g}"
    if s in ("-0", "-0.0"):
        s = "0"
    if "e" in s:
        mant, exp = s.split("e")
        return f"{mant} \\times 10^{{{int(exp)}}}"
    return s
