"""Loader: every key of format 1, and bad input reported as FILE:LINE: path: message."""

import pytest
import sympy as sp

from robosolve.errors import InputError
from robosolve.load.loader import load_problem, load_problem_text

GOOD = """\
robosolve: 1
name: t
parameters: {L1: 1/2, L2: L1*2, h: 1, F: ~, g: 9.81}
joints:
  - {name: theta1, type: revolute, limits: [-pi, pi]}
  - {name: d2, type: prismatic}
frames:
  "1": {parent: "0", pose: "Tz(h) Rz(theta1) Tx(L1)"}
  "2": {pose: "Tx(d2)"}
questions:
  - {type: position, at: {theta1: 0, d2: 0.1}}
"""


def issues(text):
    with pytest.raises(InputError) as exc:
        load_problem_text(text, "f.yaml")
    return [str(i) for i in exc.value.issues]


def test_good_problem_parses():
    p = load_problem_text(GOOD, "f.yaml")
    assert [j.name for j in p.joints] == ["theta1", "d2"]
    assert [j.actuator.name for j in p.joints] == ["C1", "F2"]
    params = {s.name: v for s, v in p.parameters.items()}
    assert params["L1"] == sp.Rational(1, 2) and params["F"] is None
    assert p.frames["2"].parent == "1"
    assert p.points["E"].frame == "2" and p.points["E"].implicit
    assert p.questions[0].id == "position"
    assert p.gravity is not None


def test_bundled_problems_validate():
    from conftest import PROBLEMS

    for f in sorted(PROBLEMS.glob("*.yaml")):
        load_problem(f)


def test_unknown_top_key_with_did_you_mean():
    out = issues(GOOD + "jionts: []\n")
    assert out == ["f.yaml:12: jionts: unknown key 'jionts' (did you mean 'joints'?) (expected one of: "
                   "robosolve, name, title, description, parameters, joints, frames, dh, points, gravity, "
                   "bodies, forces, questions, grading, variants, paper)"]


def test_undeclared_name_in_expression_with_did_you_mean():
    out = issues(GOOD.replace("Tx(L1)", "Tx(L11)"))
    assert out == ["f.yaml:8: frames.1.pose: unknown name 'L11' in 'L11' (did you mean 'L1'?)"]


def test_every_problem_reported_at_once():
    text = GOOD.replace("type: prismatic", "type: prismatc").replace("type: position", "type: positon")
    out = issues(text)
    assert "f.yaml:6: joints[1].type: unknown joint type 'prismatc' (did you mean 'prismatic'?) " \
           "(expected revolute or prismatic)" in out
    assert any(o.startswith("f.yaml:11: questions[0].type: unknown question type 'positon' "
                            "(did you mean 'position'?)") for o in out)


def test_yaml_syntax_error_names_its_line():
    out = issues("robosolve: 1\nname: x\nquestions: [\n  {type: position\n")
    assert len(out) == 1 and out[0].startswith("f.yaml:") and "YAML syntax error" in out[0]
    assert int(out[0].split(":")[1]) >= 3


@pytest.mark.parametrize("text,message", [
    ("", "the file is empty"),
    ("- 1\n- 2\n", "the top level must be a mapping"),
    ("robosolve: 2\nname: a\nquestions: [{type: dof, bodies: 2}]\n", "unsupported format version 2"),
    ("robosolve: 1\nname: Bad Name\nquestions: [{type: dof, bodies: 2}]\n", "invalid value 'Bad Name'"),
    ("robosolve: 1\nname: a\n", "missing required key 'questions'"),
])
def test_malformed_top_level(text, message):
    out = issues(text)
    assert any(message in o for o in out), out


def test_alias_bomb_rejected_fast():
    lines = ["a0: &a0 [1, 1, 1, 1, 1, 1, 1, 1, 1, 1]"]
    for i in range(1, 9):
        lines.append(f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 10) + "]")
    out = issues("\n".join(lines) + "\n")
    assert "expands to more than" in out[0]


def test_absurd_nesting_rejected():
    out = issues("a: " + "[" * 5000 + "]" * 5000 + "\n")
    assert "nesting deeper" in out[0]


def test_huge_exponent_is_an_error_not_a_hang():
    out = issues(GOOD.replace("h: 1,", "h: 10**10**10,"))
    assert any("exponent too large" in o for o in out)


def test_code_injection_is_rejected():
    out = issues(GOOD.replace("h: 1,", "h: \"__import__('os').system('true')\","))
    assert any("parameters.h" in o for o in out)


