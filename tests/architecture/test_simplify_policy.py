"""One simplification policy: robosolve/core/simplify.py is the only module that calls
sympy's simplifiers (AST walk over the package), and its variants behave as documented."""

from __future__ import annotations

import ast
from pathlib import Path

import sympy as sp

from robosolve.core import simplify as S

PACKAGE = Path(__file__).resolve().parents[2] / "robosolve"
POLICY = PACKAGE / "core" / "simplify.py"
# The notebook's runtime runs in the notebook's kernel, not in robosolve: it imports nothing of
# robosolve (tests/render/test_notebook_runtime.py), so it simplifies what it shows with sympy.
NOTEBOOK_RUNTIME = PACKAGE / "render" / "notebook_runtime.py"

# simplifiers (what changes the form of an expression to make it "simpler"); algebra that
# computes something (factor_list for roots, cancel/together for a numerator) is not here
BANNED = {"simplify", "trigsimp", "fu", "factor", "factor_terms", "radsimp", "sqrtdenest",
          "nsimplify", "ratsimp", "powsimp", "combsimp", "logcombine", "exptrigsimp",
          "besselsimp", "hyperexpand"}


def _banned(name: str) -> bool:
    return name in BANNED or (name.startswith("TR") and name[2:].rstrip("i").isdigit())


def simplifier_calls(path: Path) -> list[str]:
    """'file:line name' of every use of a sympy simplifier in one file: `sp.simplify(...)`
    or `sp.nsimplify` passed along, a name imported from sympy, a method (`e.factor()`).
    A local function that happens to be called `simplify` (a parameter) is not one."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    where = path.relative_to(PACKAGE.parent)
    imported = {a.asname or a.name for node in ast.walk(tree)
                if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("sympy")
                for a in node.names if _banned(a.name)}
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("sympy"):
            out |= {(node.lineno, f"import {a.name}") for a in node.names if _banned(a.name)}
        elif isinstance(node, ast.Attribute) and _banned(node.attr):
            if isinstance(node.value, ast.Name) and node.value.id in ("sp", "sympy"):
                out.add((node.lineno, f"sp.{node.attr}"))
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in imported:
            out.add((node.lineno, node.func.id))
    for node in ast.walk(tree):   # methods: expr.simplify(), m.factor()
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and _banned(node.func.attr) \
                and not (isinstance(node.func.value, ast.Name) and node.func.value.id in ("sp", "sympy")):
            out.add((node.lineno, f".{node.func.attr}()"))
    return [f"{where}:{line} {name}" for line, name in sorted(out)]


def test_no_simplifier_outside_the_policy():
    calls = [c for p in sorted(PACKAGE.rglob("*.py")) if p not in (POLICY, NOTEBOOK_RUNTIME)
             for c in simplifier_calls(p)]
    assert calls == [], "simplify through robosolve.core.simplify:\n" + "\n".join(calls)


def test_the_walker_finds_calls(tmp_path):
    f = tmp_path / "x.py"
    f.write_text("import sympy as sp\nfrom sympy import trigsimp\n"
                 "a = sp.simplify(1)\nb = m.applyfunc(sp.nsimplify)\nc = e.factor()\n")
    found = simplifier_calls_in(f)
    assert [c.split(" ", 1)[1] for c in found] == ["import trigsimp", "sp.simplify", "sp.nsimplify",
                                                    ".factor()"]


def simplifier_calls_in(path: Path) -> list[str]:
    global PACKAGE
    saved, PACKAGE = PACKAGE, path.parent.parent
    try:
        return simplifier_calls(path)
    finally:
        PACKAGE = saved


# ------------------------------------------------------------------ the variants

q1, q2, a, b = sp.symbols("q1 q2 a b", real=True)


def test_chain_product_collapses_addition_formulas():
    e = sp.cos(q1) * sp.cos(q2) - sp.sin(q1) * sp.sin(q2)
    assert S.chain_product(e) == sp.cos(q1 + q2)
    # equal to the input everywhere (an independent numeric check)
    assert abs(float((S.chain_product(e * a) - e * a).subs({q1: 0.3, q2: 1.1, a: 2}))) < 1e-15


def test_chain_product_budget_is_an_op_count():
    e = sp.cos(q1) * sp.cos(q2) - sp.sin(q1) * sp.sin(q2)
    assert sp.count_ops(e) > 3
    assert S.chain_product(e, 3) == e                 # over the budget: untouched
    assert S.chain_product(e, 300) == sp.cos(q1 + q2)


def test_exact_geometry_budget():
    e = sp.sin(q1) ** 2 + sp.cos(q1) ** 2
    assert S.exact_geometry(e) == 1
    assert S.exact_geometry(e, 2) == e


def test_determinant_factors_of_a_2r_arm():
    # det J of a planar 2R arm: a*b*sin(q2), once the trig identities are found
    det = a * b * (sp.sin(q1 + q2) * sp.cos(q1) - sp.cos(q1 + q2) * sp.sin(q1))
    facs = S.determinant_factors(sp.expand_trig(det))
    assert sp.sin(q2) in facs


def test_memo_is_one_table():
    S._MEMO.clear()
    S.jacobian_entry(sp.sin(q1) ** 2 + sp.cos(q1) ** 2)
    S.small_trig(sp.sin(q1) ** 2 + sp.cos(q1) ** 2)
    # (jacobian_entry's own factoring is memoised in the same table)
    assert {k[0] for k in S._MEMO} == {"jacobian_entry", "_memo_factor", "small_trig"}


def test_is_zero():
    assert S.is_zero(sp.sin(q1) ** 2 + sp.cos(q1) ** 2 - 1)
    assert not S.is_zero(sp.sin(q1) - sp.cos(q1))
