"""Parse the expressions of a problem file into sympy, safely.

We never hand user text to `sympify`/`eval`: the text is parsed by Python's
`ast`, only arithmetic, numbers, known names, the allowed functions and
`P.x` point coordinates are accepted, and the tree is converted to sympy by
hand. So a typo never becomes a silent new symbol (it is an error with a
did-you-mean), and no input can run code or build a gigantic number.
"""

from __future__ import annotations

import ast
import difflib
import math

import sympy as sp

MAX_EXPRESSION_CHARS = 2000
MAX_NODES = 2000
MAX_EXPONENT = 1000
# Numbers are bounded by their size on the expression tree *before* anything is evaluated:
# big-integer and mpmath work cannot be interrupted by a time limit, so exp(exp(exp(100))) or
# ((9**999)**999)**999 must be refused before sympy starts on it.
MAX_LOG10 = 300          # |value| < 1e300 (the range of floating-point numbers, about 1.8e308)
# Exact arithmetic grows with the size of its numbers, which no operation count sees: a link of
# L1**999 m (1/2**999, 301 digits) held a 2R arm's equations of motion for 90 s of CPU (its safety
# net), 40 digits for 17 s, 20 digits for 2 s (0.7 s with L1). An exam's exact numbers have a few
# digits (0.0125 = 1/80, deg(30) = pi/6).
MAX_EXACT_DIGITS = 30
SHORT_NUMBER_CHARS = 40  # a longer number in a message is said by its size and value, not quoted
SHOWN_CHARS = 200        # a message quotes at most this much of a text (an answers file may hold 1 MB)


def deg(x):
    """deg(x) = x * pi / 180."""
    return x * sp.pi / 180


FUNCTIONS = {
    "sin": sp.sin, "cos": sp.cos, "tan": sp.tan,
    "asin": sp.asin, "acos": sp.acos, "atan": sp.atan, "atan2": sp.atan2,
    "sqrt": sp.sqrt, "exp": sp.exp, "log": sp.log, "abs": sp.Abs, "deg": deg,
}
FUNCTION_ARITY = {name: 1 for name in FUNCTIONS} | {"atan2": 2}
CONSTANTS = {"pi": sp.pi}
PIECEWISE = ("Piecewise", "piecewise")     # answers files only (Namespace.piecewise)
COMPARISONS = {ast.Lt: sp.Lt, ast.LtE: sp.Le, ast.Gt: sp.Gt, ast.GtE: sp.Ge}
RESERVED = set(FUNCTIONS) | set(CONSTANTS) | {"t"}
COORDINATE_ATTRS = ("x", "y", "z")


class ExpressionError(Exception):
    """Why an expression was rejected (a message for the user)."""


