r"""Multi-letter names print upright (issue 22): `ma` is \mathrm{ma}, not the italic product m·a;
names sympy prints well (L1, m_p, theta1) are unchanged. One rule, in render/chain_names.py's LaTeX
names, which every report printer and (through SolveContext.names) every solver uses."""

from __future__ import annotations

from robosolve.load.loader import load_problem_text
from robosolve.render.chain_names import symbol_latex, upright_name
from robosolve.run.pipeline import solve_problem
from robosolve.render.markdown import render_report

TEXT = """\
robosolve: 1
name: ma
parameters: {ma: 2, Lb: 1, Jg2: 3, L1: 1, m_p: 1, g: 9.81}
joints: [{name: q, type: revolute}]
frames:
  "1": {pose: "Rz(q) Tx(Lb + L1)"}
bodies:
  - {name: link, frame: "1", mass: ma + m_p, com: [0, 0, 0], inertia: [[0, 0, 0], [0, Jg2, 0], [0, 0, Jg2]]}
questions:
  - {type: position}
  - {type: equations_of_motion}
"""


def test_the_rule():
    assert upright_name("ma") == r"\mathrm{ma}" and upright_name("Jg2") == r"\mathrm{Jg}_{2}"
    assert [upright_name(n) for n in ("L1", "m_p", "theta1", "g", "alpha2")] == [None] * 5


def test_reports_print_multi_letter_names_upright():
    problem = load_problem_text(TEXT, "p.yaml")
    names = symbol_latex(problem)
    assert set(names.values()) >= {r"\mathrm{ma}", r"\mathrm{Lb}", r"\mathrm{Jg}_{2}"}
    report = render_report(solve_problem(problem), {})
    text = report if isinstance(report, str) else report.decode()
    assert r"T_{x}\left(L_{1} + \mathrm{Lb}\right)" in text
    assert r"\mathrm{ma}" in text and " ma " not in text.replace("# ma", "")