def test_parameter_cycle():
    out = issues(GOOD.replace("L1: 1/2, L2: L1*2", "L1: L2/2, L2: L1*2"))
    assert any("cycle" in o for o in out)


def test_dangling_references():
    text = GOOD.replace('"2": {pose: "Tx(d2)"}', '"2": {parent: "7", pose: "Tx(d2)"}')
    out = issues(text)
    assert any("frames.2.parent: unknown parent frame '7'" in o for o in out)
    text = GOOD + "  - {type: joint_torques}\n"
    out = issues(text)
    assert any("needs a motion_profile question" in o for o in out)
    out = issues(GOOD + "  - {type: position, point: F}\n")
    assert any("questions[1].point: unknown point 'F'" in o for o in out)


def test_duplicate_keys_and_ids():
    out = issues(GOOD.replace("h: 1,", "h: 1, h: 2,"))
    assert any("duplicate key 'h'" in o for o in out)
    out = issues(GOOD + "  - {type: position, id: position}\n")
    assert any("duplicate question id 'position'" in o for o in out)


def test_default_ids_count_only_questions_without_id():
    p = load_problem_text(GOOD + "  - {type: position, id: mine}\n  - {type: position}\n", "f.yaml")
    assert [q.id for q in p.questions] == ["position", "mine", "position-2"]


def test_joint_not_in_any_frame():
    out = issues(GOOD.replace('pose: "Tx(d2)"', 'pose: "Tx(1)"'))
    assert any("joint 'd2' does not appear in any frame" in o for o in out)


def test_dh_table_equals_pose_strings():
    from robosolve.model import RobotModel

    dh = load_problem_text("""\
robosolve: 1
name: dh
parameters: {a1: 1, d1: 2, al: 0.3}
joints: [{name: q1, type: revolute}, {name: q2, type: prismatic}]
dh:
  rows:
    - {theta: q1, d: d1, a: a1, alpha: al}
    - {theta: 0, d: q2, a: 0, alpha: 0}
questions: [{type: position}]
""")
    pose = load_problem_text("""\
robosolve: 1
name: pose
parameters: {a1: 1, d1: 2, al: 0.3}
joints: [{name: q1, type: revolute}, {name: q2, type: prismatic}]
frames:
  "1": {pose: "Rz(q1) Tz(d1) Tx(a1) Rx(al)"}
  "2": {pose: "Tz(q2)"}
questions: [{type: position}]
""")
    m1, m2 = RobotModel(dh).M0("2"), RobotModel(pose).M0("2")
    assert sp.simplify(m1 - m2) == sp.zeros(4, 4)


def test_question_keys_validated_for_every_type():
    text = GOOD + """\
  - {type: jacobian, geometric: yes}
  - {type: ellipsoids}
  - {type: motion_profile, from: {theta1: 0}, to: {theta1: 1, d2: 0}, max_acceleration: {theta1: 1, d2: -1}}
  - {type: dof, bodies: 3, joints_3dof: 1}
  - {type: p_control, gains: {theta1: 1, d2: 1}, law: pid}
"""
    out = issues(text)
    joined = "\n".join(out)
    assert "questions[2]: missing required key 'at'" in joined
    assert "questions[3].from: missing joint(s) d2" in joined
    assert "questions[3].max_acceleration.d2: must be positive" in joined
    assert "questions[4].joints_3dof: 3-DOF joints exist only with space: spatial" in joined
    assert "questions[5].law: unknown value 'pid'" in joined


def test_file_errors(tmp_path):
    with pytest.raises(InputError) as exc:
        load_problem(tmp_path / "missing.yaml")
    assert "cannot read the file" in str(exc.value)
    bad = tmp_path / "bin.yaml"
    bad.write_bytes(b"\xff\xfe\x00")
    with pytest.raises(InputError) as exc:
        load_problem(bad)
    assert "not UTF-8" in str(exc.value)


def test_matrix_frame_must_be_a_rototranslation():
    text = GOOD.replace('"2": {pose: "Tx(d2)"}', '"2": {matrix: [[1, 0, 0, d2], [0, 2, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}')
    out = issues(text)
    assert any("frames.2.matrix: not a rototranslation" in o for o in out)
    ok = GOOD.replace('"2": {pose: "Tx(d2)"}',
                      '"2": {matrix: [[cos(d2), -sin(d2), 0, 0], [sin(d2), cos(d2), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}')
    load_problem_text(ok, "f.yaml")
