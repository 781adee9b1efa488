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
RESERVED = set(FUNCTIONS) | set(CONSTANTS) | {"t"}
COORDINATE_ATTRS = ("x", "y", "z")


class ExpressionError(Exception):
    """Why an expression was rejected (a message for the user)."""


def point_symbol(point: str, axis: str) -> sp.Symbol:
    """The placeholder for coordinate `axis` of point `point` in frame 0 (e.g. E.x)."""
    return sp.Symbol(f"{point}.{axis}", real=True)


def did_you_mean(name: str, candidates) -> str:
    close = difflib.get_close_matches(name, sorted(candidates), n=1, cutoff=0.5)
    return f" (did you mean '{close[0]}'?)" if close else ""


def number(value) -> sp.Expr:
    """A YAML number: exact when integer, a sympy Float otherwise."""
    if isinstance(value, bool):
        raise ExpressionError(f"expected a number or an expression, got {str(value).lower()}")
    if isinstance(value, int):
        return sp.Integer(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ExpressionError(f"{value} is not a finite number")
        return sp.Float(value)
    raise ExpressionError("expected a number or an expression")


class Namespace:
    """The names an expression may use, and what each one stands for."""

    def __init__(self, names: dict | None = None, points=(), what: str = "name", refused=None):
        self.names: dict[str, sp.Basic] = dict(names or {})
        self.points = set(points)
        self.what = what
        # names known but meaningless here -> the message that says what to do instead
        self.refused: dict[str, str] = dict(refused or {})

    def with_names(self, extra: dict) -> "Namespace":
        return Namespace({**self.names, **extra}, self.points, self.what, self.refused)

    def without_points(self) -> "Namespace":
        return Namespace(self.names, (), self.what, self.refused)

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
        if len(text) > MAX_EXPRESSION_CHARS:
            raise ExpressionError(f"expression longer than {MAX_EXPRESSION_CHARS} characters")
        try:
            tree = ast.parse(text.replace("^", "**"), mode="eval")
        except SyntaxError:
            raise ExpressionError(f"cannot parse expression {text!r}") from None
        except (RecursionError, MemoryError, ValueError):
            raise ExpressionError("expression too deeply nested") from None
        count = sum(1 for _ in ast.walk(tree))
        if count > MAX_NODES:
            raise ExpressionError("expression too large")
        try:
            return self._convert(tree.body, text)
        except RecursionError:
            raise ExpressionError("expression too deeply nested") from None

    def _convert(self, node, text):
        conv = lambda n: self._convert(n, text)  # noqa: E731
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise ExpressionError(f"unexpected {node.value!r} in {text!r}")
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
                return a * b
            if isinstance(node.op, ast.Div):
                if b.is_zero:
                    raise ExpressionError(f"division by zero in {text!r}")
                return a / b
            if isinstance(node.op, ast.Pow):
                if b.is_number and (abs(b) > MAX_EXPONENT):
                    raise ExpressionError(f"exponent too large in {text!r}")
                if a.is_zero and b.is_number and b.is_negative:
                    raise ExpressionError(f"division by zero in {text!r}")
                return a ** b
            raise ExpressionError(f"operator not allowed in {text!r} (use + - * / ** or ^)")
        if isinstance(node, ast.Call):
            if not isinstance(node.func, ast.Name) or node.keywords:
                raise ExpressionError(f"unexpected call in {text!r}")
            name = node.func.id
            if name not in FUNCTIONS:
                raise ExpressionError(f"unknown function '{name}' in {text!r}"
                                      + did_you_mean(name, FUNCTIONS))
            if len(node.args) != FUNCTION_ARITY[name]:
                raise ExpressionError(f"{name}() takes {FUNCTION_ARITY[name]} argument(s) in {text!r}")
            return FUNCTIONS[name](*[conv(a) for a in node.args])
        raise ExpressionError(f"not allowed in an expression: {text!r}")

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
        candidates = set(self.names) | set(CONSTANTS) | self.points
        raise ExpressionError(f"unknown {self.what} '{name}' in {text!r}"
                              + did_you_mean(name, candidates))
