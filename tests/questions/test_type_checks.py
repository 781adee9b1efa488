"""The cross-field checks of each question type (`check` in robosolve/questions/<type>.py):
a bad combination of keys gives one FILE:LINE: path: message, a good one none."""

from __future__ import annotations

import pytest

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text
from robosolve.questions.registry import QUESTION_TYPES

HEAD = """\
robosolve: 1
name: t
parameters: {L1: 1, L2: 1, m: 1, g: 9.81}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
points: {E: {frame: "2"}}
bodies: [{name: b, frame: "2", mass: m, point: [0, 0, 0]}]
questions:
"""


def messages(questions: str, head: str = HEAD) -> list[str]:
    """The loader's messages for `questions` (YAML list items, one per line), [] when valid."""
    try:
        load_problem_text(head + questions, "f.yaml")
    except InputError as exc:
        return [str(i) for i in exc.issues]
    return []


Q = 13  # the line of the first question in HEAD + questions


@pytest.mark.parametrize("name", sorted(QUESTION_TYPES))
def test_every_type_module_builds_its_type(name):
    import importlib

    module = importlib.import_module(f"robosolve.questions.{name}")
    assert module.TYPE is QUESTION_TYPES[name]
    assert all(callable(v) for v in module.TYPE.options.values()), "validators are functions"


def test_orientation_matrix_or_frame():
    assert messages("  - {type: orientation, matrix: [[1, 0, 0], [0, 1, 0], [0, 0, 1]], frame: '1'}\n") == [
        f"f.yaml:{Q}: questions[0]: give either matrix or frame (with at), not both"]
    assert messages("  - {type: orientation, matrix: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}\n") == []


def test_jacobian_geometric_without_coordinates():
    assert messages("  - {type: jacobian, geometric: true, coordinates: [E.x, E.y]}\n") == [
        f"f.yaml:{Q}: questions[0].geometric: geometric: true cannot be combined with coordinates"]
    assert messages("  - {type: jacobian, geometric: true}\n") == []


def test_jacobian_grades_only_what_it_computes():
    """A graded key the question never computes would be `no_reference` for every student while
    the paper asks for it: the centre-of-mass Jacobians need bodies: true, det a square J, the
    manipulability a J that is not square."""
    assert messages("  - {type: jacobian, coordinates: [E.x, E.y], grade: [com_jacobians]}\n") == [
        f"f.yaml:{Q}: questions[0].grade[0]: 'com_jacobians' is not an answer of this question: "
        "the centre-of-mass Jacobians are computed only with bodies: true"]
    assert messages("  - {type: jacobian, coordinates: [E.x], grade: [J, det]}\n") == [
        f"f.yaml:{Q}: questions[0].grade[1]: 'det' is not an answer of this question: "
        "J is 1x2: it has no determinant (grade its manipulability)"]
    assert messages("  - {type: jacobian, grade: [manipulability]}\n") == []      # 3x2: not square
    assert messages("  - {type: jacobian, coordinates: [E.x, E.y], grade: [manipulability]}\n") == [
        f"f.yaml:{Q}: questions[0].grade[0]: 'manipulability' is not an answer of this question: "
        "J is 2x2, square: grade its determinant (det)"]
    assert messages("  - {type: jacobian, coordinates: [E.x, E.y], bodies: true, grade: [com_jacobians, det]}\n") == []
    assert messages("  - {type: jacobian, geometric: true, grade: [manipulability]}\n") == []


@pytest.mark.parametrize("question, key, ok", [
    ("{type: inverse_kinematics, target: {E.x: 1, E.y: 1}, grade: [q_dot]}", "q_dot",
     "{type: inverse_kinematics, target: {E.x: 1, E.y: 1}, velocity: {E.x: 0.1, E.y: 0}, grade: [q_dot]}"),
    ("{type: ellipsoids, coordinates: [E.x, E.y], at: {q1: 0.3, q2: 1}, grade: [q_dot]}", "q_dot",
     "{type: ellipsoids, coordinates: [E.x, E.y], at: {q1: 0.3, q2: 1}, velocity: [0, 1], grade: [q_dot]}"),
    ("{type: equations_of_motion, at: {q1: 0.3}, grade: [actuators]}", "actuators",
     "{type: equations_of_motion, at: {q1: 0.3, q2: 0.1}, grade: [actuators]}"),
    ("{type: motion_profile, from: {q1: 0, q2: 0}, to: {q1: 1, q2: 1}, max_acceleration: {q1: 1, q2: 1}, "
     "grade: [velocities]}", "velocities",
     "{type: motion_profile, shape: trapezoidal, from: {q1: 0, q2: 0}, to: {q1: 1, q2: 1}, "
     "max_acceleration: {q1: 1, q2: 1}, max_velocity: {q1: 1, q2: 1}, grade: [velocities]}"),
    ("{type: displacement, from: {q1: 0, q2: 0}, to: {q1: 1, q2: 0}, grade: [L]}", "L",
     "{type: displacement, axis: [0, 0, 1], angle: 1, grade: [L]}"),
])
def test_a_grade_list_names_only_keys_the_question_computes(question, key, ok):
    said = messages(f"  - {question}\n")
    assert len(said) == 1 and said[0].startswith(f"f.yaml:{Q}: questions[0].grade[0]: '{key}' is not an answer"), said
    assert messages(f"  - {ok}\n") == []


