"""A paper's statement asks for what the question grades (papers.md "The paper", 5.): each
graded key in the course's words, whatever the `grade` list — the compliance ellipse when it is
graded, the energy of a run, the selected IK solution with its rule, the velocity matrix W, ...
— and states everything the answer depends on (a run's whole start state, a controller's run
when it follows its reference to the end). The words expected are written here by hand, from
the course's vocabulary, not taken from robosolve."""

from __future__ import annotations

import dataclasses

import pytest

from robosolve.load.loader import load_problem_text
from robosolve.model.chain import RobotModel
from robosolve.papers.keys import placeholder
from robosolve.papers.paper import Say, render_paper, statement
from robosolve.questions.registry import QUESTION_TYPES
from robosolve.render.markdown import Tex
from robosolve.render.chain_names import symbol_latex

EXAM = """\
robosolve: 1
name: every-type
parameters: {L1: 0.5, L2: 0.4, m1: 2, m2: 1, g: 9.81}
joints:
  - {name: theta1, type: revolute, limits: [-pi, pi]}
  - {name: theta2, type: revolute, limits: [-pi, pi]}
frames:
  "1": {parent: "0", pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
  tool: {parent: "2", pose: "Tx(0.1)"}
gravity: [0, -g, 0]
bodies:
  - {name: link1, frame: "1", mass: m1, point: [0, 0, 0]}
  - {name: link2, frame: "2", mass: m2, point: [0, 0, 0]}
questions:
  - {type: position, frame: tool, at: {theta1: 0.1, theta2: 0.2}}
  - {type: velocity_acceleration, at: {theta1: 0.1, theta2: 0.2, theta1_dot: 1, theta2_dot: 2}}
  - {type: jacobian, coordinates: [E.x, E.y], bodies: true, at: {theta1: 0.1, theta2: 0.2}}
  - {type: statics, force: [1, 2], coordinates: [E.x, E.y], at: {theta1: 0.1, theta2: 0.2}}
  - {type: ellipsoids, coordinates: [E.x, E.y], at: {theta1: 0.1, theta2: 0.2}, velocity: [0, 1]}
  - {type: inverse_kinematics, target: {E.x: 0.6, E.y: 0.3}, velocity: {E.x: 0.1, E.y: 0},
     select: {theta1: 0, theta2: 1}}
  - {type: motion_profile, id: move, from: {theta1: 0, theta2: 0}, to: {theta1: 1, theta2: -1},
     max_acceleration: {theta1: 2, theta2: 2}}
  - {type: task_trajectory, id: line, coordinates: [E.x, E.y], from: {E.x: 0.8, E.y: 0.2},
     to: {E.x: 0.5, E.y: 0.4}, max_velocity: 0.5, max_acceleration: 2}
  - {type: equations_of_motion, at: {theta1: 0.1, theta2: 0.2, theta1_dot: 1, theta2_dot: 0,
     theta1_ddot: 0, theta2_ddot: 1}}
  - {type: joint_torques, profile: move}
  - {type: p_control, id: joint-law, profile: move, gains: {theta1: 100, theta2: 100}}
  - {type: p_control, id: task-law, trajectory: line, law: task_pd_gravity,
     gains: {E.x: 1000, E.y: 1000}, gains_d: {E.x: 50, E.y: 50}}
  - {type: forward_dynamics, start: {theta1: 0.3, theta2_dot: -0.5}, actuators: {C2: 1}, duration: 2}
  - {type: displacement, id: screw, axis: [0, 0, 1], angle: pi/2, translation: 0.1}
  - {type: displacement, id: two-poses, from: {theta1: 0, theta2: 0}, to: {theta1: 1, theta2: 0}}
  - {type: orientation, frame: "2", at: {theta1: 0.1, theta2: 0.2}}
  - {type: dof, bodies: 4, joints_1dof: 4}
"""

