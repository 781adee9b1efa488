"""sympy's LaTeX and str texts are written through robosolve/core/printing.py (`latex`, `sstr`,
the shared printers): sympy orders a sum's terms by generators sorted out of a set, which two
generators with equal sort keys (L1 + L2 and 1.0*L1 + 1.0*L2) leave in the hash seed's order;
core/printing's order is sympy's with those ties broken the same way in every process. AST walk
over the package (the notebook's runtime, which robosolve never runs, is left out)."""

from __future__ import annotations

import ast
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[2] / "robosolve"
POLICY = PACKAGE / "core" / "printing.py"
NOTEBOOK_RUNTIME = PACKAGE / "render" / "notebook_runtime.py"
PRINTERS = {"latex", "sstr", "sstrrepr", "pretty", "pprint", "multiline_latex"}


def sympy_printer_uses(source: str, where: str) -> list[str]:
    """'where:line name' of every sympy printer a module's source calls or imports."""
    tree = ast.parse(source, where)
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("sympy"):
            out |= {(node.lineno, f"import {a.name}") for a in node.names if a.name in PRINTERS}
        elif isinstance(node, ast.Attribute) and node.attr in PRINTERS \
                and isinstance(node.value, ast.Name) and node.value.id in ("sp", "sympy"):
            out.add((node.lineno, f"sp.{node.attr}"))
    return [f"{where}:{line} {name}" for line, name in sorted(out)]


def test_sympy_texts_only_through_core_printing():
    uses = [u for p in sorted(PACKAGE.rglob("*.py")) if p not in (POLICY, NOTEBOOK_RUNTIME)
            for u in sympy_printer_uses(p.read_text(encoding="utf-8"), str(p.relative_to(PACKAGE.parent)))]
    assert uses == [], "print sympy values with robosolve.core.printing:\n" + "\n".join(uses)


def test_the_walk_sees_a_use():
    source = "import sympy as sp\nfrom sympy import sstr\nx = sp.latex(1)\ny = latex(1)\n"
    assert sympy_printer_uses(source, "m.py") == ["m.py:2 import sstr", "m.py:3 sp.latex"]
