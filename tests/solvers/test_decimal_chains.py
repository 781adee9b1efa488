"""Singular configurations of arms whose DH tables are written with decimal numbers.

An ABB IRB 140 type arm with every length inline (`d: 0.352`, `alpha: 0.0`, no parameter): det J
was factored over the floats, round-off residues (1e-17·cos²q1·…) stayed in it, and the elbow
factor cos q3 was never split off — the singularities came out as one long equation with those
residues. A KUKA KR 16 type arm in modified DH with parameters and a twist written `alpha: 0.0`:
sympy's Float(0.0) is not 0, the zero twist became a symbol of its own and the rank search ran past
its budget (no singularities at all). Reference: Robotics Toolbox's `jacob0` (det J and its
smallest singular value) for the same arms, and the textbook factors of det J.
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
JOINTS = "joints: [" + ", ".join(f"{{name: q{i}, type: revolute}}" for i in range(1, 7)) + "]\n"

IRB140 = """
robosolve: 1
name: irb140-inline
""" + JOINTS + """
dh:
  convention: standard
  rows:
    - {theta: q1, d: 0.352, a: 0.07, alpha: -pi/2}
    - {theta: q2, d: 0, a: 0.36, alpha: 0.0}
    - {theta: q3, d: 0, a: 0, alpha: -pi/2}
    - {theta: q4, d: 0.38, a: 0, alpha: pi/2}
    - {theta: q5, d: 0, a: 0, alpha: -pi/2}
    - {theta: q6, d: 0.065, a: 0, alpha: 0}
questions:
  - {type: jacobian, geometric: true, at: {q1: 0.3, q2: 0.4, q3: 0.5, q4: 0.6, q5: 0.7, q6: 0.8}}
"""
IRB140_RTB = rtb.DHRobot([rtb.RevoluteDH(d=0.352, a=0.07, alpha=-PI / 2), rtb.RevoluteDH(a=0.36),
                          rtb.RevoluteDH(alpha=-PI / 2), rtb.RevoluteDH(d=0.38, alpha=PI / 2),
                          rtb.RevoluteDH(alpha=-PI / 2), rtb.RevoluteDH(d=0.065)])

KUKA_MDH = """
robosolve: 1
name: kuka-mdh-zero-twist
parameters: {d1: 0.675, a1: 0.26, a2: 0.68, a3: 0.035, d4: 0.67}
""" + JOINTS + """
dh:
  convention: modified
  rows:
    - {alpha: 0.0, a: 0, theta: q1, d: d1}
    - {alpha: -pi/2, a: a1, theta: q2, d: 0}
    - {alpha: 0.0, a: a2, theta: q3, d: 0}
    - {alpha: -pi/2, a: a3, theta: q4, d: d4}
    - {alpha: pi/2, a: 0, theta: q5, d: 0}
    - {alpha: -pi/2, a: 0, theta: q6, d: 0}
questions:
  - {type: jacobian, geometric: true, at: {q1: 0.3, q2: 0.4, q3: 0.5, q4: 0.6, q5: 0.7, q6: 0.8}}