# key -> words the statement must hold when that key alone is graded (the course's words)
EXPECTED = {
    "position": {"M": "pose ${}^{0}M_{\\mathrm{tool}}$", "position": "coordinates of point E",
                 "chain": "each frame in its parent"},
    "velocity_acceleration": {
        "velocity": "the velocity of point E", "acceleration": "the acceleration of point E",
        "angular_velocity": "angular velocity of frame", "angular_acceleration": "angular acceleration of frame",
        "W": "velocity matrix $W", "H": "acceleration matrix $H", "W_aux": "velocity matrix $W$ of frame tool "
        "expressed in the auxiliary frame", "H_aux": "acceleration matrix $H$ of frame tool expressed in the auxiliary"},
    "jacobian": {"J": "Compute the Jacobian", "det": "determinant", "manipulability": "singular values",
                 "singularities": "singular configurations", "com_jacobians": "centre of mass of each body"},
    "statics": {"Fq": "joint forces"},
    "ellipsoids": {
        **{f"{k}.semi_axes": f"semi-axes of the {k} ellipsoid" for k in ("force", "velocity", "compliance")},
        **{f"{k}.lengths": f"lengths of the {k} ellipsoid" for k in ("force", "velocity", "compliance")},
        **{f"{k}.directions": f"directions of the semi-axes of the {k} ellipsoid"
           for k in ("force", "velocity", "compliance")},
        **{k: f"the {k} ellipsoid" for k in ("force", "velocity", "compliance")},
        "condition_number": "condition number", "A": "the matrix $A = J J^T$", "eigenvalues": "eigenvalues of $A",
        "q_dot": "joint rates giving the velocity"},
    "inverse_kinematics": {"solutions": "every configuration", "selected": "nearest to",
                           "q_dot": "joint rates giving", "closed_form": "closed-form"},
    "motion_profile": {"durations": "each joint alone", "T": "synchronized duration",
                       "accelerations": "accelerations the joints use", "profiles": "piecewise expression",
                       "velocities": "cruise velocity"},
    "task_trajectory": {"T": "duration $T$", "length": "length of the path", "start": "configuration at the start",
                        "end": "configuration at the end", "max_joint_velocity": "largest rate",
                        "max_joint_acceleration": "largest acceleration",
                        "min_singular_value": "smallest singular value"},
    "equations_of_motion": {"mass_matrix": "mass matrix", "velocity_terms": "velocity terms",
                            "gravity_terms": "gravity terms", "generalized_forces": "generalized forces",
                            "equations": "equation of each joint", "kinetic_energy": "kinetic energy",
                            "potential_energy": "potential energy", "actuators": "actuator actions"},
    "joint_torques": {"actuators": "time of that peak", "profiles": "piecewise expression"},
    "p_control": {"max_error": "largest error", "final_error": "signed error at the end",
                  "t_max_error": "time of the largest error", "max_task_error": "largest work-space error"},
    "forward_dynamics": {"final": "value at the end", "max": "largest value", "min": "smallest value",
                         "final_velocity": "rate at the end", "energy": "at the start and at the end",
                         "energy.start": "total energy $T + U$ at $t = 0$",
                         "energy.end": "total energy $T + U$ at the end", "equations": "actuator laws substituted"},
    "displacement": {"u": "unit vector $u$", "alpha": "rotation angle", "h": "translation $h$",
                     "P": "point $P$ of the axis", "Q": "displacement matrix $Q$", "pitch": "pitch",
                     "L": "matrix $L$ of the screw"},
    "orientation": {"zyz": "ZYZ Euler angles", "zyz.solutions": "ZYZ Euler angles",
                    "zyz.singular": "singularity of the ZYZ", "rpy": "roll-pitch-yaw angles",
                    "rpy.solutions": "roll-pitch-yaw angles", "rpy.singular": "singularity of the roll-pitch-yaw",
                    "axis_angle": "axis and the angle", "axis_angle.axis": "unit axis",
                    "axis_angle.angle": "angle of the rotation", "quaternion": "unit quaternion"},
    "dof": {"dof": "degrees of freedom"},
}
# the form of a question a key belongs to, where a type has two (p_control, displacement)
FORM = {("p_control", "max_task_error"): "task-law", ("displacement", "Q"): "screw",
        ("displacement", "L"): "screw", ("displacement", "pitch"): "two-poses"}


