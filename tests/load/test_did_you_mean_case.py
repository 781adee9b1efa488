"""A did-you-mean prefers the name that differs only by case: difflib's similarity is case-blind
about 'l1' against 'L1' and 'm1' (0.5 both) and its `get_close_matches` gives a tie to the last
string, so `l1` among the parameters L1, m1 was said to mean 'm1'. Every user of the shared
`did_you_mean` is probed once: varied parameters, expressions, joints, frames, question types,
answers keys."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from robosolve.errors import InputError
from robosolve.grading.answers import read_answers_text, resolve_answers
from robosolve.load.expressions import closest
from robosolve.load.loader import load_problem_text

ROOT = Path(__file__).resolve().parents[2]

ARM = """
robosolve: 1
name: case
parameters: {L1: 1/2, m1: 3}
joints:
  - {name: Q1, type: revolute}
  - {name: r1, type: revolute}
frames:
  "A1": {parent: "0", pose: "Rz(Q1) Tx(L1)"}
  "b1": {parent: "A1", pose: "Rz(r1) Tx(L1)"}
questions:
  - {type: position, at: {Q1: 0, r1: 0}}
"""


def _issues(text: str) -> list[str]:
    with pytest.raises(InputError) as exc:
        load_problem_text(textwrap.dedent(text).lstrip("\n"), "p.yaml")
    return [str(i) for i in exc.value.issues]


def test_the_case_only_difference_wins_a_tie():
    assert closest("l1", ["L1", "m1"]) == "L1"
    assert closest("l1", ["m1", "L1", "k1", "l2"]) == "L1"
    assert closest("POSITION", ["position", "orientation"]) == "position"
    assert closest("x9", ["L1", "m1"]) is None


def test_a_true_tie_goes_to_the_last_name_in_order_as_difflib_gives_it():
    assert closest("theta3", ["theta2", "theta1"]) == "theta2"
    assert closest("c", ["cb", "ab", "ca"]) == "cb"


def test_a_varied_parameter_written_in_lower_case():
    text = (ROOT / "problems" / "planar-2r-rods.yaml").read_text(encoding="utf-8")
    text += "variants:\n  parameters:\n    l1: {choices: [0.3, 0.5]}\n"
    out = _issues(text)
    assert len(out) == 1 and "undeclared parameter 'l1' (did you mean 'L1'?)" in out[0], out


def test_a_parameter_in_an_expression():
    out = _issues(ARM.replace("Rz(r1) Tx(L1)", "Rz(r1) Tx(l1)"))
    assert len(out) == 1 and "did you mean 'L1'?" in out[0], out


def test_a_joint_in_at():
    out = _issues(ARM.replace("at: {Q1: 0, r1: 0}", "at: {q1: 0, r1: 0}"))
    assert len(out) == 1 and "did you mean 'Q1'?" in out[0], out


def test_a_frame_parent():
    out = _issues(ARM.replace('parent: "A1"', 'parent: "a1"'))
    assert len(out) == 1 and "did you mean 'A1'?" in out[0], out


def test_a_question_type_in_capitals():
    out = _issues(ARM.replace("type: position", "type: POSITION"))
    assert len(out) == 1 and "did you mean 'position'?" in out[0], out


def test_an_answers_key():
    problem = load_problem_text(textwrap.dedent(ARM).lstrip("\n"), "p.yaml")
    sub = read_answers_text("robosolve-answers: 1\nanswers:\n  position:\n    m: 1\n", "a.yaml")
    with pytest.raises(InputError) as exc:
        resolve_answers(sub, problem)
    out = [str(i) for i in exc.value.issues]
    assert len(out) == 1 and "unknown answer key 'm' (did you mean 'M'?)" in out[0], out


@pytest.mark.parametrize("a, b, slips", [
    ("ojints", "joints", 1), ("ojints", "points", 2), ("kitten", "sitting", 3), ("abc", "abc", 0),
    ("ab", "ba", 1), ("ca", "abc", 3),     # (counted by hand: the alignment edits no letter twice)
])
def test_slips_count_a_swap_of_neighbours_as_one(a, b, slips):
    from robosolve.load.expressions import _slips
    assert _slips(a, b) == slips


def test_two_letters_swapped_mean_the_key_they_spell():
    """difflib rates 'ojints' alike against joints and points (5 of 6 letters matched, 0.833 each)
    and a tie went to points: the file was then read as having no joints, and every frame, `at`
    and question said so. Two neighbours swapped are one slip from joints, two from points."""
    text = (ROOT / "problems" / "pendulum-runs.yaml").read_text().replace("\njoints:", "\nojints:")
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "p.yaml")
    issues = [str(i) for i in exc.value.issues]
    assert len(issues) == 1 and "unknown key 'ojints' (did you mean 'joints'?)" in issues[0], issues
    assert closest("fraems", ["frames", "forces", "bodies"]) == "frames"
