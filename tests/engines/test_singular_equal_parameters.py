"""Singular families that exist because two parameters are equal (the KUKA LBR iiwa: d3 = d5).

The rank search solves the factors of J's minors for generic parameters; a factor of the
parameters alone (d3 − d5) that the given values make 0 made a minor look non-zero, and the
families it leaves were missed: the iiwa's flange position loses rank at q4 = π, q5 = ±π/2 (the
elbow folded, the wrist centre back on the shoulder), whatever q1, q2, q3, q6, q7; only the
special cases with q2, q3 fixed were reported. Reference: Robotics Toolbox's `jacob0` of the
same DH table (smallest singular value of its position rows).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from robosolve.kinematics.singularities import find_singularities
from robosolve.kinematics.wide_rank import wide_minors
from robosolve.load.loader import load_problem_text
from robosolve.model import RobotModel

rtb = pytest.importorskip("roboticstoolbox")

PI = math.pi
IIWA = """
robosolve: 1
name: iiwa
parameters: {d1: 0.34, d3: 0.4, d5: 0.4, d7: 0.126}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: q3, type: revolute},
         {name: q4, type: revolute}, {name: q5, type: revolute}, {name: q6, type: revolute},
         {name: q7, type: revolute}]
dh:
  convention: standard
  rows:
    - {theta: q1, d: d1, a: 0, alpha: -pi/2}
    - {theta: q2, d: 0, a: 0, alpha: pi/2}
    - {theta: q3, d: d3, a: 0, alpha: pi/2}
    - {theta: q4, d: 0, a: 0, alpha: -pi/2}
    - {theta: q5, d: d5, a: 0, alpha: -pi/2}
    - {theta: q6, d: 0, a: 0, alpha: pi/2}
    - {theta: q7, d: d7, a: 0, alpha: 0}
questions:
  - {type: jacobian}
"""
ROBOT = rtb.DHRobot([rtb.RevoluteDH(d=0.34, alpha=-PI / 2), rtb.RevoluteDH(alpha=PI / 2),
                     rtb.RevoluteDH(d=0.4, alpha=PI / 2), rtb.RevoluteDH(alpha=-PI / 2),
                     rtb.RevoluteDH(d=0.4, alpha=-PI / 2), rtb.RevoluteDH(alpha=PI / 2), rtb.RevoluteDH(d=0.126)])


def _sigma(q):
    s = np.linalg.svd(ROBOT.jacob0(q)[:3], compute_uv=False)
    return s[-1] / s[0]


def test_a_minor_that_the_parameters_values_make_zero_leaves_the_others_to_decide():
    """J's minors sin q1·cos q2 and (d3 − d5)·sin q3 with d3 = d5: J loses rank wherever
    sin q1·cos q2 = 0, whatever q3 (by hand); the search required sin q3 = 0 as well."""
    q1, q2, q3, d3, d5 = sp.symbols("q1 q2 q3 d3 d5")
    kinds = {q1: "revolute", q2: "revolute", q3: "revolute"}
    minors = [sp.sin(q1) * sp.cos(q2), (d3 - d5) * sp.sin(q3)]
    res = find_singularities(None, [q1, q2, q3], kinds, {d3: 0.4, d5: 0.4}, minors=minors)
    got = sorted(str(dict(c.values)) for c in res.conditions)
    want = sorted(str(d) for d in ({q1: 0}, {q1: sp.pi}, {q2: -sp.pi / 2}, {q2: sp.pi / 2}))
    assert got == want
    # with other values the second minor decides too
    res = find_singularities(None, [q1, q2, q3], kinds, {d3: 0.4, d5: 0.3}, minors=minors)
    assert all(q3 in dict(c.values) for c in res.conditions)


@pytest.mark.slow
def test_iiwa_flange_position_loses_rank_where_d3_equals_d5_makes_it():
    problem = load_problem_text(IIWA)
    model = RobotModel(problem)
    q = model.q
    values = {sym: float(v) for sym, v in problem.parameters.items()}
    wide = wide_minors(model, "7", [0, 0, 0], "7", False, 10 ** 6)
    kinds = {j.symbol: j.kind for j in model.joints}
    res = find_singularities(None, q, kinds, values, minors=wide.minors)
    found = [dict(c.values) for c in res.conditions if not c.equations]
    for q5 in (-sp.pi / 2, sp.pi / 2):
        assert {q[3]: sp.pi, q[4]: q5} in found, found
    rng = np.random.default_rng(0)
    for cond in found:
        for _ in range(3):
            x = rng.uniform(-PI, PI, 7)
            for sym, v in cond.items():
                x[q.index(sym)] = float(v.subs(values))
            assert _sigma(x) < 1e-9, (cond, x)
    # and the family is the arm's: q4 = pi with q5 = pi/2 loses rank at random q1, q2, q3, q6, q7
    x = rng.uniform(-PI, PI, 7)
    x[3], x[4] = PI, PI / 2
    assert _sigma(x) < 1e-9