def test_statics_load_and_components():
    assert messages("  - {type: statics}\n") == [f"f.yaml:{Q}: questions[0]: expected force, torque or weight: true"]
    assert messages("  - {type: statics, coordinates: [E.x, E.y], force: [1, 2, 3]}\n") == [
        f"f.yaml:{Q}: questions[0].force: expected 2 components (one per coordinate), got 3"]
    assert messages("  - {type: statics, coordinates: [E.x, E.y], torque: [0, 0, 1], force: [1, 2]}\n") == [
        f"f.yaml:{Q}: questions[0].torque: a torque needs the default coordinates (the point's x, y, z)"]
    assert messages("  - {type: statics, weight: true}\n") == []


def test_statics_weight_needs_gravity_and_bodies():
    head = HEAD.replace("m: 1, g: 9.81", "m: 1").replace(HEAD.splitlines(keepends=True)[10], "")
    assert messages("  - {type: statics, weight: true}\n", head) == [
        f"f.yaml:{Q - 1}: questions[0].type: this question uses gravity: declare g in parameters "
        "(the default gravity is [0, 0, -g]) or give gravity",
        f"f.yaml:{Q - 1}: questions[0].weight: weight: true needs bodies (masses)"]


def test_ellipsoids_lengths():
    assert messages("  - {type: ellipsoids, at: {q1: 0, q2: 1}, velocity: [1, 2]}\n") == [
        f"f.yaml:{Q}: questions[0].velocity: expected 3 components (one per coordinate), got 2"]
    assert messages("  - {type: ellipsoids, at: {q1: 0, q2: 1}, joint_compliance: [1]}\n") == [
        f"f.yaml:{Q}: questions[0].joint_compliance: expected 2 values (one per joint), got 1"]


def test_motion_profile_shape_and_limits():
    base = "  - {type: motion_profile, from: {q1: 0, q2: 0}, to: {q1: 1, q2: 1}, "
    assert messages(base + "max_acceleration: {q1: 1, q2: 1}, shape: trapezoidal}\n") == [
        f"f.yaml:{Q}: questions[0]: a trapezoidal profile needs max_velocity"]
    assert messages(base + "max_acceleration: {q1: 1, q2: 1}, max_velocity: {q1: 1, q2: 1}}\n") == [
        f"f.yaml:{Q}: questions[0].max_velocity: max_velocity goes with shape: trapezoidal"]
    assert messages(base + "max_acceleration: {q1: 1, q2: -2}}\n") == [
        f"f.yaml:{Q}: questions[0].max_acceleration.q2: must be positive, got -2"]


def test_p_control_law_and_derivative_gains():
    prof = "  - {type: motion_profile, from: {q1: 0, q2: 0}, to: {q1: 1, q2: 1}, max_acceleration: {q1: 1, q2: 1}}\n"
    assert messages(prof + "  - {type: p_control, gains: {q1: 1, q2: 1}, law: pd}\n") == [
        f"f.yaml:{Q + 1}: questions[1]: law pd needs gains_d"]
    assert messages(prof + "  - {type: p_control, gains: {q1: 1, q2: 1}, gains_d: {q1: 1, q2: 1}}\n") == [
        f"f.yaml:{Q + 1}: questions[1].gains_d: gains_d goes with law pd, pd_gravity or computed_torque"]
    assert messages("  - {type: p_control, gains: {q1: 1, q2: 1}}\n") == [
        f"f.yaml:{Q}: questions[0]: needs a motion_profile question (none in the file)"]


