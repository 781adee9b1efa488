"""What was accepted silently and read otherwise is refused at its line (issue 22): revolute limits
written in degrees, joint values in an inverse_kinematics `at` (the joints are the unknowns)."""

from __future__ import annotations

import pytest

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text

TEXT = """\
robosolve: 1
name: x
parameters: {L: 1}
joints: [{name: q, type: revolute, limits: %s}, {name: d, type: prismatic, limits: [0, 100]}]
frames:
  "1": {pose: "Rz(q) Tx(L) Tx(d)"}
questions:
  - {type: inverse_kinematics, target: {E.x: 0.5, E.y: 0.5}%s}
"""


def messages(limits="[-pi, pi]", at=""):
    with pytest.raises(InputError) as exc:
        load_problem_text(TEXT % (limits, at), "p.yaml")
    return [str(i) for i in exc.value.issues]


def test_revolute_limits_in_degrees():
    assert messages("[-180, 180]") == [
        "p.yaml:4: joints[0].limits: limits [-180, 180] of a revolute joint are beyond one turn "
        "(±2π ≈ ±6.283 rad): angles are radians; if they are degrees, write [deg(-180), deg(180)]"]
    assert messages("[0, 270]")[0].endswith("write [deg(0), deg(270)]")


@pytest.mark.parametrize("limits", ["[-2*pi, 2*pi]", "[-6.2832, 6.2831]", "[deg(-180), deg(180)]", "[-3, 3]",
                                    # more than a turn, its unit written: an ABB IRB 140's axis 6
                                    "[deg(-400), deg(400)]", "[-3*pi, 3*pi]"])
def test_a_full_turn_and_prismatic_lengths_are_fine(limits):
    load_problem_text(TEXT % (limits, ""), "p.yaml")       # d's [0, 100] is a length


def test_joint_values_in_an_ik_at_are_refused():
    assert messages(at=", at: {q: 0.3, L: 2, d_dot: 1}") == [
        "p.yaml:8: questions[0].at.d_dot: an inverse_kinematics question solves for the joints: its `at` "
        "may override parameters only, not 'd_dot' (joint rates come from `velocity`)",
        "p.yaml:8: questions[0].at.q: an inverse_kinematics question solves for the joints: its `at` "
        "may override parameters only, not 'q' (to choose the solution nearest a configuration, "
        "give it in `select`)"]
    load_problem_text(TEXT % ("[-pi, pi]", ", at: {L: 2}"), "p.yaml")   # a parameter: fine
