"""Names from a problem file reach the figures as text shown as written, never as mathtext
(issue 22): a frame, force or title holding `$…$` (`$\\frac{$` stopped the robot figure with
"could not be drawn (ValueError …)" and the paper with a traceback) is drawn, escaped."""

from __future__ import annotations

import pytest

from robosolve.core.prose import name_plot
from robosolve.load.loader import load_problem_text
from robosolve.render.drawing import InlineFigures
from robosolve.run.pipeline import render_files, solve_problem

FRAME = "$\\\\frac{$"            # YAML-escaped: $\frac{$
FORCE = '\\"\\"\\"; open(\\"Z\\") # $x$'
TITLE = "Costs $5 and $\\\\alpha$ {"

PROBLEM = f"""\
robosolve: 1
name: names
title: "{TITLE}"
parameters: {{L: 1, F: 2}}
joints:
  - {{name: q1, type: revolute}}
  - {{name: q2, type: revolute}}
frames:
  "{FRAME}": {{parent: "0", pose: "Rz(q1) Tx(L)"}}
  "2": {{parent: "{FRAME}", pose: "Rz(q2) Tx(L)"}}
forces:
  - {{name: "{FORCE}", frame: "2", at: [0, 0, 0], force: [0, -F, 0]}}
questions:
  - {{type: position, at: {{q1: 0.3, q2: 0.4}}}}
  - {{type: displacement, frame: "{FRAME}", from: {{q1: 0, q2: 0}}, to: {{q1: 0.5, q2: 0.2}}}}
"""


def test_name_plot_escapes_every_dollar():
    assert name_plot("$\\frac{$ a $") == "\\$\\frac{\\$ a \\$"
    assert name_plot("tool") == "tool"


@pytest.fixture(scope="module")
def problem():
    p = load_problem_text(PROBLEM, "names.yaml")
    assert "$\\frac{$" in p.frames and p.title.startswith("Costs $5")
    return p


def test_the_report_figures_are_drawn(problem):
    files = render_files(solve_problem(problem), ("md",), InlineFigures())
    report = files["report.md"].decode()
    assert "could not be drawn" not in report
    pngs = [k for k in files if k.endswith(".png")]
    assert {"figures/position-robot.png", "figures/displacement-helical_axis.png"} <= set(pngs), pngs


def test_the_paper_figure_is_drawn(problem, tmp_path):
    from robosolve.model.chain import RobotModel
    from robosolve.papers.drawing import paper_figure
    from robosolve.render import plots

    spec = paper_figure(problem, RobotModel(problem))
    assert "\\$5" in spec.title
    frame = next(f for f in spec.data["frames"] if f["name"] == "$\\frac{$")
    assert frame["axis_labels"] == ["x (\\$\\frac{\\$)", "y (\\$\\frac{\\$)", "z (\\$\\frac{\\$)"]
    # a name longer than the drawing's LABEL_CHARS is cut there (the paper's text has it whole)
    assert [f["label"] for f in spec.data["forces"]] == ['"""; open…']
    plots.draw(spec, tmp_path / "robot.png")
    assert (tmp_path / "robot.png").stat().st_size > 1000
