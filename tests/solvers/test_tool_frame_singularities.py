"""The singular configurations of a 6-joint arm's geometric Jacobian taken at a tool frame.

An ABB IRB 120 (datasheet DH table) with a tool Tz(0.15)·Ry(π/6) after the flange: J at the tool
is J at the flange times a shear of determinant 1, so the singular configurations are the arm's
(elbow, wrist, shoulder). det J by decoupling at the wrist centre is short, but the search was
refused because the whole J (the tool's offset in every column) was counted as its input,
above the budget of expression nodes: no singularities at all. The reference is Robotics
Toolbox's `jacob0` (with the tool) and its smallest singular value.
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
SE3 = pytest.importorskip("spatialmath").SE3

PI = math.pi
PARAMS = {"d1": 0.29, "a2": 0.27, "a3": 0.07, "d4": 0.302, "d6": 0.072}

PROBLEM = """
robosolve: 1
name: irb120-tool
parameters: {d1: 0.29, a2: 0.27, a3: 0.07, d4: 0.302, d6: 0.072, dt: 0.15}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
  - {name: q3, type: revolute}
  - {name: q4, type: revolute}
  - {name: q5, type: revolute}
  - {name: q6, type: revolute}
dh:
  convention: standard
  rows:
    - {theta: q1, d: d1, a: 0, alpha: -pi/2}
    - {theta: q2 - pi/2, d: 0, a: a2, alpha: 0}
    - {theta: q3, d: 0, a: a3, alpha: -pi/2}
    - {theta: q4, d: d4, a: 0, alpha: pi/2}
    - {theta: q5, d: 0, a: 0, alpha: -pi/2}
    - {theta: q6, d: d6, a: 0, alpha: 0}
frames:
  tool: {parent: "6", pose: "Tz(dt) Ry(pi/6)"}
questions:
  - {type: jacobian, geometric: true, at: {q1: 0.3, q2: -0.5, q3: 0.8, q4: 1.1, q5: -0.7, q6: 0.4}}
"""

ROBOT = rtb.DHRobot([rtb.RevoluteDH(d=0.29, alpha=-PI / 2), rtb.RevoluteDH(a=0.27, offset=-PI / 2),
                     rtb.RevoluteDH(a=0.07, alpha=-PI / 2), rtb.RevoluteDH(d=0.302, alpha=PI / 2),
                     rtb.RevoluteDH(alpha=-PI / 2), rtb.RevoluteDH(d=0.072)],
                    tool=SE3.Tz(0.15) * SE3.Ry(PI / 6))


def _sigma_ratio(q):
    s = np.linalg.svd(ROBOT.jacob0(q), compute_uv=False)
    return s[-1] / s[0]


def _points_on(condition, rng, count=3):
    """Configurations satisfying a condition: joint values fixed, an equation solved for one of
    its joints by bisection on a sign change (the others random)."""
    q = sp.symbols("q1:7")
    subs = {sp.Symbol(k): v for k, v in PARAMS.items()}
    out = []
    for _ in range(50):
        if len(out) == count:
            break
        x = rng.uniform(-PI, PI, 6)
        if isinstance(condition, dict):
            for name, value in condition.items():
                x[int(name[1]) - 1] = float(sp.sympify(value).subs(subs))
            out.append(x)
            continue
        lhs, rhs = condition.split("=")
        e = (sp.sympify(lhs) - sp.sympify(rhs)).subs(subs)
        k = q.index(sorted(e.free_symbols, key=str)[-1])
        f = sp.lambdify(q, e)
        grid = np.linspace(-PI, PI, 721)
        vals = [f(*np.r_[x[:k], g, x[k + 1:]]) for g in grid]
        for i in range(720):
            if vals[i] * vals[i + 1] < 0:
                lo, hi = grid[i], grid[i + 1]
                for _ in range(80):
                    mid = (lo + hi) / 2
                    if f(*np.r_[x[:k], lo, x[k + 1:]]) * f(*np.r_[x[:k], mid, x[k + 1:]]) <= 0:
                        hi = mid
                    else:
                        lo = mid
                x[k] = (lo + hi) / 2
                out.append(x)
                break
    return out


def test_tool_frame_jacobian_has_the_arms_singular_configurations():
    report = solve_problem(load_problem_text(PROBLEM))
    a = json.loads(json.dumps(answer_record(report.answers[0], [])))
    conds = a["symbolic"].get("singularities")
    assert conds is not None, a["notes"]
    rng = np.random.default_rng(0)
    for c in conds:
        points = _points_on(c, rng)
        assert len(points) == 3, c
        for x in points:
            assert _sigma_ratio(x) < 1e-9, (c, x)
    # every family of the arm is there: wrist (q5 = 0, pi), elbow (q3 from a3, d4), shoulder
    assert {"q5": "0"} in conds and {"q5": "pi"} in conds
    elbow = [c for c in conds if isinstance(c, dict) and set(c) == {"q3"}]
    assert len(elbow) == 2
    assert any(isinstance(c, str) for c in conds)
    # a random configuration is not singular, and the determinant is J's (RTB's with the tool)
    x = [0.3, -0.5, 0.8, 1.1, -0.7, 0.4]
    assert a["numeric"]["det"] == pytest.approx(np.linalg.det(ROBOT.jacob0(x)), rel=1e-9)