def shown(text: str, width: int = SHOWN_CHARS) -> str:
    """A text as a message quotes it: at most about `width` characters, the middle left out."""
    return text if len(text) <= width else text[:width // 2] + "…" + text[-(width // 2):]


def point_symbol(point: str, axis: str) -> sp.Symbol:
    """The placeholder for coordinate `axis` of point `point` in frame 0 (e.g. E.x)."""
    return sp.Symbol(f"{point}.{axis}", real=True)


def closest(name: str, candidates, cutoff: float = 0.5) -> str | None:
    """The candidate a misspelt `name` most likely stands for, or None (every did-you-mean).

    Ranked by: differing from `name` by case alone; then difflib's similarity with case ignored
    (at least `cutoff`); then the fewest typing slips (`_slips`: a swap of two neighbours is one,
    so 'ojints' means joints, not points, which difflib rates alike); then similarity with case;
    a tie goes to the last candidate in sorted order, as in difflib's `get_close_matches` (theta3
    among theta1, theta2: theta2). `get_close_matches` alone compares with case, so 'l1' among L1
    and m1 (0.5 both) was said to mean 'm1'."""
    if not isinstance(name, str):
        return None
    folded = name.casefold()
    best, best_rank = None, None
    for c in sorted(candidates, key=str):
        c_folded = str(c).casefold()
        matcher = difflib.SequenceMatcher(None, folded, c_folded)
        if matcher.real_quick_ratio() < cutoff or matcher.quick_ratio() < cutoff:
            continue
        ratio = matcher.ratio()
        if ratio < cutoff:
            continue
        rank = (c_folded == folded, ratio, -_slips(folded, c_folded),
                difflib.SequenceMatcher(None, name, str(c)).ratio())
        if best_rank is None or rank >= best_rank:
            best, best_rank = c, rank
    return best


def _slips(a: str, b: str) -> int:
    """The typing slips from `a` to `b`: letters left out, added, replaced, or two neighbours
    swapped, one each (the optimal string alignment distance)."""
    rows = [list(range(len(b) + 1))]
    for i in range(1, len(a) + 1):
        row = [i] + [0] * len(b)
        for j in range(1, len(b) + 1):
            row[j] = min(rows[-1][j] + 1, row[j - 1] + 1, rows[-1][j - 1] + (a[i - 1] != b[j - 1]))
            if i > 1 and j > 1 and a[i - 1] == b[j - 2] and a[i - 2] == b[j - 1]:
                row[j] = min(row[j], rows[-2][j - 2] + 1)
        rows.append(row)
    return rows[-1][-1]


def did_you_mean(name: str, candidates) -> str:
    close = closest(name, candidates)
    return f" (did you mean '{close}'?)" if close is not None else ""


def missing_keys(keys) -> str:
    """The one message for the required keys a mapping lacks: 'from', 'to' and 'max_acceleration'."""
    if len(keys) == 1:
        return f"missing required key '{keys[0]}'"
    quoted = [f"'{k}'" for k in keys]
    return f"missing required keys {', '.join(quoted[:-1])} and {quoted[-1]}"


def meant_value(value, choices):
    """The choice a misspelt word stands for (its did-you-mean), or None: after the message about
    it, the rest of the file is checked with that choice (one mistake, one message)."""
    return closest(value, choices)


def degrees_hint(e) -> str | None:
    """A warning for an angle given as a plain number that reads like degrees (90, -90, 30, 180:
    a whole multiple of 5 beyond a full turn), which robosolve takes in radians; None otherwise."""
    if not isinstance(e, sp.Number) or e == 0:
        return None
    v = float(e)
    if abs(v) <= 2 * math.pi + 1e-9 or abs(v / 5 - round(v / 5)) > 1e-9:
        return None
    text = f"{v:g}"
    return (f"{text} is an angle in radians ({abs(v) / (2 * math.pi):.3g} turns); if degrees were meant, "
            f"write deg({text})")


class _TooLarge(Exception):
    pass


def size_issue(expr, values: dict | None = None, memo: dict | None = None) -> str | None:
    """Why `expr` (with the numeric `values` of some symbols substituted) holds a number too
    large to compute, or None. Works on the tree, evaluating only subtrees already bounded.
    `memo` (estimates of subtrees already seen, for the same `values`) may be shared between
    calls: a parser checks every product it builds, and each holds the ones below it."""
    memo = {} if memo is None else memo
    try:
        _log10(sp.sympify(expr), values or {}, memo)
    except _TooLarge as exc:
        return str(exc)
    except (RecursionError, MemoryError):
        return "the expression is too deeply nested"
    return None


def _too_large(log10: float):
    return _TooLarge(f"a number in it is too large (about 10^{log10:.3g}; robosolve handles magnitudes "
                     f"up to 1e{MAX_LOG10})")


def _numeric(expr, values) -> complex | None:
    """The value of a subtree already known to be bounded, or None when it is symbolic."""
    v = expr.xreplace(values) if values else expr
    if v.free_symbols:
        return None
    try:
        return complex(sp.N(v, 15))
    except (TypeError, ValueError, OverflowError, ZeroDivisionError):
        return None


def _log10(e, values, memo) -> float | None:
    """An estimate of log10|e| (None: depends on an unknown symbol); raises _TooLarge."""
    if e in memo:
        return memo[e]
    est = _log10_node(e, values, memo)
    if est is not None and est > MAX_LOG10 + 5:   # (the estimate is rough: a little slack)
        raise _too_large(est)
    memo[e] = est
    return est


def _log10_node(e, values, memo) -> float | None:
    if e.is_Integer:
        return max(int(e).bit_length() - 1, 0) * 0.30103
    if e.is_Rational:
        return _log10(sp.Integer(e.p), values, memo) or 0.0
    if e.is_Float:
        sign, man, exp, bc = e._mpf_ if len(e._mpf_) == 4 else (0, 0, 0, 0)
        return (exp + bc) * 0.30103 if man else 0.0
    if e.is_Symbol:
        return _log10(sp.sympify(values[e]), values, memo) if e in values else None
    if e.is_NumberSymbol or e is sp.I:
        return 0.5
    args = [_log10(a, values, memo) for a in e.args]
    if any(a is None for a in args):
        return None
    if e.is_Add:
        return max(args) + 0.5
    if e.is_Mul:
        return sum(max(a, 0.0) for a in args)
    if e.is_Pow:
        return _log10_power(e, args, values)
    if isinstance(e, sp.exp):
        x = _numeric(e.args[0], values)
        if x is None:
            return None
        return x.real * 0.4343
    if isinstance(e, (sp.sin, sp.cos, sp.asin, sp.acos, sp.atan, sp.atan2)):
        return 0.5  # bounded for the real arguments of a problem file
    if isinstance(e, sp.log):
        return math.log10(max(args[0], 1.0) * 2.303 + 1.0)
    return max(args + [0.0])


def _log10_power(e, args, values) -> float | None:
    base, exponent = e.args
    if args[0] <= 1e-12 and base.is_number and abs(complex(sp.N(base, 15))) == 1:
        return 0.0
    k = _numeric(exponent, values)
    if k is None:
        return None
    if abs(k.real) > 1e6:
        raise _too_large(abs(k.real))
    b = _numeric(base, values)
    if b is not None and b != 0:
        return k.real * math.log10(abs(b))
    return abs(k.real) * args[0]


def value_issue(e, values: dict, shown: str | None = None) -> str | None:
    """Why the expression `e` with `values` substituted is not a finite real number, or None.

    `shown` is the text the user wrote (sympy may have evaluated log(0) to zoo already)."""
    e = sp.sympify(e)   # a symbol replaced by a plain 0 (`t` at the start) is an int
    issue = size_issue(e, values)
    if issue is not None:
        return issue
    v = sp.sympify(e.xreplace(values)) if values else e
    if v.free_symbols:
        return None
    what = shown if shown is not None else str(e)
    given = f" (with the parameters' values it is {v})" if e.free_symbols and len(str(v)) < 80 else ""
    undefined = f"{what} is undefined or infinite (a division by zero, log(0), tan(pi/2)?)" + given
    if v.has(sp.zoo, sp.nan, sp.oo, -sp.oo):
        return undefined
    try:
        c = complex(sp.N(v, 15))
    except (TypeError, ValueError, ZeroDivisionError, OverflowError):
        return f"{what} has no numeric value" + given
    if not (math.isfinite(c.real) and math.isfinite(c.imag)):
        return undefined
    if abs(c.imag) > 1e-12 * max(1.0, abs(c.real)):
        return (f"{what} is not a real number (it is {c.real:.6g}{c.imag:+.6g}i: a square root or "
                "logarithm of a negative number, or acos/asin beyond [-1, 1]?)")
    return digits_issue(what, v, c.real)


def exact_digits(e) -> int:
    """The most decimal digits of a numerator or a denominator among the rationals of `e`."""
    return max((len(str(max(abs(r.p), abs(r.q)))) for r in e.atoms(sp.Rational)), default=0)


# the advice of a value typed in a problem file too long to stay exact (`robosolve variants`
# gives its own for a drawn value, which nobody typed)
DECIMAL_ADVICE = "write it as a decimal number"


def digits_issue(what: str, v, approx: float, advice: str = DECIMAL_ADVICE) -> str | None:
    """Why the value `v` (about `approx`) of `what` (the text the user wrote) holds an exact
    number too long, or None. The message quotes `what` when it is short: a 301-digit fraction
    (a variant's drawn value, written for the user by `robosolve variants`) is said by its size."""
    digits = exact_digits(v)
    if digits <= MAX_EXACT_DIGITS:
        return None
    what = what if len(what) <= SHORT_NUMBER_CHARS else "the value"
    return (f"{what} is an exact number of {digits} digits (about {approx:.3g}): robosolve keeps exact "
            f"numbers of at most {MAX_EXACT_DIGITS} digits, whose arithmetic stays fast; {advice}")


def number(value) -> sp.Expr:
    """A YAML number: exact when integer, a sympy Float otherwise."""
    if isinstance(value, bool):
        raise ExpressionError(f"expected a number or an expression, got {str(value).lower()}")
    if isinstance(value, int):
        return sp.Integer(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ExpressionError(f"{value} is not a finite number" + (
                " (too large for a floating-point number, which stops near 1.8e308)"
                if math.isinf(value) else ""))
        return sp.Float(value)
    raise ExpressionError("expected a number or an expression")


#: Typography a text pasted from a printed paper, a PDF or a word processor carries, and the
#: ASCII it stands for (answers are read through it: `typed_math`).
TYPOGRAPHY = {"\u2212": "-", "\u2013": "-", "\u00d7": "*", "\u00b7": "*", "\u22c5": "*", "\u2217": "*",
              "\u03c0": "pi", "\u00b2": "^2", "\u00b3": "^3", "\u00a0": " ", "\u2009": " ",
              "\u00b0": "*(pi/180)"}


def typed_math(text: str) -> str:
    """A student's typed expression in the parser's ASCII: `−0.45` (a Unicode minus), `2·L1`,
    `π/2`, `2π` and `2√2` (products by juxtaposition), `L1²`, `√3/4` and `√(a + b)` (a root of
    one number, name or parenthesis), `30°` (degrees, as deg(30))."""
    import re

    # print writes a product by juxtaposition (`2π`, `3π/4`, `2√2`, `√2π`): the factors touch,
    # so a space (which separates a typed matrix's entries) never becomes a product
    text = re.sub(r"(?<=[\d.)\u03c0\u00b2\u00b3])(?=[\u03c0\u221a])", "*", text)
    for mark, ascii_text in TYPOGRAPHY.items():
        text = text.replace(mark, ascii_text)
    text = re.sub(r"\u221a\s*(\d+(?:\.\d*)?|[A-Za-z_]\w*)", r"sqrt(\1)", text)
    return text.replace("\u221a", "sqrt")


def _parse_hint(text: str) -> str:
    import re

    marks = ([m for m in TYPOGRAPHY if m in text and m != "\u00b0"]     # (° has its own hint below)
             + (["\u221a"] if "\u221a" in text else []))
    if marks:
        return " (write " + ", ".join(
            f"{TYPOGRAPHY.get(m, 'sqrt(…)').strip() or 'a space'!r} for {m!r}" for m in marks) + ")"
    if re.fullmatch(r"\s*[-+]?\d+,\d+\s*", text):
        return f" (decimals are written with a point: {shown(text.strip().replace(',', '.'))})"
    # the number starts where a run of digits starts: no search restarted inside a long run
    m = re.search(r"(?<![\d.])(\d+(?:\.\d*)?)\s*(?:deg|°)", text)
    if m:
        return f" (for an angle in degrees write deg({shown(m.group(1))}); angles are radians otherwise)"
    if re.search(r"\d[a-zA-Z_(]", text):
        return " (write the multiplication: 2*L, not 2L)"
    return ""


class Namespace:
    """The names an expression may use, and what each one stands for."""

    def __init__(self, names: dict | None = None, points=(), what: str = "name", refused=None,
                 unknown_ok: bool = False, max_chars: int = MAX_EXPRESSION_CHARS, max_nodes: int = MAX_NODES,
                 piecewise: bool = False):
        self.names: dict[str, sp.Basic] = dict(names or {})
        self.points = set(points)
        self.what = what
        # names known but meaningless here -> the message that says what to do instead
        self.refused: dict[str, str] = dict(refused or {})
        # a name refused where it is defined (a joint named `2*`): every unknown name may be one of
        # its uses, read as a plain symbol — the file is rejected already (one mistake, one message)
        self.unknown_ok = unknown_ok
        # the size of one expression: a problem file's are written by hand; an answers file may
        # hold the reference's own (a PUMA's velocity terms run to 15,000 characters)
        self.max_chars, self.max_nodes = max_chars, max_nodes
        # an answers file's profiles are piecewise in t (`piecewise(t < 1, t^2, ...)`, as the course
        # writes them, or sympy's `Piecewise((t**2, t < 1), ...)`, as results.json does); a problem
        # file has no use for them
        self.piecewise = piecewise

    def with_names(self, extra: dict) -> "Namespace":
        return Namespace({**self.names, **extra}, self.points, self.what, self.refused, self.unknown_ok,
                         self.max_chars, self.max_nodes, self.piecewise)

    def without_points(self) -> "Namespace":
        return Namespace(self.names, (), self.what, self.refused, self.unknown_ok, self.max_chars,
                         self.max_nodes, self.piecewise)

    # ------------------------------------------------------------------
    def parse(self, value) -> sp.Expr:
        """Parse a YAML value (number or string) into a sympy expression."""
        if isinstance(value, str):
            return self.parse_text(value)
        return number(value)

    def parse_text(self, text: str) -> sp.Expr:
        text = text.strip()
        if not text:
            raise ExpressionError("empty expression")
        if len(text) > self.max_chars:
            raise ExpressionError(f"expression longer than {self.max_chars} characters")
        try:
            tree = ast.parse(text.replace("^", "**"), mode="eval")
        except SyntaxError:
            raise ExpressionError(f"cannot parse expression {shown(text)!r}" + _parse_hint(text)) from None
        except (RecursionError, MemoryError, ValueError):
            raise ExpressionError("expression too deeply nested") from None
        count = sum(1 for _ in ast.walk(tree))
        if count > self.max_nodes:
            raise ExpressionError("expression too large")
        self._sizes: dict = {}      # size estimates of the subtrees built, shared by `_bounded`
        try:
            return self._convert(tree.body, shown(text))      # the text only goes into messages
        except RecursionError:
            raise ExpressionError("expression too deeply nested") from None

    def _convert(self, node, text):
        conv = lambda n: self._convert(n, text)  # noqa: E731
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise ExpressionError(f"unexpected {node.value!r} in {text!r}")
            if isinstance(node.value, float) and math.isinf(node.value):
                raise ExpressionError(f"a number in {text!r} is too large for a floating-point number "
                                      f"(they stop near 1.8e308; robosolve handles magnitudes up to 1e{MAX_LOG10})")
            return number(node.value)
        if isinstance(node, ast.Name):
            return self._name(node.id, text)
        if isinstance(node, ast.Attribute):
            if isinstance(node.value, ast.Name) and node.attr in COORDINATE_ATTRS:
                point = node.value.id
                if point in self.points:
                    return point_symbol(point, node.attr)
                if not self.points:
                    raise ExpressionError(f"point coordinates such as '{point}.{node.attr}' "
                                          "cannot be used here")
                raise ExpressionError(f"unknown point '{point}' in {text!r}"
                                      + did_you_mean(point, self.points))
            raise ExpressionError(f"unexpected '.{node.attr}' in {text!r} "
                                  "(only P.x, P.y, P.z of a named point)")
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            v = conv(node.operand)
            return -v if isinstance(node.op, ast.USub) else v
        if isinstance(node, ast.BinOp):
            a, b = conv(node.left), conv(node.right)
            if isinstance(node.op, ast.Add):
                return a + b
            if isinstance(node.op, ast.Sub):
                return a - b
            if isinstance(node.op, ast.Mult):
                return self._bounded(a * b, text)
            if isinstance(node.op, ast.Div):
                if b.is_zero:
                    raise ExpressionError(f"division by zero in {text!r}")
                return a / b
            if isinstance(node.op, ast.Pow):
                if b.is_number and (abs(b) > MAX_EXPONENT):
                    raise ExpressionError(f"exponent too large in {text!r}")
                if a.is_zero and b.is_number and b.is_negative:
                    raise ExpressionError(f"division by zero in {text!r}")
                return self._bounded(sp.Pow(a, b, evaluate=False), text, lambda: a ** b)
            raise ExpressionError(f"operator not allowed in {text!r} (use + - * / ** or ^)")
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.keywords:
                raise ExpressionError(f"unexpected call in {text!r}")
            name = node.func.id
            if self.piecewise and name in PIECEWISE:
                return self._piecewise(node, text)
            if name not in FUNCTIONS:
                raise ExpressionError(f"unknown function '{name}' in {text!r}"
                                      + did_you_mean(name, FUNCTIONS))
            if len(node.args) != FUNCTION_ARITY[name]:
                raise ExpressionError(f"{name}() takes {FUNCTION_ARITY[name]} argument(s) in {text!r}")
            args = [conv(a) for a in node.args]
            if name == "exp":
                return self._bounded(sp.exp(args[0], evaluate=False), text, lambda: sp.exp(args[0]))
            return FUNCTIONS[name](*args)
        if self.piecewise and isinstance(node, (ast.Compare, ast.BoolOp)):
            raise ExpressionError(f"a condition stands only in piecewise(…) in {text!r} "
                                  "(piecewise(t < 1, t^2, 2 - (2 - t)^2))")
        raise ExpressionError(f"not allowed in an expression: {text!r}" + _parse_hint(text))

    def _piecewise(self, node, text):
        """`Piecewise((e1, c1), (e2, c2), …)` (sympy's, results.json's) or `piecewise(c1, e1, c2, e2,
        …[, otherwise])` (Maple's and MATLAB's, the course's): the first piece whose condition holds."""
        args = node.args
        if args and all(isinstance(a, ast.Tuple) and len(a.elts) == 2 for a in args):
            pairs = [(a.elts[0], a.elts[1]) for a in args]
        elif len(args) >= 2 and not any(isinstance(a, ast.Tuple) for a in args):
            pairs = [(args[i + 1], args[i]) for i in range(0, len(args) - 1, 2)]
            if len(args) % 2:
                pairs.append((args[-1], ast.Constant(True)))
        else:
            raise ExpressionError(f"{node.func.id}() takes (expression, condition) pairs, as in "
                                  f"Piecewise((t**2, t < 1), (1, True)), or conditions and expressions "
                                  f"in turn, as in piecewise(t < 1, t^2, 1), in {text!r}")
        pieces = [(self._convert(e, text), self._condition(c, text)) for e, c in pairs]
        try:
            return sp.Piecewise(*pieces)
        except (TypeError, ValueError) as exc:
            raise ExpressionError(f"cannot read {text!r} as a piecewise expression: {exc}") from None

    def _condition(self, node, text):
        """A condition of a piecewise expression: comparisons (chained: `0 <= t < 1`), joined by
        `and` / `&`, `or` / `|`; `True` (or `otherwise`) for the last piece."""
        if isinstance(node, ast.Constant) and isinstance(node.value, bool):
            return sp.true if node.value else sp.false
        if isinstance(node, ast.Name) and node.id in ("true", "otherwise"):
            return sp.true
        if isinstance(node, ast.BoolOp) or (isinstance(node, ast.BinOp) and isinstance(node.op, (ast.BitAnd, ast.BitOr))):
            parts = node.values if isinstance(node, ast.BoolOp) else [node.left, node.right]
            both = sp.And if isinstance(node.op, (ast.And, ast.BitAnd)) else sp.Or
            return both(*(self._condition(p, text) for p in parts))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            return sp.Not(self._condition(node.operand, text))
        if isinstance(node, ast.Compare):
            sides = [self._convert(x, text) for x in [node.left, *node.comparators]]
            tests = []
            for op, a, b in zip(node.ops, sides, sides[1:]):
                if type(op) not in COMPARISONS:
                    raise ExpressionError(f"a condition compares with < <= > >= in {text!r}")
                try:
                    tests.append(COMPARISONS[type(op)](a, b))
                except TypeError as exc:
                    raise ExpressionError(f"cannot compare in {text!r}: {exc}") from None
            return sp.And(*tests)
        raise ExpressionError(f"expected a condition (t < 1, 0 <= t and t < 2, True) in {text!r}")

    def _bounded(self, unevaluated, text, evaluate=None):
        """`unevaluated` checked for number size first; then `evaluate()` builds the real thing."""
        issue = size_issue(unevaluated, memo=self._sizes)
        if issue is not None:
            raise ExpressionError(f"{text!r}: {issue}")
        return evaluate() if evaluate is not None else unevaluated

    def _name(self, name: str, text: str):
        if name in self.names:
            return self.names[name]
        if name in self.refused:
            raise ExpressionError(f"{self.refused[name]} (in {text!r})")
        if name in CONSTANTS:
            return CONSTANTS[name]
        if name in FUNCTIONS:
            raise ExpressionError(f"'{name}' is a function: write {name}(...)")
        if name in self.points:
            raise ExpressionError(f"'{name}' is a point: use {name}.x, {name}.y or {name}.z "
                                  "(Euler's number is exp(1))")
        if name == "e":
            raise ExpressionError("unknown name 'e' (Euler's number is exp(1))")
        if self.unknown_ok:
            return sp.Symbol(name, real=True)
        candidates = set(self.names) | set(CONSTANTS) | self.points
        raise ExpressionError(f"unknown {self.what} '{shown(name)}' in {text!r}"
                              + did_you_mean(name, candidates))
