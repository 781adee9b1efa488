"""report.ipynb's recomputing cells run in-process (the runtime's namespace, the notebook's own data
cell) and recompute the right values, checked against closed forms by hand."""

import re

import numpy as np

from robosolve.load.loader import load_problem
from robosolve.render import notebook_runtime as rt
from robosolve.render.notebook import code_cells
from robosolve.run.pipeline import solve_problem

ARM_2R = """\
robosolve: 1
name: point-on-link-one
parameters: {L1: 0.6, L2: 0.4}
joints:
  - {name: q1, type: revolute}
  - {name: q2, type: revolute}
frames:
  "1": {parent: "0", pose: "Rz(q1) Tx(L1)"}
  "2": {pose: "Rz(q2) Tx(L2)"}
points:
  G: {frame: "1", at: [-0.3, 0, 0]}
questions:
  - type: velocity_acceleration
    point: G
    at: {q1: 0.5, q2: -1.1, q1_dot: 1.5, q2_dot: -0.7, q1_ddot: 0.3, q2_ddot: 0.9}
"""


def _run_cells(tmp_path, text, capsys):
    path = tmp_path / "problem.yaml"
    path.write_text(text, encoding="utf-8")
    problem = load_problem(path)
    report = solve_problem(problem)
    namespace = dict(vars(rt))
    for source in code_cells(problem, report.answers)[1:]:      # the data cell, then the answers'
        exec(source, namespace)
    return capsys.readouterr().out


def _recomputed(printed, key):
    m = re.search(rf"recomputed {key} = (\[.*?\])\n", printed)
    return np.array(eval(m.group(1)))                           # a printed list of floats


def test_the_velocity_of_a_point_fixed_in_another_frame_than_the_question_s(tmp_path, capsys):
    """G is fixed in frame 1, the question's frame is 2: G moves with frame 1 (by hand, G at
    r = 0.3 m from the base on link 1: v = r q1'(-s1, c1), a = r q1''(-s1, c1) - r q1'^2 (c1, s1))."""
    printed = _run_cells(tmp_path, ARM_2R, capsys)
    r, q1, w, wd = 0.3, 0.5, 1.5, 0.3
    c, s = np.cos(q1), np.sin(q1)
    assert np.allclose(_recomputed(printed, "velocity"), [-r * w * s, r * w * c, 0], atol=1e-9)
    assert np.allclose(_recomputed(printed, "acceleration"),
                       [-r * wd * s - r * w * w * c, r * wd * c - r * w * w * s, 0], atol=1e-9)
    assert "DIFFERS" not in printed and printed.count("agrees with robosolve") == 4
