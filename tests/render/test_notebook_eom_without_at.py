"""An equations_of_motion question without `at` (symbolic answers only) gets a notebook cell
that runs: no numbers to recompute, the equations by Lagrange for a small arm (it stopped the
notebook with "Cannot convert expression to float" in robot.dynamics_at)."""

from __future__ import annotations

import ast
import json

import pytest

from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import render_files, solve_problem

PROBLEM = """\
robosolve: 1
name: eom-free
parameters: {L: 1, m: 2, g: 9.81}
joints: [{name: q1, type: revolute}, {name: q2, type: revolute}]
frames:
  "1": {pose: "Rz(q1) Tx(L)"}
  "2": {pose: "Rz(q2) Tx(L)"}
gravity: [0, -g, 0]
bodies:
  - {name: a, frame: "1", mass: m, point: [0, 0, 0]}
  - {name: b, frame: "2", mass: m, point: [0, 0, 0]}
questions:
  - {type: equations_of_motion}
  - {type: equations_of_motion, id: half, at: {q1: 0.2}}
"""


@pytest.fixture(scope="module")
def notebook():
    files = render_files(solve_problem(load_problem_text(PROBLEM, "e.yaml")), ("ipynb",))
    return json.loads(files["report.ipynb"])


def _cells(nb):
    return ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code"]


def test_the_cells_compute_no_numbers_without_a_whole_configuration(notebook):
    eom = [c for c in _cells(notebook) if "robot.lagrange" in c]
    assert len(eom) == 2
    for cell in eom:
        ast.parse(cell)
        assert "dynamics_at" not in cell and "no whole configuration" in cell


@pytest.mark.slow
def test_the_notebook_runs(notebook, tmp_path):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.reads(json.dumps(notebook), as_version=4)
    nbclient.NotebookClient(nb, timeout=300, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
