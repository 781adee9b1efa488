"""Why a pose is not reached, in words and numbers (results.json's `reason`, the report's step).

The reasons of the decoupled arm were joined with `str()` of the arm's reason, a `Text` of prose
and `Num`s: results.json and the report showed "Text('distance …', Num(value=2.29, …))". A wrist
centre reached only outside a prismatic joint's limits was said to be "beyond the reach". The
references: the arm's reach (distance from the shoulder to the wrist centre against the sum of the
links, computed here) and the Stanford arm's d3 = |wrist centre − shoulder| (closed form).
"""

from __future__ import annotations

import json
import math
import re

import numpy as np

from robosolve.load.loader import load_problem_text
from robosolve.render.results_json import answer_record
from robosolve.run.pipeline import solve_problem

KR6 = """
robosolve: 1
name: kr6-far
parameters: {d1: 0.4, a1: 0.025, a2: 0.455, a3: 0.035, d4: 0.42, d6: 0.08}
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
    - {theta: q6, d: d6, a: 0, alpha: 0}
questions:
  - {type: inverse_kinematics, target: {position: [2.0, 0.5, 1.5], rpy: [0.2, 0.3, 0.4]}}
"""

STANFORD = """
robosolve: 1
name: stanford-far
parameters: {d1: 0.412, d2: 0.154, d6: 0.263}
joints: [{name: th1, type: revolute}, {name: th2, type: revolute}, {name: d3, type: prismatic, limits: [0.2, 1.2]},
         {name: th4, type: revolute}, {name: th5, type: revolute}, {name: th6, type: revolute}]
dh:
  convention: standard
  rows:
    - {theta: th1, d: d1, a: 0, alpha: -pi/2}
    - {theta: th2, d: d2, a: 0, alpha: pi/2}
    - {theta: 0, d: d3, a: 0, alpha: 0}
    - {theta: th4, d: 0, a: 0, alpha: -pi/2}
    - {theta: th5, d: 0, a: 0, alpha: pi/2}
    - {theta: th6, d: d6, a: 0, alpha: 0}
questions:
  - {type: inverse_kinematics, target: {position: [2.0, 0.5, 1.5], rpy: [0.2, 0.3, 0.4]}}
"""


def _answer(text):
    """results.json's record, and the words of the report's "Unreachable target" step."""
    report = solve_problem(load_problem_text(text))
    record = json.loads(json.dumps(answer_record(report.answers[0], [])))
    step = next(s for s in report.answers[0].steps if s.title == "Unreachable target")
    return record, step.text.words() if hasattr(step.text, "words") else step.text