@pytest.fixture(scope="module")
def exam(tmp_path_factory):
    problem = load_problem_text(EXAM, str(tmp_path_factory.mktemp("p") / "every-type.yaml"))
    return problem, Say(problem, Tex(symbol_latex(problem)))


def _gradeable(qt) -> list[str]:
    """The keys a question may grade: those an answers file holds (grading's own list)."""
    from robosolve.grading.answers import known_keys

    return [k for k in known_keys(qt) if not qt.key(k).top]


def _question(problem, type_name, key):
    form = FORM.get((type_name, key))
    if form is None and type_name == "displacement":
        form = "two-poses"
    if form is None and type_name == "p_control":
        form = "joint-law"
    return next(q for q in problem.questions if q.type == type_name and (form is None or q.id == form))


def _stated(exam, type_name, key):
    problem, say = exam
    q = dataclasses.replace(_question(problem, type_name, key), grade=(key,))
    return statement(q, say)


def test_the_table_names_every_gradeable_key_of_every_type():
    for name, qt in QUESTION_TYPES.items():
        assert set(EXPECTED[name]) == set(_gradeable(qt)), name


@pytest.mark.parametrize("type_name", sorted(EXPECTED))
def test_the_statement_asks_for_each_graded_key(exam, type_name):
    stated = {}
    for key, words in EXPECTED[type_name].items():
        text = _stated(exam, type_name, key)
        assert words in text, (type_name, key, text)
        stated[key] = text
    # what is not graded is not asked: the statements of two keys graded alone differ
    distinct = {t for k, t in stated.items() if "." not in k or k.partition(".")[0] not in stated}
    plain = [k for k in stated if "." not in k or k.partition(".")[0] not in stated]
    assert len(distinct) == len(plain), type_name


def test_what_is_not_graded_is_not_asked(exam):
    compliance = _stated(exam, "ellipsoids", "compliance.lengths")
    assert "force ellipsoid" not in compliance and "velocity ellipsoid" not in compliance
    assert "condition number" not in compliance
    energy = _stated(exam, "forward_dynamics", "energy.end")
    assert "largest value" not in energy and "value at the end" not in energy
    selected = _stated(exam, "inverse_kinematics", "selected")
    assert "every configuration" not in selected and "Euclidean" in selected
    w = _stated(exam, "velocity_acceleration", "W")
    assert "the velocity of point E" not in w
    q = _stated(exam, "displacement", "pitch")
    assert "unit vector" not in q


def test_a_run_states_its_whole_start_and_a_controller_its_run(exam):
    problem, say = exam
    run = statement(next(q for q in problem.questions if q.type == "forward_dynamics"), say)
    # start: {theta1: 0.3, theta2_dot: -0.5}: the others are 0 (problem-format.md); actuators: C1 is 0
    assert "$\\theta_{1} = 0.3$, $\\theta_{2} = 0$" in run
    assert "$\\dot{\\theta}_{1} = 0$, $\\dot{\\theta}_{2} = -0.5$" in run
    assert "$C_{1} = 0$, $C_{2} = 1$" in run
    control = statement(next(q for q in problem.questions if q.id == "joint-law"), say)
    # no start, no duration: from rest at the profile's start, over the profile's duration
    assert "starting from rest at the start of that motion" in control
    assert "to the end $T$ of that motion" in control


def test_default_statements_ask_for_the_principal_keys(exam):
    problem, say = exam
    by_type = {q.type: q for q in problem.questions}
    assert "determinant" in statement(by_type["jacobian"], say)
    assert "manipulability" not in statement(by_type["jacobian"], say)          # J is 2×2: det J
    ik = statement(by_type["inverse_kinematics"], say)
    assert "every configuration" in ik and "nearest to $\\theta_{1} = 0$, $\\theta_{2} = 1$" in ik
    mechanism = statement(by_type["dof"], say)
    assert "4 joints of 1 degree of freedom" in mechanism
    paper = render_paper(problem, RobotModel(problem))
    assert "`at`" not in paper.split("## Questions")[1]          # no YAML key in a question


