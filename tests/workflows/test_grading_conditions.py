"""Singular conditions written as equations that isolate no joint (`sin(q2) = 0`): read as the
joint values they stand for, the roots in (−π, π] (grading.md "Singularities").

References by hand: the planar 2R arm's det J = L1·L2·sin q2 (zero at q2 = 0, π); a 2R arm whose
point E sits at (a, b) in frame 2, det J = L1·(a·sin q2 + b·cos q2) (zero at q2 = −atan(b/a) and
π − atan(b/a), which depend on the parameters); the polar RRP arm's det, zero at cos q2 = 0
(q2 = ±π/2) and d = 0. None is copied from robosolve's output.
"""

from __future__ import annotations

import math

import pytest

from robosolve.grading.conditions import roots_at
from tests._grading import TWO_R, grade_text, key, reference_of

OFFSET = """
robosolve: 1
name: offset
parameters: {L1: 1/2, a: 2/5, b: 1/10}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2)"}
points:
  E: {frame: "2", at: [a, b, 0]}
questions:
  - {type: jacobian, coordinates: [E.x, E.y], at: {q1: 0.3, q2: 0.7}}
"""


@pytest.fixture(scope="module")
def two_r():
    return reference_of(TWO_R)


@pytest.fixture(scope="module")
def offset():
    return reference_of(OFFSET)


def singularities(ref, value: str):
    text = f"robosolve-answers: 1\nstudent: s1\nanswers:\n  jacobian:\n    singularities: {value}\n"
    return key(grade_text(ref, text), "jacobian", "singularities")


@pytest.mark.parametrize("value", [
    '["sin(q2) = 0"]', '["L1*L2*sin(q2) = 0"]', '["q2 = 0 or q2 = pi"]', '["sin(q2)^2 = 0"]',
    '["tan(q2) = 0"]', '["0 = 2*sin(q2)"]', '["1 - cos(q2)^2 = 0"]',
])
def test_a_condition_equivalent_to_the_set_is_right(two_r, value):
    r = singularities(two_r, value)
    assert r.verdict == "correct", (value, r)


@pytest.mark.parametrize("value, diagnosis", [
    ('["cos(q2) = 0"]', ""),                          # ±π/2: none of the two
    ('["1 - cos(q2) = 0"]', "incomplete_set"),        # 0 only
    ('["cos(q2) = 1"]', "incomplete_set"),
    ('["sin(2*q2) = 0"]', "extra_in_set"),            # 0, ±π/2, π
    ('["sin(q2) = 0", {q2: 0}]', "extra_in_set"),     # 0 twice
    ('["cos(q2) = 2"]', ""),                          # no root: one wrong condition
])
def test_a_condition_with_other_roots_is_wrong(two_r, value, diagnosis):
    r = singularities(two_r, value)
    assert (r.verdict, r.diagnosis) == ("incorrect", diagnosis), (value, r)


def test_roots_that_depend_on_the_parameters(offset):
    """det J = L1·(a·sin q2 + b·cos q2): the equation is right for every a, b; its roots are
    compared with the reference's values at the problem's values, however written."""
    for value in ('["a*sin(q2) + b*cos(q2) = 0"]', '["tan(q2) = -b/a"]', '["L1*(a*sin(q2) + b*cos(q2)) = 0"]',
                  f'[{{q2: {-math.atan(0.25):.4f}}}, {{q2: {math.pi - math.atan(0.25):.4f}}}]',
                  '[{q2: "-atan(b/a)"}, {q2: "pi - atan(b/a)"}]'):
        r = singularities(offset, value)
        assert r.verdict == "correct", (value, r)
    for value in ('["a*sin(q2) - b*cos(q2) = 0"]', '["a*cos(q2) + b*sin(q2) = 0"]'):
        assert singularities(offset, value).verdict == "incorrect", value


def test_two_joints_each_with_its_equation():
    """The planar 3R arm's position Jacobian (x, y of the tip) loses rank with sin q2 = sin q3 = 0
    (all links aligned or folded): four conditions {q2, q3} ∈ {0, π}²."""
    ref = reference_of("""
        robosolve: 1
        name: three-r
        parameters: {L1: 1, L2: 1, L3: 1}
        joints:
          - {name: q1, type: revolute}
          - {name: q2, type: revolute}
          - {name: q3, type: revolute}
        frames:
          "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
          "2": {pose: "Rz(q2) Tx(L2)"}
          "3": {pose: "Rz(q3) Tx(L3)"}
        questions:
          - {type: jacobian, coordinates: [E.x, E.y], at: {q1: 0.1, q2: 0.2, q3: 0.3}, grade: [singularities]}
        """)
    assert singularities(ref, '["sin(q2) = 0, sin(q3) = 0"]').verdict == "correct"
    assert singularities(ref, '["sin(q2) = 0, q3 = 0", "sin(q2) = 0, q3 = pi"]').verdict == "correct"
    r = singularities(ref, '["sin(q2) = 0, q3 = 0"]')
    assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set")