"""
KUKA_VALUES = {"d1": 0.675, "a1": 0.26, "a2": 0.68, "a3": 0.035, "d4": 0.67}
KUKA_RTB = rtb.DHRobot([rtb.RevoluteMDH(d=0.675), rtb.RevoluteMDH(alpha=-PI / 2, a=0.26),
                        rtb.RevoluteMDH(a=0.68), rtb.RevoluteMDH(alpha=-PI / 2, a=0.035, d=0.67),
                        rtb.RevoluteMDH(alpha=PI / 2), rtb.RevoluteMDH(alpha=-PI / 2)])


def _answer(text):
    report = solve_problem(load_problem_text(text))
    a = json.loads(json.dumps(answer_record(report.answers[0], [])))
    assert "error" not in a, a.get("error")
    return a


def _sigma_ratio(robot, q):
    s = np.linalg.svd(robot.jacob0(q), compute_uv=False)
    return s[-1] / s[0]


def _check_conditions(conds, robot, subs, rng):
    """Every condition makes RTB's J lose rank: joint values directly, an equation at a root
    found along q2 (the other joints random)."""
    q2 = sp.Symbol("q2")
    for c in conds:
        checked = 0
        for _ in range(30):
            q = rng.uniform(-PI, PI, 6)
            if isinstance(c, dict):
                for name, value in c.items():
                    q[int(name[1]) - 1] = float(sp.sympify(value).subs(subs))
            else:
                lhs, rhs = (sp.sympify(s) for s in c.split("="))
                f = (lhs - rhs).subs(subs).subs({sp.Symbol(f"q{i + 1}"): q[i] for i in range(6) if i != 1})
                roots = [r for r in np.roots(_trig_poly(f, q2)) if abs(abs(r) - 1) < 1e-9]
                if not roots:          # this q3 leaves the equation no root in q2
                    continue
                q[1] = float(np.angle(roots[0]))
            assert _sigma_ratio(robot, q) < 1e-9, (c, q)
            checked += 1
        assert checked >= 3, c


def _trig_poly(f, q):
    """Coefficients of f(q) = a cos q + b sin q + c as a polynomial in z = e^{iq} (times z)."""
    c0 = complex(f.subs(q, 0))
    a = complex(f.subs(q, 0) - f.subs(q, PI)) / 2
    b = complex(f.subs(q, PI / 2)) - (c0 - a)
    c = c0 - a
    return [a / 2 + b / 2j, c, a / 2 - b / 2j]


def test_an_inline_decimal_table_gives_the_factors_of_det_j_without_round_off():
    a = _answer(IRB140)
    conds = a["symbolic"].get("singularities")
    assert conds is not None, a["notes"]
    assert "e-1" not in json.dumps(conds) and "e-1" not in a["symbolic"]["det"], conds
    values = [c for c in conds if isinstance(c, dict)]
    for joint, value in (("q3", PI / 2), ("q3", -PI / 2), ("q5", 0.0), ("q5", PI)):
        assert any(list(c) == [joint] and abs(float(sp.sympify(c[joint])) - value) < 1e-12 for c in values), conds
    # det J: RTB's, and the textbook product a2·d4·cos q3·(a1 + a2 cos q2 − d4 sin(q2 + q3))·sin q5
    det = sp.lambdify(sp.symbols("q1:7"), sp.sympify(a["symbolic"]["det"]))
    rng = np.random.default_rng(1)
    for _ in range(5):
        q = rng.uniform(-PI, PI, 6)
        ref = np.linalg.det(IRB140_RTB.jacob0(q))
        shoulder = 0.07 + 0.36 * math.cos(q[1]) - 0.38 * math.sin(q[1] + q[2])
        assert det(*q) == pytest.approx(ref, abs=1e-12)
        assert abs(ref) == pytest.approx(0.36 * 0.38 * abs(math.cos(q[2]) * shoulder * math.sin(q[4])), abs=1e-12)
    _check_conditions(conds, IRB140_RTB, {}, rng)


def test_a_zero_twist_written_as_a_float_keeps_the_singularities_of_a_modified_dh_arm():
    a = _answer(KUKA_MDH)
    conds = a["symbolic"].get("singularities")
    assert conds is not None, a["notes"]
    subs = {sp.Symbol(k): v for k, v in KUKA_VALUES.items()}
    det = sp.lambdify(sp.symbols("q1:7"), sp.sympify(a["symbolic"]["det"]).subs(subs))
    rng = np.random.default_rng(2)
    for _ in range(5):
        q = rng.uniform(-PI, PI, 6)
        assert det(*q) == pytest.approx(np.linalg.det(KUKA_RTB.jacob0(q)), abs=1e-12)
    _check_conditions(conds, KUKA_RTB, subs, rng)
    assert sum(isinstance(c, dict) for c in conds) == 4 and len(conds) == 5, conds


UR3_TOOL = """
robosolve: 1
name: ur3-offset-tool
""" + JOINTS + """
dh:
  convention: standard
  rows:
    - {theta: q1, d: 0.1519, a: 0, alpha: pi/2}
    - {theta: q2, d: 0, a: -0.24365, alpha: 0}
    - {theta: q3, d: 0, a: -0.21325, alpha: 0}
    - {theta: q4, d: 0.11235, a: 0, alpha: pi/2}
    - {theta: q5, d: 0.08535, a: 0, alpha: -pi/2}
    - {theta: q6, d: 0.0819, a: 0, alpha: 0}
frames:
  "7": {parent: "6", pose: "Tx(0.02) Ty(-0.03) Tz(0.15) Rx(0.3)"}
questions:
  - {type: jacobian, geometric: true, at: {q1: 0.3, q2: 0.4, q3: 0.5, q4: 0.6, q5: 0.7, q6: 0.8}}
"""


def test_a_tool_off_the_last_axis_keeps_the_singularities_of_the_arm():
    """A UR3 with a tool tip off the last joint's axis: its geometric J's search ran past the budget
    (no singularities, no det J); the det is that of the last joint's frame (a shear of det 1)."""
    from spatialmath import SE3
    from spatialmath.base import transl, trotx

    robot = rtb.DHRobot([rtb.RevoluteDH(d=0.1519, alpha=PI / 2), rtb.RevoluteDH(a=-0.24365),
                         rtb.RevoluteDH(a=-0.21325), rtb.RevoluteDH(d=0.11235, alpha=PI / 2),
                         rtb.RevoluteDH(d=0.08535, alpha=-PI / 2), rtb.RevoluteDH(d=0.0819)],
                        tool=SE3(transl(0.02, -0.03, 0.15) @ trotx(0.3), check=False))
    a = _answer(UR3_TOOL)
    conds = a["symbolic"].get("singularities")
    assert conds is not None, a["notes"]
    J = np.array(a["numeric"]["J"], dtype=float)
    np.testing.assert_allclose(J, robot.jacob0([0.3, 0.4, 0.5, 0.6, 0.7, 0.8]), atol=1e-10)
    det = sp.lambdify(sp.symbols("q1:7"), sp.sympify(a["symbolic"]["det"]))
    rng = np.random.default_rng(3)
    for _ in range(5):
        q = rng.uniform(-PI, PI, 6)
        assert det(*q) == pytest.approx(np.linalg.det(robot.jacob0(q)), abs=1e-12)
    _check_conditions(conds, robot, {}, rng)
    assert sum(isinstance(c, dict) for c in conds) == 4 and len(conds) == 5, conds