def test_forward_dynamics_at_overrides_parameters_only():
    assert messages("  - {type: forward_dynamics, duration: 1, at: {q1: 0, m: 2}}\n") == [
        f"f.yaml:{Q}: questions[0].at.q1: a forward_dynamics question's `at` may override parameters "
        "only: give the starting value of 'q1' in `start` (joint values and <joint>_dot rates)"]
    assert messages("  - {type: forward_dynamics, duration: 1, at: {m: 2}}\n") == []


def test_forward_dynamics_massless_bodies():
    head = HEAD.replace("mass: m,", "mass: 0,")
    assert messages("  - {type: forward_dynamics, duration: 1}\n", head) == [
        f"f.yaml:{Q}: questions[0].type: every body has mass 0, so the mass matrix M(q) is singular and "
        "the motion cannot be integrated: give the bodies their masses"]
    assert messages("  - {type: equations_of_motion}\n", head) == []


def test_equations_of_motion_at_with_forces_in_time():
    head = HEAD.replace("questions:\n", "forces: [{name: push, frame: \"2\", at: [0, 0, 0], force: [sin(t), 0, 0]}]\nquestions:\n")
    assert messages("  - {type: equations_of_motion, at: {q1: 0, q2: 0}}\n", head) == [
        f"f.yaml:{Q + 1}: questions[0].at: the force push varies with time t, so the numbers at a "
        "configuration would need a time: drop `at` (the symbolic equations keep t), or follow the "
        "motion with a forward_dynamics question"]
    assert messages("  - {type: equations_of_motion}\n", head) == []


def test_displacement_forms():
    assert messages("  - {type: displacement, from: {q1: 0, q2: 0}, axis: [0, 0, 1]}\n") == [
        f"f.yaml:{Q}: questions[0]: give either from/to or a screw (axis, angle, through, translation), "
        "not both (found from, axis)"]
    assert messages("  - {type: displacement, from: {q1: 0, q2: 0}}\n") == [
        f"f.yaml:{Q}: questions[0]: missing required key 'to' (or give a screw: axis and angle)"]
    assert messages("  - {type: displacement, angle: 1}\n") == [
        f"f.yaml:{Q}: questions[0]: angle describe a screw: give its axis too"]
    assert messages("  - {type: displacement, axis: [0, 0, 0], angle: 1}\n") == [
        f"f.yaml:{Q}: questions[0].axis: the zero vector has no direction (give the axis direction, "
        "any non-zero length)"]


def test_dof_spatial_joints():
    assert messages("  - {type: dof, bodies: 3, joints_3dof: 1}\n") == [
        f"f.yaml:{Q}: questions[0].joints_3dof: 3-DOF joints exist only with space: spatial"]
    assert messages("  - {type: dof, bodies: 3, joints_3dof: 1, space: spatial}\n") == []


def test_duration_must_be_positive():
    assert messages("  - {type: forward_dynamics, duration: L1 - 2}\n") == [
        f"f.yaml:{Q}: questions[0].duration: must be positive (seconds), got 'L1 - 2'"]


def test_a_check_called_directly_reports_through_the_loader_checker():
    """`QuestionType.check(ql, path, item, question)` only needs the loader's checker."""
    from types import SimpleNamespace

    errors = []
    chk = SimpleNamespace(error=lambda path, message: errors.append((path, message)))
    ql = SimpleNamespace(chk=chk)
    q = SimpleNamespace(options={"space": "planar"})
    QUESTION_TYPES["dof"].check(ql, ("questions", 2), {"joints_3dof": 1}, q)
    assert errors == [(("questions", 2, "joints_3dof"), "3-DOF joints exist only with space: spatial")]
    errors.clear()
    QUESTION_TYPES["dof"].check(ql, ("questions", 2), {"joints_3dof": 1}, SimpleNamespace(options={"space": "spatial"}))
    assert errors == []


def test_inverse_kinematics_pose_target_of_the_fixed_frame():
    """A pose target of frame 0 (or of a point fixed in it) is an input error with its line; it was
    a solver error (exit 1) after the solve had started."""
    target = "target: {position: [1, 1, 0], R: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}"
    assert messages(f"  - {{type: inverse_kinematics, {target}, frame: '0'}}\n") == [
        f"f.yaml:{Q}: questions[0].frame: frame 0 is the fixed base, which no joint moves: a pose target is "
        "the pose of a moving frame (e.g. frame: '2', the default)"]
    head = HEAD.replace('points: {E: {frame: "2"}}', 'points: {E: {frame: "2"}, B: {frame: "0", at: [1, 0, 0]}}')
    assert messages(f"  - {{type: inverse_kinematics, {target}, point: B}}\n", head) == [
        f"f.yaml:{Q}: questions[0].point: point B is fixed in frame 0, which no joint moves: a pose target's "
        "point is fixed in a moving frame (its orientation is that frame's)"]
    assert messages(f"  - {{type: inverse_kinematics, {target}, frame: '1'}}\n") == []
    assert messages("  - {type: inverse_kinematics, target: {E.x: 1, E.y: 1}, frame: '0'}\n") == []