def test_the_template_lays_out_lists_and_mappings_of_known_size(exam):
    """chain: one 4×4 pose per frame of the chain (frames 1, 2 and tool: three); energies: one value
    per body and the total; centre-of-mass Jacobians: one 3×2 per body; equations: one per joint."""
    problem, _ = exam
    blank = [[None] * 4 for _ in range(4)]
    cases = {("position", "chain"): [blank, blank, blank],
             ("equations_of_motion", "kinetic_energy"): {"link1": None, "link2": None, "total": None},
             ("jacobian", "com_jacobians"): {b: [[None, None]] * 3 for b in ("link1", "link2")},
             ("equations_of_motion", "equations"): [None, None],
             ("forward_dynamics", "equations"): [None, None]}
    for (type_name, key), expected in cases.items():
        q = _question(problem, type_name, key)
        assert placeholder(QUESTION_TYPES[type_name].key(key), q, problem) == expected, key


def test_a_pose_target_given_by_angles_states_them_and_their_rotation(tmp_path):
    """target: {position, rpy: [0.1, 0.9, 0.3]}: the angles as given, the convention, and R =
    Rz(yaw)·Ry(pitch)·Rx(roll) computed here with numpy (it printed R alone)."""
    import numpy as np

    from test_paper_drawing import STANFORD

    text = STANFORD.replace("questions:\n", "questions:\n  - {type: inverse_kinematics, target: "
                            "{position: [0.4, 0.3, 0.7], rpy: [0.1, 0.9, 0.3]}}\n")
    problem = load_problem_text(text, str(tmp_path / "s.yaml"))
    ik = statement(problem.questions[0], Say(problem, Tex(symbol_latex(problem))))
    assert "roll-pitch-yaw angles $(\\mathrm{roll}, \\mathrm{pitch}, \\mathrm{yaw})$ = ($0.1$, $0.9$, $0.3$)" in ik
    assert "R_z(\\mathrm{yaw})\\,R_y(\\mathrm{pitch})\\,R_x(\\mathrm{roll})" in ik

    def rot(axis, t):
        c, s = np.cos(t), np.sin(t)
        return {"x": np.array([[1, 0, 0], [0, c, -s], [0, s, c]]), "y": np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]),
                "z": np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])}[axis]

    R = rot("z", 0.3) @ rot("y", 0.9) @ rot("x", 0.1)
    assert all(f"{x:.6g}" in ik for x in R.ravel()), R


def test_targets_and_loads_are_stated_exact_and_with_decimals(tmp_path):
    """An IK target's exact value with its decimals, as every configuration (π/6 ≈ 0.523599:
    the paper wrote π/6 alone), its rates likewise; a statics force applied at its point."""
    text = EXAM.replace("target: {E.x: 0.6, E.y: 0.3}, velocity: {E.x: 0.1, E.y: 0}",
                        'target: {E.x: 0.6, "theta1 + theta2": pi/6}, velocity: {E.x: pi/10, E.y: 0}')
    problem = load_problem_text(text, str(tmp_path / "t.yaml"))
    say = Say(problem, Tex(symbol_latex(problem)))
    ik = statement(next(q for q in problem.questions if q.type == "inverse_kinematics"), say)
    assert "$\\theta_{1} + \\theta_{2} = \\frac{\\pi}{6} \\approx 0.523599$" in ik
    assert "$\\dot{E_{x}} = \\frac{\\pi}{10} \\approx 0.314159$" in ik
    statics = statement(next(q for q in problem.questions if q.type == "statics"), say)
    assert "applied at point E (one component per coordinate ($E_{x}$, $E_{y}$))" in statics