def _rpy(r, p, y):
    cr, sr, cp, sp_, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    Rz = np.array([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    Ry = np.array([[cp, 0, sp_], [0, 1, 0], [-sp_, 0, cp]])
    Rx = np.array([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return Rz @ Ry @ Rx


def _numbers(text):
    return [float(x) for x in re.findall(r"-?\d+\.\d+", text)]


def test_wrist_centre_beyond_the_reach_is_said_with_its_numbers():
    a, step = _answer(KR6)
    assert "Text(" not in step and "Num(" not in step, step
    assert a["unreachable"] is True and a["numeric"]["solutions"] == []
    reason = a["reason"]
    assert "Text(" not in reason and "Num(" not in reason, reason
    assert reason.startswith("the wrist centre is beyond the reach of the arm")
    # the distance from the shoulder's circle to the wrist centre, against the arm's reach
    w = np.array([2.0, 0.5, 1.5]) - 0.08 * _rpy(0.2, 0.3, 0.4)[:, 2]
    # (on either branch of q1: the shoulder offset a1 towards the wrist centre or away from it)
    dists = [math.hypot(w[2] - 0.4, math.hypot(w[0], w[1]) - s * 0.025) for s in (1, -1)]
    reach = 0.455 + math.hypot(0.035, 0.42)
    assert min(dists) > reach
    got = _numbers(reason)
    assert any(abs(x - round(d, 3)) < 2e-3 for x in got for d in dists), (dists, reason)
    assert any(abs(x - round(reach, 4)) < 2e-4 for x in got)


def test_wrist_centre_reached_only_outside_the_limits_says_so():
    a, _ = _answer(STANFORD)
    reason = a["reason"]
    assert a["unreachable"] is True and "Text(" not in reason and "Num(" not in reason, reason
    assert reason.startswith("the wrist centre is reached only with the arm's joints outside their limits")
    # d3 = the distance from the shoulder (on the axis of joint 2, d2 off joint 1's axis) to W
    w = np.array([2.0, 0.5, 1.5]) - 0.263 * _rpy(0.2, 0.3, 0.4)[:, 2]
    d3 = math.sqrt(w[0] ** 2 + w[1] ** 2 - 0.154 ** 2 + (w[2] - 0.412) ** 2)
    assert any(abs(x - round(d3, 3)) < 2e-3 for x in _numbers(reason)), (d3, reason)


UR3_INLINE = """
robosolve: 1
name: ur3-far
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: q3, type: revolute},
         {name: q4, type: revolute}, {name: q5, type: revolute}, {name: q6, type: revolute}]
dh:
  convention: standard
  rows:
    - {theta: q1, d: 0.1519, a: 0, alpha: pi/2}
    - {theta: q2, d: 0, a: -0.24365, alpha: 0}
    - {theta: q3, d: 0, a: -0.21325, alpha: 0}
    - {theta: q4, d: 0.11235, a: 0, alpha: pi/2}
    - {theta: q5, d: 0.08535, a: 0, alpha: -pi/2}
    - {theta: q6, d: 0.0819, a: 0, alpha: 0}
questions:
  - {type: inverse_kinematics, target: {position: [1.0, 0.5, 0.8], rpy: [0.2, 0.3, 0.4]}}
"""


def test_a_reach_of_decimals_is_said_once_as_a_number():
    """An arm written in decimals: the reach bound has no symbol, and its sympy string was written
    before its value ("> 0.456900000000000 = 0.4569"). Reference: |a2| + |a3| of the UR3."""
    a, step = _answer(UR3_INLINE)
    assert a["unreachable"] is True
    reach = 0.24365 + 0.21325
    assert f"> {reach:.4g}:" in a["reason"], a["reason"]
    assert "> #:" in step, step           # the report's words: each number a `#`
    for text in (a["reason"], step):
        assert not re.search(r"\d\.\d{9,}", text), text


def test_a_pose_far_beyond_the_reach_is_unreachable_without_numpy_warnings():
    """A position of 1e150 m: JᵀJ of the numeric search overflowed and numpy's RuntimeWarnings
    reached stderr under the answer. Reference: |p| is beyond any sum of the UR3's lengths."""
    import warnings

    text = UR3_INLINE.replace("[1.0, 0.5, 0.8]", "[1e150, 0.5, 0.8]")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        report = solve_problem(load_problem_text(text))
    a = json.loads(json.dumps(answer_record(report.answers[0], [])))
    assert a["unreachable"] is True and a["numeric"]["solutions"] == []
    assert not [w for w in caught if issubclass(w.category, RuntimeWarning)], [str(w.message) for w in caught]


def test_the_report_writes_the_reach_distance_as_a_formula_and_names_the_joints():
    """The report's step writes the planar arm's distance as a formula ($\\sqrt{b_x^2 + b_y^2}$:
    it was sympy's plain `sqrt(b_x**2 + b_y**2)`); results.json keeps the plain text; both name the
    arm's own joints (th1…th6 here: the words said q1, q5, q6 of any arm)."""
    text = UR3_INLINE.replace("name: q", "name: th").replace("theta: q", "theta: th")
    a, step = _answer(text)
    assert a["unreachable"] is True
    assert "sqrt(b_x**2 + b_y**2)" in a["reason"] and "$" not in a["reason"]
    assert "$\\sqrt{b_{x}^{2} + b_{y}^{2}}$" in step and "sqrt(" not in step, step
    for words in (a["reason"], step):
        assert "th1, th5, th6" in words and "th2, th3, th4" in words and "q1" not in words, words
    assert f"> {0.24365 + 0.21325:.4g}:" in a["reason"]       # |a2| + |a3|
