"""Papers (papers.md "The paper"): no answer in any paper of a bundled problem, the teacher's
`text`, `paper: {at}`, the command's files and its refusals (exit 2, nothing written)."""

from __future__ import annotations

import json
import re

import pytest
import sympy as sp
from typer.testing import CliRunner

from conftest import PROBLEMS, ROOT
from robosolve.cli import app
from robosolve.load.loader import load_problem
from robosolve.model.chain import RobotModel
from robosolve.papers.paper import render_paper

runner = CliRunner()
FILES = sorted(PROBLEMS.glob("*.yaml"))
NUMBER = re.compile(r"(?<![\w.])-?\d+\.\d+(?:e-?\d+)?(?![\w.])")


def _leaves(tree):
    if isinstance(tree, dict):
        for v in tree.values():
            yield from _leaves(v)
    elif isinstance(tree, list):
        for v in tree:
            yield from _leaves(v)
    else:
        yield tree


def _forms(x: float) -> set[str]:
    return {f"{x:.6g}", f"{x:.4g}", f"{x:.3g}"}


def _inputs(problem, text: str) -> set[str]:
    """Numbers a paper may show because they are given: written in the file, or the decimals of
    a given exact value (parameters, `at`, limits, options)."""
    allowed = set(NUMBER.findall(text))
    values = list(problem.parameters.values()) + [v for q in problem.questions for v in q.at.values()]
    values += [x for j in problem.joints if j.limits for x in j.limits]
    values += [x for q in problem.questions for x in _leaves(q.options) if isinstance(x, sp.Basic)]
    for q in problem.questions:        # a pose target's R and p: the given orientation, as a matrix
        target = q.options.get("target")
        if hasattr(target, "R") and hasattr(target, "p"):
            values += list(target.R) + list(target.p)
    subs = {s: v for s, v in problem.parameters.items() if v is not None}
    for v in values:
        try:
            x = float(sp.sympify(v).xreplace(subs))
        except (TypeError, ValueError, AttributeError):
            continue
        allowed |= _forms(x) | _forms(-x)
    return allowed


@pytest.mark.parametrize("file", FILES, ids=[f.stem for f in FILES])
def test_no_answer_in_the_paper(file):
    problem = load_problem(file)
    paper = render_paper(problem, RobotModel(problem) if problem.has_robot else None, "s1", None)
    results = json.loads((ROOT / "tests" / "golden" / problem.name / "results.json").read_text())["answers"]
    computed: set[str] = set()
    symbolic: set[str] = set()
    for r in results.values():
        for x in _leaves(r.get("numeric", {})):
            if isinstance(x, float) and abs(x) > 1e-9 and not float(x).is_integer():
                computed |= _forms(x)
        for s in _leaves(r.get("symbolic", {})):
            if isinstance(s, str) and len(s) > 8 and any(op in s for op in "*+/("):
                symbolic.add(s)
    shown = set(NUMBER.findall(paper))
    leaked = (shown & computed) - _inputs(problem, file.read_text())
    assert not leaked, leaked
    assert not [s for s in symbolic if s in paper]


def test_paper_header_and_order():
    problem = load_problem(PROBLEMS / "exam-2r-full.yaml")
    paper = render_paper(problem, RobotModel(problem), "Jo Smith", "exam-2r-full-007")
    head = paper.split("## Data")[0]
    assert "**Student:** Jo Smith" in head and "`exam-2r-full-007`" in head and "11 marks" in head
    assert "![The robot at its reference configuration](figures/robot.png)" in head
    numbers = [int(m) for m in re.findall(r"^### (\d+)\. ", paper, re.M)]
    assert numbers == list(range(1, len(problem.questions) + 1))
    assert "`solutions`" in paper and "(1 mark)" in paper
    blank = render_paper(problem, RobotModel(problem))
    assert "**Name:** ____" in blank


ARM = """\
robosolve: 1
name: arm
parameters: {L1: 1/2, L2: 2/5}
joints:
  - {name: theta1, type: revolute, limits: [-pi, pi]}
  - {name: theta2, type: revolute, limits: [-deg(150), deg(150)]}
frames:
  "1": {pose: "Rz(theta1) Tx(L1)"}
  "2": {pose: "Rz(theta2) Tx(L2)"}
questions:
  - {type: position, at: {theta1: pi/6, theta2: pi/2}, marks: 2,
     text: "With L1 = {L1} and {{braces}}, find M {at}."}
  - {type: jacobian, id: jac, coordinates: [E.x, E.y], at: {theta1: 0, theta2: pi/3}}
"""


