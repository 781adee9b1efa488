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