def test_roots_found_by_the_grid_and_refined():
    """The roots of equations with simple, double and close roots and with poles, against their
    closed forms."""
    import numpy as np
    import sympy as sp

    q, c = sp.symbols("q c", real=True)
    cases = [
        (sp.sin(q), [0, math.pi]),
        (sp.sin(q) ** 2, [0, math.pi]),                       # double roots: no sign change
        (sp.tan(q), [0, math.pi]),                            # the poles at ±π/2 are no roots
        (sp.cos(q) - c, [-math.acos(0.3), math.acos(0.3)]),   # c = 0.3 from a column
        ((sp.cos(q) - 0.3) ** 2, [-math.acos(0.3), math.acos(0.3)]),
        (sp.sin(q - 0.001) * sp.sin(q + 0.001), [-0.001, 0.001, math.pi - 0.001, -math.pi + 0.001]),
        (sp.cos(q) + 2, []),
    ]
    for residual, expected in cases:
        found = roots_at(residual, q, {c: np.array([0.3])}, 1)[0]
        want = sorted(math.remainder(x, 2 * math.pi) if abs(math.remainder(x, 2 * math.pi)) < math.pi - 1e-9
                      else math.pi for x in expected)
        assert len(found) == len(want), (residual, found)
        assert np.allclose(sorted(found), want, atol=1e-7), (residual, found, want)
    assert roots_at(sp.sin(q) ** 2 + sp.cos(q) ** 2 - 1, q, {}, 1) is None     # true for every q


def test_a_product_is_the_conditions_of_its_factors(two_r):
    """det J = 0 written whole: a product is zero when a factor is. sin(q1 + q2)·cos q1 −
    cos(q1 + q2)·sin q1 = sin q2 (by the addition formula): right; cos q1·sin q2 = 0 adds
    q1 = ±π/2, which are not singular: extra_in_set."""
    r = singularities(two_r, '["L1*L2*(sin(q1 + q2)*cos(q1) - cos(q1 + q2)*sin(q1)) = 0"]')
    assert r.verdict == "correct", r
    r = singularities(two_r, '["cos(q1)*sin(q2) = 0"]')
    assert (r.verdict, r.diagnosis) == ("incorrect", "extra_in_set"), r


ANTHROPOMORPHIC = """
robosolve: 1
name: anthropomorphic
parameters: {L1: 1/2, L2: 2/5, L3: 3/10}
joints:
  - {name: theta1, type: revolute}
  - {name: theta2, type: revolute}
  - {name: theta3, type: revolute}
frames:
  "1": {parent: "0", pose: "Tz(L1) Rz(theta1) Rx(pi/2)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
  "3": {pose: "Rz(theta3) Tx(L3)"}
questions:
  - {type: jacobian, at: {theta1: 0.3, theta2: 0.6, theta3: -0.9}, grade: [singularities]}
"""

# a planar arm turning theta and sliding d along its link: E = (d·cos θ, d·sin θ), det J = d
RP = """
robosolve: 1
name: rp
joints:
  - {name: theta, type: revolute}
  - {name: d, type: prismatic}
frames:
  "1": {parent: "0", pose: "Rz(theta)"}
  "2": {pose: "Tx(d)"}
questions:
  - {type: jacobian, coordinates: [E.x, E.y], at: {theta: 0.3, d: 0.5}, grade: [singularities]}
"""


def test_the_textbook_determinant_of_the_anthropomorphic_arm():
    """det J = L2·L3·sin θ3·(L2·cos θ2 + L3·cos(θ2 + θ3)) (Siciliano et al., the anthropomorphic
    arm): the elbow (θ3 = 0, π) and the wrist point on the base axis (the second factor, an
    equation in two joints). Written whole, it is those conditions; without its last factor,
    incomplete."""
    ref = reference_of(ANTHROPOMORPHIC)
    det = "L2*L3*sin(theta3)*(L2*cos(theta2) + L3*cos(theta2 + theta3)) = 0"
    assert singularities(ref, f'["{det}"]').verdict == "correct"
    r = singularities(ref, '["L2*L3*sin(theta3) = 0"]')
    assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set"), r


def test_a_prismatic_joint_given_its_value_by_any_linear_equation():
    ref = reference_of(RP)
    for value in ('[{d: 0}]', '["d = 0"]', '["2*d = 0"]', '["d^2 = 0"]'):
        r = singularities(ref, value)
        assert r.verdict == "correct", (value, r)
    assert singularities(ref, '["d = 1"]').verdict == "incorrect"
