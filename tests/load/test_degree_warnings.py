"""An angle given as a plain number that reads like degrees (90, -90, 30) is accepted — robosolve
takes radians — with a warning that says how to write degrees (deg(90)); angles that read like
radians (pi/2, 1.2), lengths and prismatic joints' values give none."""

from __future__ import annotations

import pytest

from robosolve.load.loader import load_problem_text

ARM = """robosolve: 1
name: arm
parameters: {L1: 1/2}
joints: [{name: q1, type: revolute}, {name: d2, type: prismatic}]
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1) {extra}"}
  "2": {dh: {theta: 0, d: d2, a: 0, alpha: {alpha}}}
questions:
  - {type: position, at: {q1: {q1}, d2: {d2}}}
"""


def _warnings(extra="", alpha="0", q1="0.3", d2="30"):
    text = ARM.replace("{extra}", extra).replace("{alpha}", alpha).replace("{q1}", q1).replace("{d2}", d2)
    return [str(w) for w in load_problem_text(text, "p.yaml").warnings]


@pytest.mark.parametrize("kw, where", [
    ({"alpha": "-90"}, "frames.2.dh.alpha"),
    ({"extra": "Rx(90)"}, "frames.1.pose"),
    ({"q1": "30"}, "questions[0].at.q1"),
    ({"q1": "180"}, "questions[0].at.q1"),
])
def test_a_degree_like_angle_is_warned_with_how_to_write_degrees(kw, where):
    warnings = _warnings(**kw)
    assert len(warnings) == 1 and f"{where}: warning:" in warnings[0] and "write deg(" in warnings[0], warnings


@pytest.mark.parametrize("kw", [{"alpha": "pi/2"}, {"alpha": "-1.5708"}, {"extra": "Rx(1.2)"}, {"q1": "6"},
                                {"q1": "deg(30)"}, {"d2": "90"}])
def test_radian_angles_lengths_and_prismatic_values_are_not_warned(kw):
    assert _warnings(**kw) == []


def test_typography_in_a_problem_file_is_named(tmp_path):
    """A problem file is the teacher's: a pasted Unicode minus is an error that says what to type."""
    from robosolve.errors import InputError
    from robosolve.load.loader import load_problem

    p = tmp_path / "p.yaml"
    p.write_text("robosolve: 1\nname: x\nparameters: {L: \"−2\"}\nquestions:\n"
                 "  - {type: dof, bodies: 2, joints_1dof: 1}\n")
    with pytest.raises(InputError) as info:
        load_problem(p)
    assert "p.yaml:3: parameters.L: cannot parse expression '−2' (write '-' for '−')" in str(info.value)


IK = """robosolve: 1
name: ik
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: q3, type: revolute}]
frames:
  "1": {pose: "Rz(q1) Tx(1)"}
  "2": {pose: "Ry(q2) Tx(1)"}
  "3": {pose: "Rx(q3)"}
questions:
  - {type: inverse_kinematics, target: {position: [1, 0, 0], {key}: {angles}}}
"""


@pytest.mark.parametrize("key, angles, meant", [
    ("rpy", "[30, 45, 60]", "[deg(30), deg(45), deg(60)]"),
    ("zyz", "[pi/2, -90, 0.3]", "[pi/2, deg(-90), 0.3]"),
])
def test_degree_like_angles_of_a_pose_target_are_one_warning_with_how_to_write_degrees(key, angles, meant):
    """rpy: [30, 45, 60] was silently read as radians (an orientation of 4.8, 7.2 and 9.5 turns)."""
    text = IK.replace("{key}", key).replace("{angles}", angles)
    warnings = [str(w) for w in load_problem_text(text, "p.yaml").warnings]
    assert len(warnings) == 1 and f"questions[0].target.{key}: warning:" in warnings[0], warnings
    assert f"write {meant}" in warnings[0], warnings


def test_radian_angles_of_a_pose_target_are_not_warned():
    text = IK.replace("{key}", "rpy").replace("{angles}", "[0.2, -1.3, pi]")
    assert load_problem_text(text, "p.yaml").warnings == []
