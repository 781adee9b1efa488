"""A body that cannot exist is an input error at its line (issue 22): an inertia tensor that is not
positive semi-definite or breaks the triangle inequalities, a pseudo-inertia matrix with a
negative mass or not positive semi-definite. Real bodies (clouds of point masses, built here
from their definition) always pass."""

from __future__ import annotations

import numpy as np
import pytest

from robosolve.errors import InputError
from robosolve.load.loader import load_problem_text
from robosolve.load.physical import inertia_issue, pseudo_inertia_issue

BASE = """\
robosolve: 1
name: b
parameters: {L: 1, m: 2, g: 9.81, J3: 3}
joints: [{name: q, type: revolute}]
frames:
  "1": {pose: "Rz(q) Tx(L)"}
bodies:
  - {name: link, frame: "1", %s}
questions:
  - {type: equations_of_motion}
"""


def messages(body):
    with pytest.raises(InputError) as exc:
        load_problem_text(BASE % body, "p.yaml")
    return [str(i) for i in exc.value.issues]


@pytest.mark.parametrize("body, message", [
    ("mass: m, com: [0, 0, 0], inertia: [[-1, 0, 0], [0, -1, 0], [0, 0, -1]]",
     "p.yaml:8: bodies[0].inertia: the inertia tensor is not positive semi-definite: Ixx, Iyy, Izz < 0; "
     "no body has it"),
    ("mass: m, com: [0, 0, 0], inertia: [[2, 3, 0], [3, 2, 0], [0, 0, 1]]",
     "p.yaml:8: bodies[0].inertia: the inertia tensor is not positive semi-definite (principal "
     "moments -1, 1, 5): I1 < 0; no body has it"),
    ("pseudo_inertia: [[1, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, -1]]",
     "p.yaml:8: bodies[0].pseudo_inertia: the mass (the [4,4] entry) is negative (-1)"),
])
def test_impossible_bodies_are_one_message_at_their_line(body, message):
    assert messages(body) == [message]


def test_pseudo_inertia_not_psd():
    [message] = messages("pseudo_inertia: [[0.1, 0, 0, 1], [0, 0, 0, 0], [0, 0, 0, 0], [1, 0, 0, 2]]")
    assert message.startswith("p.yaml:8: bodies[0].pseudo_inertia: the pseudo-inertia matrix is not "
                              "positive semi-definite (smallest eigenvalue -0.3")


def test_triangle_inequalities():
    assert inertia_issue(np.diag([1.0, 1.0, 3.0])) == (
        "the inertia tensor breaks the triangle inequality Ixx + Iyy ≥ Izz (1 + 1 < 3); no body has it")
    assert inertia_issue([[2, 1, 0], [1, 2, 0], [0, 0, 1]]) == (
        "the inertia tensor breaks the triangle inequality I1 + I2 ≥ I3 (1 + 1 < 3) (principal "
        "moments 1, 1, 3); no body has it")
    # a motor's rotor inertia lumped into a link (the PUMA 560 data): accepted by the loader
    assert inertia_issue(np.diag([0.0, 0.35, 0.0]), triangle=False) is None
    load_problem_text(BASE % "mass: m, com: [0, 0, 0], inertia: [[1, 0, 0], [0, 1, 0], [0, 0, J3]]", "p.yaml")


def test_a_rod_and_unknown_values_are_accepted():
    load_problem_text(BASE % "mass: m, com: [0, 0, 0], inertia: [[0, 0, 0], [0, J3, 0], [0, 0, J3]]", "p.yaml")
    load_problem_text(BASE.replace("J3: 3", "J3: null") % "mass: m, com: [0, 0, 0], "
                      "inertia: [[1, 0, 0], [0, 1, 0], [0, 0, J3]]", "p.yaml")


def _cloud(rng, n=7):
    masses = rng.uniform(0.1, 2.0, n)
    points = rng.normal(size=(n, 3)) * rng.uniform(0.1, 3.0, 3)
    com = masses @ points / masses.sum()
    r = points - com
    inertia = sum(m * (np.dot(p, p) * np.eye(3) - np.outer(p, p)) for m, p in zip(masses, r))
    hom = np.hstack([points, np.ones((n, 1))])
    pseudo = sum(m * np.outer(h, h) for m, h in zip(masses, hom))
    return inertia, pseudo


