"""The ways of writing a rotation that its convention leaves open (problem-format.md: axis-angle
with the angle in [0, π], the quaternion with η ≥ 0) are all right.

By hand (Rodrigues): diag(1, −1, −1) is a half turn about x — the axis ±x with the angle π, the
quaternion (0, ±1, 0, 0), both signs within the convention; the identity has the angle 0 and any
axis (the reference writes null); a quarter turn about z, (0, 0, 1) and π/2, η = cos(π/4) > 0,
has one answer, and its −q or (−u, −α) are wrong.
"""

from __future__ import annotations

import pytest
import yaml

from tests._grading import grade_text, key, reference_of

ROTATIONS = """
robosolve: 1
name: rotations
questions:
  - {type: orientation, id: half, matrix: [[1, 0, 0], [0, -1, 0], [0, 0, -1]]}
  - {type: orientation, id: identity, matrix: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}
  - {type: orientation, id: quarter, matrix: [[0, -1, 0], [1, 0, 0], [0, 0, 1]]}
"""


@pytest.fixture(scope="module")
def ref():
    return reference_of(ROTATIONS)


def given(ref, question, name, value):
    text = yaml.safe_dump({"robosolve-answers": 1, "student": "s1", "answers": {question: {name: value}}})
    return key(grade_text(ref, text), question, name)


@pytest.mark.parametrize("question, name, value", [
    ("half", "axis_angle", {"axis": [1, 0, 0], "angle": "pi"}),
    ("half", "axis_angle", {"axis": [-1, 0, 0], "angle": "pi"}),        # was `negated`
    ("half", "quaternion", [0, 1, 0, 0]),
    ("half", "quaternion", [0, -1, 0, 0]),                              # was `negated`
    ("identity", "axis_angle", {"axis": None, "angle": 0}),             # was invalid: null unread
    ("identity", "axis_angle", {"axis": [None, None, None], "angle": 0}),   # the template's blanks
    ("identity", "axis_angle", {"angle": 0}),
    ("identity", "axis_angle", {"axis": [0, 0, 1], "angle": 0}),
    ("identity", "axis_angle", {"axis": ["sqrt(2)/2", 0, "-sqrt(2)/2"], "angle": 0}),
    ("quarter", "axis_angle", {"axis": [0, 0, 1], "angle": "pi/2"}),
])
def test_every_writing_the_convention_allows_is_right(ref, question, name, value):
    r = given(ref, question, name, value)
    assert r.verdict == "correct", (question, value, r)


@pytest.mark.parametrize("question, name, value", [
    ("quarter", "quaternion", [-0.7071, 0, 0, -0.7071]),               # η < 0: outside the convention
    ("quarter", "axis_angle", {"axis": [0, 0, -1], "angle": "-pi/2"}),  # angle outside [0, π]
    ("quarter", "axis_angle", {"axis": [0, 0, -1], "angle": "pi/2"}),   # the opposite rotation
    ("identity", "axis_angle", {"axis": [0, 0, 2], "angle": 0}),        # not a unit axis
    ("identity", "axis_angle", {"axis": [0, 0, 1], "angle": 0.5}),
    ("half", "axis_angle", {"axis": [0, 1, 0], "angle": "pi"}),
])
def test_other_rotations_stay_wrong(ref, question, name, value):
    r = given(ref, question, name, value)
    assert r.verdict == "incorrect", (question, value, r)


def test_a_missing_euler_solution_is_an_incomplete_set(ref):
    """The quarter turn about z has the RPY solutions (0, 0, π/2) and (π, π, −π/2) (by hand:
    Rz(yaw)·Ry(pitch)·Rx(roll) with roll = pitch = π turns the same); one of them alone is
    `incomplete_set`, as a set key is (it had no diagnosis inside the record)."""
    r = given(ref, "quarter", "rpy", {"solutions": [[0, 0, "pi/2"]], "singular": False})
    assert (r.verdict, r.diagnosis) == ("incorrect", "incomplete_set"), r
    r = given(ref, "quarter", "rpy", {"solutions": [["pi", "pi", "-pi/2"], [0, 0, "pi/2"]], "singular": False})
    assert r.verdict == "correct", r


SINGULAR = """
robosolve: 1
name: singular-euler
questions:
  - {type: orientation, id: flip, matrix: [[1, 0, 0], [0, -1, 0], [0, 0, -1]]}
  - {type: orientation, id: pitch-up, matrix: [[0, 0, 1], [0, 1, 0], [-1, 0, 0]]}
"""


@pytest.fixture(scope="module")
def singular_ref():
    return reference_of(SINGULAR)


# By hand: Rz(φ)·Ry(π)·Rz(ψ) depends on φ − ψ only (diag(1, −1, −1) needs φ − ψ = ±π), and
# Rz(yaw)·Ry(π/2)·Rx(roll) on yaw − roll only (the matrix above needs yaw = roll).
@pytest.mark.parametrize("question, name, value, verdict", [
    ("flip", "zyz", {"solutions": [[0, "pi", "pi"]], "singular": True}, "correct"),
    ("flip", "zyz", {"solutions": [[1.2, "pi", "1.2 - pi"]], "singular": True}, "correct"),
    ("flip", "zyz", {"solutions": [[0, "pi", 0]], "singular": True}, "incorrect"),
    ("pitch-up", "rpy", {"solutions": [[0.5, "pi/2", 0.5]], "singular": True}, "correct"),
    ("pitch-up", "rpy", {"solutions": [[0.5, "pi/2", -0.5]], "singular": True}, "incorrect"),
    ("pitch-up", "rpy", {"solutions": [[0.5, "pi/2", 0.5]], "singular": False}, "incorrect"),
])
def test_any_member_of_a_singular_euler_family_is_right(singular_ref, question, name, value, verdict):
    """At a singularity the reference writes one representative (the last angle 0); any triple of
    the family, flagged singular, is the same rotation."""
    r = given(singular_ref, question, name, value)
    assert r.verdict == verdict, (question, value, r)
