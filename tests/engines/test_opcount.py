"""robosolve.core.opcount.count_ops against sympy's count_ops (the reference it replaces): random
expressions of every shape its rules distinguish, and the expressions of the golden results."""

from __future__ import annotations

import json
import random
from pathlib import Path

import sympy as sp

from robosolve.core.opcount import count_ops

ROOT = Path(__file__).resolve().parents[2]
x, y, z = sp.symbols("x y z")
n = sp.Symbol("n", negative=True)


def _random_expr(rng: random.Random, depth: int):
    if depth == 0 or rng.random() < 0.2:
        return rng.choice([x, y, z, n, sp.Integer(rng.randint(-3, 3)), sp.Rational(rng.randint(-5, 5), rng.randint(1, 4)),
                           sp.Float(rng.uniform(-2, 2), 6), sp.pi, sp.E, sp.S.Half, sp.S.NegativeOne])
    k = rng.randrange(12)
    a = _random_expr(rng, depth - 1)
    b = _random_expr(rng, depth - 1)
    if k == 0:
        return a + b
    if k == 1:
        return a - b
    if k == 2:
        return a * b
    if k == 3:
        return -a * b
    if k == 4:
        return a / (b if b != 0 else x)
    if k == 5:
        return a ** rng.choice([2, 3, -1, -2, sp.Rational(1, 2), sp.Rational(-1, 2)])
    if k == 6:
        return rng.choice([sp.sin, sp.cos, sp.exp, sp.sqrt, sp.Abs])(a)
    if k == 7:
        return sp.atan2(a, b)
    if k == 8:
        return sp.Max(a, b) if rng.random() < 0.5 else sp.Min(a, x)
    if k == 9:
        return -a - b - x
    if k == 10:
        return sp.Piecewise((a, x > 0), (b, True))
    return a * b * z / 3


def test_random_expressions_count_as_sympy_counts_them():
    rng = random.Random(20261203)
    checked = 0
    for _ in range(1500):
        try:
            e = _random_expr(rng, rng.randint(1, 5))
        except (ValueError, TypeError, ZeroDivisionError):     # Max of complex numbers, ...
            continue
        if not isinstance(e, sp.Basic):
            continue
        assert count_ops(e) == sp.count_ops(e), e
        checked += 1
    assert checked > 1300


def test_matrices_and_lists_are_summed():
    m = sp.Matrix([[x + y, -x * y], [sp.sin(x) ** 2, 1 / (x + 1)]])
    assert count_ops(m) == sp.count_ops(m) == sum(sp.count_ops(e) for e in m)
    assert count_ops([x + 1, -y]) == sp.count_ops([x + 1, -y])


def test_the_golden_results_expressions():
    """Every symbolic string of a few golden results.json files, parsed back."""
    strings: list[str] = []

    def walk(v):
        if isinstance(v, str):
            strings.append(v)
        elif isinstance(v, dict):
            for w in v.values():
                walk(w)
        elif isinstance(v, list):
            for w in v:
                walk(w)

    for name in ("puma560-dynamics", "ur5", "scara-payload-dynamics", "ik-anthropomorphic-3r"):
        doc = json.loads((ROOT / "tests" / "golden" / name / "results.json").read_text(encoding="utf-8"))
        for a in doc["answers"].values():
            walk(a.get("symbolic", {}))
    checked = 0
    for s in strings[:600]:
        try:
            e = sp.sympify(s)
        except (sp.SympifyError, SyntaxError, TypeError, ValueError, AttributeError):
            continue
        if isinstance(e, sp.Expr):
            assert count_ops(e) == sp.count_ops(e), s
            checked += 1
    assert checked > 200