def test_real_bodies_pass_and_their_impossible_neighbours_fail():
    rng = np.random.default_rng(22)
    for _ in range(50):
        inertia, pseudo = _cloud(rng)
        assert inertia_issue(inertia) is None and pseudo_inertia_issue(pseudo) is None
        k = rng.integers(3)
        w, v = np.linalg.eigh(inertia)
        w[k] = w.sum() - w[k] + 1.0  # one principal moment above the sum of the other two
        broken = v @ np.diag(w) @ v.T
        assert "triangle inequality" in inertia_issue(broken)
        thin = pseudo.copy()         # ∫x² dm below m·x_G²: the Schur complement loses its sign
        thin[0, 0] = thin[0, 3] ** 2 / thin[3, 3] - 0.5
        assert "not positive semi-definite" in pseudo_inertia_issue(thin)
    # a thin rod (one moment 0) and a point mass (all 0) are bodies
    assert inertia_issue(np.diag([0.0, 1.0, 1.0])) is None and inertia_issue(np.zeros((3, 3))) is None


# -- a broken triangle inequality: accepted (a rotor inertia lumped in), but said -------------

LUMPED = "mass: m, com: [0, 0, 0], inertia: [[1, 0, 0], [0, 1, 0], [0, 0, J3]]"   # 1 + 1 < 3


def test_a_broken_triangle_inequality_is_a_warning_with_the_body_and_its_line():
    problem = load_problem_text(BASE % LUMPED, "p.yaml")
    assert [str(w) for w in problem.warnings] == [
        "p.yaml:8: bodies[0].inertia: warning: body 'link': the inertia tensor breaks the triangle "
        "inequality Ixx + Iyy ≥ Izz (1 + 1 < 3); no rigid body alone has it, but a link that carries "
        "its motor's rotor inertia (lumped in, as published data sets do) can; accepted: the tensor "
        "is positive semi-definite, so M(q) keeps its sign"]
    # a physical tensor, or a value still unknown: no warning
    assert load_problem_text(BASE % LUMPED.replace("J3]]", "2]]"), "p.yaml").warnings == []
    assert load_problem_text(BASE.replace("J3: 3", "J3: null") % LUMPED, "p.yaml").warnings == []


def test_the_report_notes_it_under_the_bodies_and_the_paper_does_not():
    from robosolve.papers.paper import render_paper
    from robosolve.run.pipeline import render_files, solve_problem

    from robosolve.model.chain import RobotModel

    problem = load_problem_text(BASE % LUMPED, "p.yaml")
    problem.questions = []          # the data section only
    report = render_files(solve_problem(problem), ("md",))["report.md"].decode()
    bodies = report.index("### Bodies")
    note = report.index("**Note on the data** (line 8 of the problem file). Body link: the inertia "
                        "tensor breaks the triangle inequality Ixx + Iyy ≥ Izz (1 + 1 < 3)")
    assert bodies < note
    assert "Note on the data" not in "\n".join(render_paper(problem, RobotModel(problem)))


def test_the_cli_says_it_on_standard_error_and_exits_0(tmp_path):
    from typer.testing import CliRunner

    from robosolve.cli import app

    (tmp_path / "p.yaml").write_text(BASE % LUMPED, encoding="utf-8")
    r = CliRunner().invoke(app, ["validate", str(tmp_path / "p.yaml")])
    assert r.exit_code == 0
    assert f"{tmp_path / 'p.yaml'}:8: bodies[0].inertia: warning: body 'link': " in r.stderr
    assert "warning" not in r.stdout


def test_the_bundled_puma_data_is_accepted_with_its_two_notes():
    from robosolve.load.loader import load_problem
    from tests.conftest import PROBLEMS

    problem = load_problem(PROBLEMS / "puma560-dynamics.yaml")
    assert [(w.line, w.subject) for w in problem.warnings] == [(38, ("body", "link1")), (42, ("body", "link3"))]
