"""An ellipsoids `velocity` is a list in the order of `coordinates` or, as an inverse_kinematics
`velocity` is written, a mapping coordinate: value (issue 22); a wrong key names the order."""

from __future__ import annotations

import pytest

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text

TEXT = """\
robosolve: 1
name: ell
parameters: {L1: 1/2, L2: 2/5}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames:
  "1": {pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: ellipsoids, coordinates: [E.x, E.y], at: {q1: pi/6, q2: pi/3}, velocity: %s}
"""


def test_a_mapping_is_put_in_the_order_of_the_coordinates():
    as_list = load_problem_text(TEXT % "[0.1, 0]", "p.yaml").questions[0].options["velocity"]
    as_map = load_problem_text(TEXT % "{E.y: 0, E.x: 0.1}", "p.yaml").questions[0].options["velocity"]
    assert list(as_map) == list(as_list)


@pytest.mark.parametrize("value, message", [
    ("{E.y: 0, E.z: 0.1}", "the keys must be the coordinates E.x, E.y (not E.z); or give a list in that order"),
    ("{E.x: 0.1}", "the keys must be the coordinates E.x, E.y; or give a list in that order"),
    ("3", "expected a list of values in the order of `coordinates` (default: the point's x, y, z), "
          "or a mapping coordinate: value such as {E.x: 0.1, E.y: 0}"),
])
def test_a_wrong_layout_names_the_expected_order(value, message):
    with pytest.raises(InputError) as exc:
        load_problem_text(TEXT % value, "p.yaml")
    assert [str(i) for i in exc.value.issues] == [f"p.yaml:9: questions[0].velocity: {message}"]
