"""The one number-formatting policy of robosolve's outputs.

results.json keeps 12 significant digits (enough for any exam, and it hides
the last-bit noise between machines); report.md shows 6.
"""

from __future__ import annotations

import math

JSON_DIGITS = 12
REPORT_DIGITS = 6
# Round-off of exact zeros (cos(pi/2) = 6.1e-17) is shown as 0.
ZERO = 1e-13


def json_number(x):
    if isinstance(x, bool) or x is None:
        return x
    if isinstance(x, int):
        return x
    x = float(x)
    if not math.isfinite(x):
        return None
    if abs(x) < ZERO:
        return 0.0
    r = float(f"{x:.{JSON_DIGITS}g}")
    return 0.0 if r == 0 else r


def report_number(x) -> str:
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
    s = f"{x:.{REPORT_DIGITS}g}"
    if s in ("-0", "-0.0"):
        s = "0"
    if "e" in s:
        mant, exp = s.split("e")
        return f"{mant} \\times 10^{{{int(exp)}}}"
    return s