def test_a_pose_target_asks_only_for_the_joints_that_move_its_frame():
    """The Panda asked the pose of frame 6: q7 does not move it, so the solutions give q1…q6
    (solvers/ik_pose.py). The paper and the template asked for {q1: …, …, q7: …}, and a student
    who wrote q7 as told had every solution marked wrong. Which joints move frame 6 is found here
    with numpy: the modified DH table multiplied out, each joint perturbed in turn."""
    import numpy as np

    from conftest import PROBLEMS
    from robosolve.load.loader import load_problem
    from robosolve.papers.template import render_template

    problem = load_problem(PROBLEMS / "panda.yaml")
    q = next(q for q in problem.questions if q.type == "inverse_kinematics")
    assert q.frame == "6"
    d1, d3, a4, d5, a6 = 0.333, 0.316, 0.0825, 0.384, 0.088
    rows = [(0, 0, d1), (-np.pi / 2, 0, 0), (np.pi / 2, 0, d3), (np.pi / 2, a4, 0), (-np.pi / 2, -a4, d5),
            (np.pi / 2, 0, 0), (np.pi / 2, a6, 0)]

    def pose6(qs):
        T = np.eye(4)
        for (alpha, a, d), th in list(zip(rows, qs))[:6]:
            ca, sa, ct, st = np.cos(alpha), np.sin(alpha), np.cos(th), np.sin(th)
            T = T @ np.array([[ct, -st, 0, a], [st * ca, ct * ca, -sa, -sa * d], [st * sa, ct * sa, ca, ca * d],
                              [0, 0, 0, 1]])
        return T

    q0 = np.array([0.1, -0.4, 0.2, -1.9, 0.3, 1.5, 0.6])
    moving = [f"q{i + 1}" for i in range(7) if not np.allclose(pose6(q0 + 0.3 * np.eye(7)[i]), pose6(q0))]
    assert moving == ["q1", "q2", "q3", "q4", "q5", "q6"]
    element = "{" + ", ".join(f"{n}: …" for n in moving) + "}"
    ik = statement(q, Say(problem, Tex(symbol_latex(problem))))
    assert "Find every configuration ($q_{1}$, $q_{2}$, $q_{3}$, $q_{4}$, $q_{5}$, $q_{6}$) within" in ik
    assert "$q_{7}$ does not move frame 6" in ik
    template = render_template(problem, "panda.yaml")
    ik_comment = next(line for line in template.splitlines() if line.strip().startswith("# solutions"))
    assert f"a set, a list of {element} in any order" in ik_comment
    assert placeholder(QUESTION_TYPES["inverse_kinematics"].key("selected"), q, problem) == dict.fromkeys(moving)


def test_a_configuration_written_with_parameters_is_stated_with_their_values(tmp_path):
    """`at: {theta1: q1a}` (a variant's drawn configuration), a target `E.x: xt` and a gain `kp`: the
    paper wrote θ₁ = q1a, leaving the student to look the value up, where the report writes
    θ₁ = q1a = π/6 ≈ 0.523599 (papers.md: values exact and with decimals, as in the report)."""
    import math

    text = EXAM.replace("parameters: {L1: 0.5,", "parameters: {q1a: pi/6, xt: 3/5, kp: 2*q1a, L1: 0.5,")
    text = text.replace("{type: position, frame: tool, at: {theta1: 0.1, theta2: 0.2}}",
                        "{type: position, frame: tool, at: {theta1: q1a, theta2: 0.2}}")
    text = text.replace("target: {E.x: 0.6, E.y: 0.3}", "target: {E.x: xt, E.y: 0.3}")
    problem = load_problem_text(text, str(tmp_path / "v.yaml"))
    say = Say(problem, Tex(symbol_latex(problem)))
    position = statement(next(q for q in problem.questions if q.type == "position"), say)
    assert f"$\\theta_{{1}} = \\mathrm{{q1a}} = \\frac{{\\pi}}{{6}} \\approx {math.pi / 6:.6g}$" in position
    ik = statement(next(q for q in problem.questions if q.type == "inverse_kinematics"), say)
    assert "$E_{x} = \\mathrm{xt} = \\frac{3}{5} \\approx 0.6$" in ik
    assert say.per_joint({"theta1": problem.names["kp"]}) == (
        f"$\\theta_{{1}}$: $\\mathrm{{kp}} = \\frac{{\\pi}}{{3}} \\approx {math.pi / 3:.6g}$")