def test_text_placeholders(write_problem, tmp_path):
    path = write_problem(ARM)
    out = tmp_path / "paper"
    r = runner.invoke(app, ["paper", str(path), "--out", str(out)])
    assert r.exit_code == 0, r.output
    paper = (out / "paper.md").read_text()
    assert "With L1 = $\\frac{1}{2}$ and {braces}, find M at $\\theta_{1} = \\frac{\\pi}{6}" in paper
    assert "(2 marks)" in paper and "**Total:** 3 marks" in paper
    assert (out / "figures" / "robot.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (out / ".robosolve").exists()
    template = (out / "answers.yaml").read_text()
    assert 'problem: "../p.yaml"' in template
    assert "jac:" in template and "J: [[~, ~], [~, ~]]" in template and "det: ~" in template


@pytest.mark.parametrize("edit, message", [
    (("text: \"With L1 = {L1}", "text: \"With L1 = {L11}"), "questions[0].text: unknown name '{L11}' in text (did you mean 'L1'?"),
    (("{{braces}}", "{braces"), "questions[0].text: a lone brace"),
    (("questions:", "paper: {at: {theta2: pi}}\nquestions:"), "paper.at.theta2: 'pi' is outside the limits of theta2"),
    (("questions:", "paper: {at: {theta3: 0}}\nquestions:"), "paper.at.theta3: unknown joint 'theta3' (did you mean 'theta2'?"),
])
def test_bad_input_nothing_written(write_problem, tmp_path, edit, message):
    path = write_problem(ARM.replace(*edit))
    out = tmp_path / "paper"
    r = runner.invoke(app, ["paper", str(path), "--out", str(out)])
    assert r.exit_code == 2
    assert re.search(r"p\.yaml:\d+: " + re.escape(message), r.output), r.output
    assert not out.exists()


def test_bad_format_and_input_folder(write_problem, tmp_path):
    path = write_problem(ARM)
    r = runner.invoke(app, ["paper", str(path), "--out", str(tmp_path / "x"), "--format", "htm"])
    assert r.exit_code == 2 and "did you mean 'html'" in r.output
    assert not (tmp_path / "x").exists()
    r = runner.invoke(app, ["paper", str(path), "--out", str(path.parent)])
    assert r.exit_code == 2
    assert path.exists()


def test_paper_at_is_the_drawing_configuration(write_problem):
    from robosolve.papers.drawing import reference_configuration

    p = load_problem(write_problem(ARM.replace("questions:", "paper: {at: {theta2: pi/4}}\nquestions:")))
    theta1, theta2 = (j.symbol for j in p.joints)
    assert reference_configuration(p) == {theta1: 0, theta2: sp.pi / 4}
    p = load_problem(write_problem(ARM, "q.yaml"))
    assert reference_configuration(p) == {theta1: sp.pi / 6, theta2: sp.pi / 2}


def test_paper_html_boxes_shaped_like_the_answers(write_problem, tmp_path):
    path = write_problem(ARM)
    out = tmp_path / "paper"
    r = runner.invoke(app, ["paper", str(path), "--out", str(out), "--format", "md,html", "--student", "s1"])
    assert r.exit_code == 0, r.output
    page = (out / "paper.html").read_text()
    assert "<script" not in page and "http://" not in page.replace("http://www.w3.org", "")
    assert 'src="data:image/png;base64,' in page and "<math" in page
    assert "break-inside: avoid" in page and "@page" in page and "RSBOX" not in page
    # a question's heading and its "What to give" stay with what follows them when printed
    assert page.count('<p class="rs-give"><strong>What to give</strong>') == 2
    assert "h2, h3, .rs-give { break-after: avoid;" in page
    grids = re.findall(r'<table class="rs-grid">(.*?)</table>', page, re.S)
    cells = [g.count("<td></td>") for g in grids]
    assert cells == [16, 3, 4]            # M 4×4, position [x, y, z], J 2×2
    assert page.count('<div class="rs-line"></div>') == 1 + 4     # det: a line; singularities: a set


def test_every_type_writes_its_statement():
    from robosolve.questions.registry import QUESTION_TYPES

    assert all(t.statement is not None for t in QUESTION_TYPES.values())
    problem = load_problem(PROBLEMS / "exam-2r-full.yaml")
    paper = render_paper(problem, RobotModel(problem))
    assert "maximum accelerations $\\theta_{1}$: $2$ rad/s², $\\theta_{2}$: $3$ rad/s²" in paper
    assert "$E_{y} = 0.6$, $E_{z} = 0.3$" in paper and "question 8" in paper
    assert "$F_s = $" in paper and "Gravity points along −z₀" in paper


WORK_SPACE = """robosolve: 1
name: ws
parameters: {L1: 0.5, L2: 0.4, m1: 2, m2: 1, g: 9.81}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}, {name: q3, type: revolute}]
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
  "3": {pose: "Rz(q3) Tx(0.3)"}
gravity: [0, -g, 0]
bodies:
  - {name: b1, frame: "1", mass: m1, point: [0, 0, 0]}
  - {name: b2, frame: "2", mass: m2, point: [0, 0, 0]}
  - {name: b3, frame: "3", mass: 1, point: [0, 0, 0]}
questions:
  - {type: task_trajectory, id: arc, coordinates: [E.x, E.y, "q1 + q2 + q3"],
     from: {E.x: 0.8, E.y: 0.2, "q1 + q2 + q3": 0.3}, to: {E.x: 0.4, E.y: 0.6, "q1 + q2 + q3": 0.3},
     path: {circle: {center: [0.4, 0.2, 0.3]}}, duration: 2, shape: quintic}
  - {type: p_control, id: ct, trajectory: arc, law: task_computed_torque, duration: 2.5,
     gains: {E.x: 400, E.y: 400, "q1 + q2 + q3": 300}, gains_d: {E.x: 30, E.y: 30, "q1 + q2 + q3": 20},
     grade: [max_error, final_error, max_task_error]}
  - {type: p_control, id: pd, trajectory: arc, law: task_pd_gravity, start: {q1: 0.1, q2: 0.2, q3: 0.3},
     gains: {E.x: 2000, E.y: 2000, "q1 + q2 + q3": 50}, gains_d: {E.x: 100, E.y: 100, "q1 + q2 + q3": 5}}
"""


def _statements(paper: str) -> list[str]:
    questions = paper.split("## Questions", 1)[1]
    return [s.split("**What to give**")[0] for s in questions.split("\n### ")[1:]]


def test_the_work_space_statements_state_the_path_scheme_gains_units_and_what_to_give(tmp_path):
    from robosolve.load.loader import load_problem_text

    problem = load_problem_text(WORK_SPACE, str(tmp_path / "ws.yaml"))
    paper = render_paper(problem, RobotModel(problem))
    traj, ct, pd = _statements(paper)
    assert "along the arc of the circle of centre" in traj and "quintic timing law" in traj and "$2$ s" in traj
    assert "the length of the path (" not in traj         # positions and an angle: no one unit
    for s in (ct, pd):                                     # the path restated, its coordinates
        assert "along the arc of the circle" in s and "$E_{x} = 0.8$" in s and "$E_{y} = 0.6$" in s
    assert "resolved-acceleration computed torque" in ct and "J^{-1}" in ct
    assert "$400$ s⁻²" in ct and "$30$ s⁻¹" in ct and "for $2.5$ s" in ct
    assert "transposed Jacobian" in pd and "gravity compensation" in pd
    assert "$2000$ N/m" in pd and "$100$ N·s/m" in pd and "$50$ N·m/rad" in pd and "$5$ N·m·s/rad" in pd
    assert "to the end $T$ of the path" in pd and "$\\theta_{1} = 0.1$" not in pd
    assert "m for a position, rad for an angle" in pd and "(rad)" not in pd
    assert "largest work-space error" in ct                # graded: asked


@pytest.mark.parametrize("start", [None, "{q1: 0.1, q2: 0.6, q3: 0.9}"])
def test_a_redundant_path_s_statement_names_the_start_the_answer_uses(tmp_path, start):
    """Two coordinates, three joints: `from` has a family of configurations, and the answer's start is
    the one nearest q = 0 (or nearest `start`) — docs/questions/task_trajectory.md, checked there
    against scipy's SLSQP. The paper said "the configuration Newton's minimum-norm steps reach from
    every joint at 0" (or "Newton's method from this configuration"): on this arm 0.11 rad (1e-2 rad)
    from the answer's, so a student who followed it got every joint value wrong."""
    from robosolve.load.loader import load_problem_text

    text = WORK_SPACE.split("questions:")[0] + (
        "questions:\n  - {type: task_trajectory, id: red, coordinates: [E.x, E.y], from: {E.x: 0.8, E.y: 0.2},\n"
        "     to: {E.x: 0.2, E.y: 0.7}, duration: 2" + ("" if start is None else f", start: {start}") + "}\n")
    problem = load_problem_text(text, str(tmp_path / "ws.yaml"))
    (traj,) = _statements(render_paper(problem, RobotModel(problem)))
    assert "Newton" not in traj
    assert ("nearest $q = 0$" in traj) if start is None else ("nearest $q_{1} = 0.1$" in traj)


def test_the_template_lays_out_a_control_law_s_errors_per_joint_or_per_coordinate(tmp_path):
    from robosolve.load.loader import load_problem_text
    from robosolve.papers.template import render_template

    problem = load_problem_text(WORK_SPACE, str(tmp_path / "ws.yaml"))
    template = render_template(problem, "ws.yaml")
    assert 'max_error: {E.x: ~, E.y: ~, "q1 + q2 + q3": ~}' in template
    assert 'max_task_error: {E.x: ~, E.y: ~, "q1 + q2 + q3": ~}' in template
    exam = render_template(load_problem(PROBLEMS / "exam-2r-full.yaml"), "exam.yaml")
    assert "max_error: {theta1: ~, theta2: ~}" in exam


def test_decimal_marks_are_written_as_the_teacher_wrote_them(write_problem, tmp_path):
    """marks: 1.5 is "1.5 marks" (it was "1.50000000000000 marks"), the total 1.5 + 1 = 2.5."""
    from robosolve.papers.template import render_template

    problem = load_problem(write_problem(ARM.replace("marks: 2,", "marks: 1.5,")))
    paper = render_paper(problem, RobotModel(problem))
    assert "### 1. Position (direct kinematics) (1.5 marks)" in paper
    assert "**Total:** 2.5 marks" in paper
    assert "# 1. Position (direct kinematics), 1.5 marks" in render_template(problem, "p.yaml")
    assert "0000" not in paper


def test_the_data_a_student_needs_is_on_the_paper(tmp_path):
    """A frame given as a matrix is shown (it said only "explicit matrix"), DH(…) and MDH(…) of the
    frames table are defined (problem-format.md: Rz(θ) Tz(d) Tx(a) Rx(α), Rx(α) Tx(a) Rz(θ) Tz(d)),
    and a problem without a robot has no data section (it listed a point E of frame 0)."""
    from robosolve.load.loader import load_problem_text

    arm = load_problem_text(ARM.replace('"2": {pose: "Rz(theta2) Tx(L2)"}',
                                        '"2": {matrix: [[cos(theta2), -sin(theta2), 0, L2], [sin(theta2), '
                                        'cos(theta2), 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}'), str(tmp_path / "a.yaml"))
    paper = render_paper(arm, RobotModel(arm))
    row = next(line for line in paper.splitlines() if line.startswith("| 2 | 1 |"))
    assert "\\cos{\\left(\\theta_{2} \\right)}" in row and "L_{2}" in row and "explicit matrix" not in row
    assert "DH(" not in paper
    mdh = load_problem_text("""robosolve: 1
name: m
parameters: {a1: 0.3, d1: 0.2}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
dh:
  convention: modified
  rows:
    - {alpha: 0, a: 0, theta: q1, d: d1}
    - {alpha: pi/2, a: a1, theta: q2, d: 0}
frames:
  tool: {parent: "2", dh: {theta: 0, d: 0.1, a: 0, alpha: 0}}
questions:
  - {type: position, at: {q1: 0, q2: 0}}
""", str(tmp_path / "m.yaml"))
    conventions = next(p for p in render_paper(mdh, RobotModel(mdh)).split("\n\n") if p.startswith("**Conventions"))
    assert "$MDH(\\alpha, a, \\theta, d) = R_x(\\alpha)\\,T_x(a)\\,R_z(\\theta)\\,T_z(d)$" in conventions
    assert "$DH(\\theta, d, a, \\alpha) = R_z(\\theta)\\,T_z(d)\\,T_x(a)\\,R_x(\\alpha)$" in conventions
    screw = load_problem_text("""robosolve: 1
name: s
questions:
  - {type: displacement, axis: [0, 0, 1], angle: pi/2}
  - {type: dof, bodies: 4, joints_1dof: 4}
""", str(tmp_path / "s.yaml"))
    bare = render_paper(screw, None)
    assert "## Data" not in bare and "Points" not in bare and "origin of the last frame" not in bare


def test_the_student_id_is_shown_as_written(write_problem, tmp_path):
    """A roster id is not Markdown: '*Jo* _Smith_ $x$' was shown as emphasis and a formula."""
    path = write_problem(ARM)
    out = tmp_path / "paper"
    r = runner.invoke(app, ["paper", str(path), "--out", str(out), "--format", "md,html",
                            "--student", "*Jo* _Smith_ $x$ <b>"])
    assert r.exit_code == 0, r.output
    page = (out / "paper.html").read_text()
    assert "<strong>Student:</strong> *Jo* _Smith_ $x$ &lt;b&gt;" in page


def test_the_data_table_names_questions_by_their_numbers(write_problem):
    """A parameter a question overrides: "0.3 in question 2" and no file key (`at`, an id) on the
    paper; the report keeps the ids."""
    from robosolve.render.markdown import Tex, render_data

    problem = load_problem(write_problem(ARM.replace("at: {theta1: 0, theta2: pi/3}",
                                                     "at: {theta1: 0, theta2: pi/3, L2: 0.3}")))
    paper = render_paper(problem, RobotModel(problem))
    data = paper.split("## Data")[1].split("## Questions")[0]
    assert "| $L_{2}$ | $\\frac{2}{5}$ | $0.3$ in question 2 |" in data
    assert "`" not in data
    report = "\n".join(render_data(problem, RobotModel(problem), Tex({})))
    assert "in `jac`" in report and "changed by a question's `at`" in report


def test_at_placeholder_after_a_written_at_and_without_a_configuration(write_problem, tmp_path):
    """'at {at}' read 'at at θ₁ = …' (and 'at at the data's values' without `at`): one 'at'; a
    question without a configuration is about any (its answers symbolic in the joints)."""
    text = ARM.replace('text: "With L1 = {L1} and {{braces}}, find M {at}."', 'text: "Find M at {at}."').replace(
        "  - {type: jacobian, id: jac,", "  - {type: jacobian, id: jac, text: 'Find J {at}.',").replace(
        "coordinates: [E.x, E.y], at: {theta1: 0, theta2: pi/3}}", "coordinates: [E.x, E.y]}")
    out = tmp_path / "paper"
    r = runner.invoke(app, ["paper", str(write_problem(text)), "--out", str(out)])
    assert r.exit_code == 0, r.output
    paper = (out / "paper.md").read_text()
    assert "Find M at $\\theta_{1} = \\frac{\\pi}{6}" in paper and "at at" not in paper
    assert "Find J at any configuration (the joint variables as symbols)." in paper


def test_a_wide_data_table_spans_both_columns():
    """The exam's forces table (name, frame, point, force, torque, components: six columns) sat in
    one of the two data columns and ran past the page's margin: printed by Chromium on Letter,
    its last heading 'components' lost its final letter. Wide tables span both columns; the
    joints' (five columns) stay in theirs."""
    from robosolve.papers.workflow import paper_files

    problem = load_problem(PROBLEMS / "exam-2r-full.yaml")
    page = paper_files(problem, "exam-2r-full.yaml", formats=("md", "html"))["paper.html"].decode()
    data = page[page.index('<div class="rs-data">'):page.index("<h2>Questions</h2>")]
    wide = re.findall(r'<div class="rs-wide">(<h3>[^<]*</h3>)', data)
    assert wide == ["<h3>External forces</h3>"]
    assert ".rs-data > .rs-wide { column-span: all; }" in page.replace("h2:first-child, ", "")
