"""Singular configurations of an arm whose chain has decimals beside parameters.

A KUKA KR 6 R900 written with parameters except its flange, `d: 0.08` (or a tool Tz(0.12) after
d6): the trig ring's coefficients lie in RR[a1, …, d4]. sympy's factoring failed there (the
jacobian question ended in an internal error, geometric or not), and, that mended, the 3×6
position Jacobian's rank search ran past its budget: nothing cancels exactly in floats. The
decimals are now searched as symbols and written back. Reference: Robotics Toolbox's `jacob0`
(its smallest singular value at configurations on each condition) for the same arm.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import sympy as sp

from robosolve.load.loader import load_problem_text
from robosolve.render.results_json import answer_record
from robosolve.run.pipeline import solve_problem

rtb = pytest.importorskip("roboticstoolbox")

PI = math.pi
VALUES = {"d1": 0.4, "a1": 0.025, "a2": 0.455, "a3": 0.035, "d4": 0.42}

PROBLEM = """
robosolve: 1
name: kr6-decimal-flange
parameters: {d1: 0.4, a1: 0.025, a2: 0.455, a3: 0.035, d4: 0.42}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: q3, type: revolute},
         {name: q4, type: revolute}, {name: q5, type: revolute}, {name: q6, type: revolute}]
dh:
  convention: standard
  rows:
    - {theta: q1, d: d1, a: a1, alpha: -pi/2}
    - {theta: q2, d: 0, a: a2, alpha: 0}
    - {theta: q3 - pi/2, d: 0, a: a3, alpha: -pi/2}
    - {theta: q4, d: d4, a: 0, alpha: pi/2}
    - {theta: q5, d: 0, a: 0, alpha: -pi/2}
    - {theta: q6, d: 0.08, a: 0, alpha: 0}
questions:
  - {type: jacobian, at: {q1: 0.3, q2: -0.5, q3: 0.8, q4: 1.1, q5: -0.7, q6: 0.4}}
"""

ROBOT = rtb.DHRobot([rtb.RevoluteDH(d=0.4, a=0.025, alpha=-PI / 2), rtb.RevoluteDH(a=0.455),
                     rtb.RevoluteDH(a=0.035, alpha=-PI / 2, offset=-PI / 2), rtb.RevoluteDH(d=0.42, alpha=PI / 2),
                     rtb.RevoluteDH(alpha=-PI / 2), rtb.RevoluteDH(d=0.08)])


def test_position_jacobian_singularities_with_a_decimal_flange():
    report = solve_problem(load_problem_text(PROBLEM))
    a = json.loads(json.dumps(answer_record(report.answers[0], [])))
    assert "error" not in a, a.get("error")
    conds = a["symbolic"].get("singularities")
    assert conds is not None, a["notes"]
    assert any("0.08" in (c if isinstance(c, str) else " ".join(c.values())) for c in conds)
    subs = {sp.Symbol(k): v for k, v in VALUES.items()}
    rng = np.random.default_rng(0)
    checked = 0
    for c in conds:
        if not isinstance(c, dict):
            continue
        for _ in range(3):
            q = rng.uniform(-PI, PI, 6)
            for name, value in c.items():
                q[int(name[1]) - 1] = float(sp.sympify(value).subs(subs))
            s = np.linalg.svd(ROBOT.jacob0(q)[:3], compute_uv=False)
            assert s[-1] / s[0] < 1e-9, (c, q)
            checked += 1
    assert checked >= 24
    # the numbers at `at` are the flange point's (RTB)
    J = np.array(a["numeric"]["J"], dtype=float)
    np.testing.assert_allclose(J, ROBOT.jacob0([0.3, -0.5, 0.8, 1.1, -0.7, 0.4])[:3], atol=1e-10)
