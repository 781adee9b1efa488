"""The report's LaTeX printer, which prints each subexpression once per report
(render/markdown.py:_SharedLatexPrinter), against sympy's own `latex` of every expression."""

from __future__ import annotations

import random

import sympy as sp

from robosolve.render.markdown import Tex

q1, q2, q3, L, m = sp.symbols("q1 q2 q3 L m")
NAMES = {q1: "\\theta_{1}", q2: "\\theta_{2}", q3: "\\vartheta_{3}", L: "L_{1}"}


def _random_expr(rng: random.Random, depth: int = 3):
    leaves = [q1, q2, q3, L, m, sp.Rational(3, 7), sp.Float(0.25), sp.pi, -1, 2]
    if depth == 0:
        return rng.choice(leaves)
    kind = rng.randrange(7)
    a, b = _random_expr(rng, depth - 1), _random_expr(rng, depth - 1)
    power = rng.choice([2, -1, sp.Rational(1, 2)])
    try:
        return [a + b, a * b, a - b, sp.cos(a), sp.sin(a + b) ** 2, a ** power, sp.sqrt(a * a + b)][kind]
    except ZeroDivisionError:      # 0.0 ** -1
        return a


def test_every_expression_prints_as_sympy_prints_it():
    rng = random.Random(15)
    exprs = [_random_expr(rng) for _ in range(80)]
    # the same subexpressions inside bigger ones, in matrices, after they were printed alone
    exprs += [sp.Matrix([[e, exprs[k + 1]], [exprs[k + 2] * e, -e]]) for k, e in enumerate(exprs[:20])]
    exprs += [sum(exprs[k:k + 5]) for k in range(0, 40, 5)]
    tex = Tex(NAMES)
    for e in exprs:
        assert tex(e) == sp.latex(_report_decimals(e), symbol_names=NAMES), e


def _report_decimals(e):
    """`e` with each Float at the report's 6 significant digits (render/numbers.py): the one
    place where the report's LaTeX departs from sympy's on purpose."""
    return e.xreplace({f: sp.Float(f"{float(f):.6g}") for f in e.atoms(sp.Float) if f != int(f)})


def test_decimals_follow_the_report_number_policy():
    t = sp.Symbol("t")
    tex = Tex({})
    assert tex(sp.Float(1.4142135623731) * sp.sqrt(sp.pi)) == r"1.41421 \sqrt{\pi}"
    assert tex(sp.Float(1.0000000000002) * t ** 2 / sp.pi + sp.Float(0.3)) == r"\frac{t^{2}}{\pi} + 0.3"
    assert tex(-sp.Float(1.0) * t) == "- t"
    assert tex(sp.Float(2.5e-9) * t) == r"2.5 \cdot 10^{-9} t"


def test_a_derivative_and_a_power_of_a_function_print_as_sympy_prints_them():
    t = sp.Symbol("t")
    f = sp.Function("f")(t)
    exprs = [sp.cos(q1) ** 2, sp.sin(q1 + q2) ** 3 * sp.cos(q1) ** 2, f.diff(t) ** 2 + f, sp.exp(-q1) ** 2]
    tex = Tex(NAMES)
    assert [tex(e) for e in exprs + exprs] == [sp.latex(e, symbol_names=NAMES) for e in exprs + exprs]


def test_results_json_strings_are_str_of_every_expression():
    """render/results_json.py:SharedStrPrinter against sympy's own `str` (Floats at the top and
    inside, as a matrix entry and within a sum, are printed differently by `str`)."""
    from robosolve.render.results_json import SharedStrPrinter, symbolic_value

    rng = random.Random(16)
    exprs = [_random_expr(rng) for _ in range(80)] + [sp.Float(2.0), sp.Float(0.5) * q1, q1 + sp.Float(1.25)]
    exprs += [sum(exprs[k:k + 5]) for k in range(0, 40, 5)]
    printer = SharedStrPrinter()
    for e in exprs + exprs[::-1]:
        assert printer.doprint(e) == str(e), e
    m = sp.Matrix([[sp.Float(1.0), q1 * sp.Float(2.0)], [exprs[3], exprs[4]]])
    assert symbolic_value({"M": m, "v": [exprs[5], sp.Float(3.0)]}, printer) == {
        "M": [[str(x) for x in m.row(i)] for i in range(2)], "v": [str(exprs[5]), str(sp.Float(3.0))]}


def test_the_term_order_kept_across_printers_prints_as_sympy_prints():
    """Sums printed by the str printer first, then by the LaTeX one (which reuses the terms'
    order the first computed), and in the other order: each as sympy prints it."""
    from robosolve.core.printing import SharedStrPrinter

    rng = random.Random(17)
    exprs = [sum(_random_expr(rng) for _ in range(4)) for _ in range(60)]
    # (a decimal coefficient printing as ±1 is dropped by the report on purpose: not compared here)
    exprs = [e for e in exprs if not any(a.is_Mul and a.args[0].is_Float and abs(float(a.args[0])) == 1
                                         for a in sp.preorder_traversal(e))][:40]
    assert len(exprs) == 40
    printer, tex = SharedStrPrinter(), Tex(NAMES)
    for e in exprs[:20]:
        assert printer.doprint(e) == str(e) and tex(e) == sp.latex(_report_decimals(e), symbol_names=NAMES), e
    for e in exprs[20:]:
        assert tex(e) == sp.latex(_report_decimals(e), symbol_names=NAMES) and printer.doprint(e) == str(e), e