def test_inverse_kinematics_pose_target_point_fixed_in_another_frame_than_the_question_frame():
    """The spec's point of a pose target is fixed in `frame`, whose orientation the target gives: a
    point of frame 2 with `frame: '1'` was solved as frame 2's pose, `frame` silently dropped."""
    target = "target: {position: [1, 1, 0], R: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}"
    head = HEAD.replace('points: {E: {frame: "2"}}', 'points: {E: {frame: "2"}, P: {frame: "2", at: [0.1, 0, 0]}}')
    assert messages(f"  - {{type: inverse_kinematics, {target}, point: P, frame: '1'}}\n", head) == [
        f"f.yaml:{Q}: questions[0].frame: point P is fixed in frame 2, not in frame 1: a pose target's point "
        "is fixed in the question's frame, whose orientation the target gives (remove `frame`, or give a "
        "point fixed in frame 1)"]
    assert messages(f"  - {{type: inverse_kinematics, {target}, point: P, frame: '2'}}\n", head) == []
    assert messages(f"  - {{type: inverse_kinematics, {target}, point: P, frame: 2}}\n", head) == []
    assert messages("  - {type: inverse_kinematics, target: {P.x: 1, P.y: 1}, point: P, frame: '1'}\n", head) == []


def test_a_misspelt_joint_of_a_configuration_is_one_message_naming_the_joint_not_given():
    """`{q9: 0, q2: 1}` for joints q1, q2: q9 stands for q1, the joint not given (its did-you-mean
    named q2, already given, and a second message said q1 was missing)."""
    assert messages("  - {type: motion_profile, from: {q9: 0, q2: 0}, to: {q1: 1, q2: 1}, "
                    "max_acceleration: {q1: 1, q2: 1}}\n") == [
        f"f.yaml:{Q}: questions[0].from.q9: unknown joint 'q9' (did you mean 'q1'?) (joints: q1, q2)"]
    assert messages("  - {type: motion_profile, from: {q2: 0}, to: {q1: 1, q2: 1}, "
                    "max_acceleration: {q1: 1, q2: 1}}\n") == [
        f"f.yaml:{Q}: questions[0].from: missing joint(s) q1 (give a value for every joint)"]


def test_a_profile_follower_before_its_profile_is_an_input_error():
    """A joint_torques (or p_control) question placed before the motion_profile it follows was
    answered with the error 'the motion profile ... has no answer' (exit 1), though the profile is
    answered further down: questions are solved in file order, so it is an input error that says so."""
    prof = "  - {type: motion_profile, id: later, from: {q1: 0, q2: 0}, to: {q1: 1, q2: 1}, max_acceleration: {q1: 1, q2: 1}}\n"
    assert messages("  - {type: joint_torques, profile: later}\n" + prof) == [
        f"f.yaml:{Q}: questions[0].profile: the motion_profile question 'later' is questions[1], after this "
        "one: put it before (questions are answered in file order)"]
    assert messages("  - {type: p_control, gains: {q1: 1, q2: 1}}\n" + prof) == [
        f"f.yaml:{Q}: questions[0]: needs a motion_profile question before it (the first one, 'later', is "
        "questions[1]: put it before; questions are answered in file order)"]
    assert messages(prof + "  - {type: joint_torques, profile: later}\n") == []


def test_a_trajectory_follower_before_its_trajectory_is_an_input_error():
    """The same for a p_control that follows a task_trajectory given further down: it was answered
    with 'the task trajectory ... has no answer'."""
    traj = ("  - {type: task_trajectory, id: line, coordinates: [E.x, E.y], from: {E.x: 1.5, E.y: 0.2}, "
            "to: {E.x: 1.2, E.y: 0.6}, max_velocity: 0.5, max_acceleration: 2}\n")
    follower = "  - {type: p_control, trajectory: line, gains: {q1: 1, q2: 1}}\n"
    assert messages(traj + follower) == []
    assert messages(follower + traj) == [
        f"f.yaml:{Q}: questions[0].trajectory: the task_trajectory question 'line' is questions[1], after "
        "this one: put it before (questions are answered in file order)"]
