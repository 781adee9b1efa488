"""What a mistaken inverse-kinematics target is told: an empty target says what it lacks, a joint
where a number belongs is named a joint (not an unknown parameter)."""
import pytest

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text

TEXT = """\
robosolve: 1
name: x
parameters: {L: 1}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames:
  "1": {pose: "Rz(q1) Tx(L)"}
  "2": {pose: "Rz(q2) Tx(L)"}
questions:
  - {type: inverse_kinematics, target: %s}
"""


def messages(target):
    with pytest.raises(InputError) as exc:
        load_problem_text(TEXT % target, "p.yaml")
    return [str(i) for i in exc.value.issues]


def test_an_empty_target_says_what_it_lacks():
    [message] = messages("{}")
    assert message.startswith("p.yaml:9: questions[0].target: an empty target: give the coordinates")
    assert "{pose: M}" in message


@pytest.mark.parametrize("target, path", [("{E.x: q2, E.y: 0.5}", "target.E.x"),
                                          ("{E.x: 1, E.y: 2*q1}", "target.E.y")])
def test_a_joint_where_a_value_belongs_is_named_a_joint(target, path):
    [message] = messages(target)
    assert message.startswith(f"p.yaml:9: questions[0].{path}: '")
    assert "is a joint: this value is a number or an expression of the parameters" in message


def test_an_unknown_name_is_still_unknown():
    [message] = messages("{E.x: Ll, E.y: 0.5}")
    assert "unknown parameter 'Ll'" in message and "did you mean 'L'?" in message
