"""`core.simplify` runs sympy's simplify without importing sympy.physics.units (a quarter of a
second of CPU per process, for a question simplify asks of every expression: does it hold a
physical Quantity?). Checked in a fresh interpreter: the same results as sympy's own simplify,
the units module not imported by it, and the real module still importable afterwards."""

from __future__ import annotations

import subprocess
import sys

SCRIPT = r"""
import sys
import sympy as sp
from robosolve.core import simplify as S

x = sp.Symbol("x")
cases = [sp.sqrt(8) / 2 + sp.Rational(1, 3), (x**2 - 1) / (x - 1), sp.sin(x)**2 + sp.cos(x)**2,
         sp.Rational(5, 2) - sp.sqrt(17) / 2]
ours = [S.full(e) for e in cases] + [S.eigenvalue(cases[-1])]
assert "sympy.physics.units" not in sys.modules, "simplify imported the units"
import sympy.physics.units as units                     # the real module, after our calls
assert hasattr(units, "meter")
theirs = [sp.simplify(e) for e in cases] + [sp.radsimp(sp.simplify(cases[-1]))]
assert ours == theirs, (ours, theirs)
print("ok")
"""


def test_simplify_gives_sympys_results_without_importing_the_units():
    done = subprocess.run([sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "ok"
