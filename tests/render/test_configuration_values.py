"""A configuration given through parameters states its values (issue 22): `at: {theta1: q1a}`
reads "θ₁ = q1a = π/6 ≈ 0.523599", exact and in decimals, with the question's own overrides."""

from __future__ import annotations

import sympy as sp

from robosolve.load.loader import load_problem_text
from robosolve.render.configuration import configuration_text

TEXT = """\
robosolve: 1
name: var
parameters: {L1: 1/2, L2: 2/5, q1a: pi/6, q2a: q1a*2, k: null}
joints: [{name: theta1, type: revolute}, {name: theta2, type: revolute}]
frames:
  "1": {pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
questions:
  - {type: jacobian, at: {theta1: q1a, theta2: q2a}}
  - {type: position, at: {theta1: q1a, theta2: k, q1a: pi/4}}
"""


def test_values_through_parameters_are_stated():
    problem = load_problem_text(TEXT, "p.yaml")
    tex = sp.latex
    first = configuration_text(problem.questions[0], problem, tex)
    assert r"\theta_{1} = q1a = \frac{\pi}{6} \approx 0.523599" in first
    assert r"\theta_{2} = q2a = \frac{\pi}{3} \approx 1.0472" in first
    second = configuration_text(problem.questions[1], problem, tex)
    assert r"\theta_{1} = q1a = \frac{\pi}{4} \approx 0.785398" in second   # the override
    assert r"\theta_{2} = k$" in second                                       # null: no value
