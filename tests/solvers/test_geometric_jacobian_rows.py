"""The geometric Jacobian of a 4-joint arm with a tool point in decimals: its velocity rows are the
derivatives of the point's (tidy) coordinates, so the 6x4 J stays within the symbolic budget (its
rank conditions are then searched, as the spec asks up to 4 joints); the values against a numpy
chain by hand (finite differences of the point, vex(R' R^T) for the angular rows)."""

import numpy as np
import sympy as sp

from robosolve.core.simplify import expression_nodes
from robosolve.load.loader import load_problem
from robosolve.model.chain import RobotModel
from robosolve.run.pipeline import solve_context
from robosolve.solvers.task_space import task_space

ARM = """\
robosolve: 1
name: four-joints-and-a-tool
parameters: {a1: 0.3, a2: 0.25, b: 0.1, c: 0.05}
joints:
  - {name: t1, type: revolute}
  - {name: t2, type: revolute}
  - {name: s, type: prismatic}
  - {name: t4, type: revolute}
frames:
  "1": {parent: "0", dh: {theta: t1, d: b, a: a1, alpha: 0}}
  "2": {mdh: {alpha: pi/2, a: 0, theta: t2, d: 0}}
  "3": {matrix: [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, s], [0, 0, 0, 1]]}
  "4": {pose: "Rx(t4) Ty(c)"}
  tool: {parent: "4", pose: "Tx(a2) Rz(pi/6)"}
points:
  E: {frame: tool, at: [0.02, 0, 0.01]}
questions:
  - {type: jacobian, geometric: true, frame: tool, at: {t1: 0.2, t2: -0.4, s: 0.3, t4: 1.0}}
"""


def _rot(axis, a):
    c, s = np.cos(a), np.sin(a)
    m = {"x": [[1, 0, 0], [0, c, -s], [0, s, c]], "y": [[c, 0, s], [0, 1, 0], [-s, 0, c]],
         "z": [[c, -s, 0], [s, c, 0], [0, 0, 1]]}[axis]
    out = np.eye(4)
    out[:3, :3] = m
    return out


def _tr(x, y, z):
    out = np.eye(4)
    out[:3, 3] = [x, y, z]
    return out


def _tool(q):
    t1, t2, s, t4 = q
    return (_rot("z", t1) @ _tr(0, 0, 0.1) @ _tr(0.3, 0, 0) @ _rot("x", np.pi / 2) @ _rot("z", t2)
            @ _tr(0, 0, s) @ _rot("x", t4) @ _tr(0, 0.05, 0) @ _tr(0.25, 0, 0) @ _rot("z", np.pi / 6))


def test_the_velocity_rows_are_tidy_and_right(tmp_path):
    path = tmp_path / "arm.yaml"
    path.write_text(ARM, encoding="utf-8")
    problem = load_problem(path)
    ctx = solve_context(problem, model=RobotModel(problem))
    question = problem.questions[0]
    ts = task_space(question, ctx, 30, geometric=True)
    assert expression_nodes(ts.J) <= ctx.budgets.symbolic_nodes

    q0, h = np.array([0.2, -0.4, 0.3, 1.0]), 1e-6
    ref = np.zeros((6, 4))
    for i in range(4):
        e = np.eye(4)[i] * h
        plus, minus = _tool(q0 + e), _tool(q0 - e)
        ref[:3, i] = ((plus - minus) @ [0.02, 0, 0.01, 1])[:3] / (2 * h)
        w = (plus[:3, :3] - minus[:3, :3]) / (2 * h) @ _tool(q0)[:3, :3].T
        ref[3:, i] = [w[2, 1], w[0, 2], w[1, 0]]
    values = dict(zip(["t1", "t2", "s", "t4"], q0)) | {"a1": 0.3, "a2": 0.25, "b": 0.1, "c": 0.05}
    J = ts.J.subs({x: values[x.name] for x in ts.J.free_symbols})
    assert np.allclose(np.array(J.evalf(), dtype=float), ref, atol=1e-8)
