"""Work-space inputs refused with their line before anything is solved (task_trajectory,
coordinates): each was an internal error, or an answer that blamed the arm's reach."""

from __future__ import annotations

import warnings

import pytest

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text
from robosolve.motion import task_path as tp
from robosolve.run.pipeline import check_inputs

ARM = """\
robosolve: 1
name: arm
parameters: {L1: 1/2, L2: 2/5}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
questions:
  - {type: task_trajectory, coordinates: %s, from: %s, to: %s, max_velocity: 0.5, max_acceleration: 2}
"""


def messages(coordinates, start, end) -> list[str]:
    try:
        check_inputs(load_problem_text(ARM % (coordinates, start, end), "f.yaml"))
    except InputError as exc:
        return [str(i) for i in exc.issues]
    return []


def test_a_coordinate_that_names_no_joint_or_point_is_refused():
    assert messages("[L1, E.y]", "{L1: 0.5, E.y: 0.2}", "{L1: 0.5, E.y: 0.5}") == [
        "f.yaml:11: questions[0].coordinates[0]: 'L1' does not depend on the joints: a coordinate is a "
        "point's coordinate (E.x, E.y, E.z) or an expression of the joints"]


def test_a_coordinate_given_twice_is_refused():
    assert messages("[E.x, E.x]", "{E.x: 0.7}", "{E.x: 0.3}") == [
        "f.yaml:11: questions[0].coordinates[1]: the coordinate 'E.x' is given twice"]


def test_a_coordinate_the_arm_never_moves_is_refused_with_the_model():
    """E.z of an arm moving in the x-y plane is 0 in every configuration (J has a zero row): the path
    was answered as out of the arm's reach."""
    assert messages("[E.z, E.y]", "{E.z: 0, E.y: 0.2}", "{E.z: 0, E.y: 0.5}") == [
        "f.yaml:11: questions[0].coordinates: E.z does not move with the joints (it is 0 in every "
        "configuration): each task coordinate must change as the arm moves"]
    assert messages("[q1 + q2, E.y]", "{q1 + q2: 0.3, E.y: 0.2}", "{q1 + q2: 0.1, E.y: 0.5}") == []


def test_a_circle_centre_beyond_the_floating_point_range_is_a_path_error():
    with warnings.catch_warnings():
        warnings.simplefilter("error")                   # no overflow warning either
        with pytest.raises(tp.PathError, match="too far"):
            tp.circle([0.7, 0.2], [0.3, 0.5], [1e200, 0.35])


def test_a_normal_for_an_arc_in_two_coordinates_says_the_plane_is_given():
    with pytest.raises(tp.PathError, match="a path in 2 coordinates lies in their plane: give no `normal`"):
        tp.circle([0.7, 0.2], [0.3, 0.5], [0.5, 0.35], normal=[0, 0, 1])
    with pytest.raises(tp.PathError, match="the normal is a non-zero vector of the 3 coordinates"):
        tp.circle([1, 0, 0], [0, 1, 0], [0, 0, 0], normal=[0, 0, 0])
