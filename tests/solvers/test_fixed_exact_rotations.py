"""A fixed rotation by an exact angle sympy keeps as it is (Rz(2), Rz(1/3)) inside a frame's pose:
the equations of motion used to stop with an internal error (cos²2 + sin²2 left in a divisor,
the actuator's action no longer a polynomial). Checked against the closed form of the pendulum it
makes: the mass at L·(cos(θ + a), sin(θ + a)) in the x–y plane, gravity −g y:
m L² θ̈ + m g L cos(θ + a) = C."""

from __future__ import annotations

import math

import pytest

from robosolve.load.loader import load_problem_text
from robosolve.model import RobotModel
from robosolve.run.pipeline import solve_context, _solve_question
from robosolve.solvers.base import Budgets

PENDULUM = """robosolve: 1
name: pendulum
parameters: {{L: 0.7, m: 2, g: 9.81}}
joints: [{{name: theta, type: revolute, actuator: C}}]
frames:
  "1": {{parent: "0", pose: "Rz(theta) Rz({a}) Tx(L)"}}
gravity: [0, -g, 0]
bodies: [{{name: bob, frame: "1", mass: m, point: [0, 0, 0]}}]
questions:
  - {{type: equations_of_motion, at: {{theta: 0.4, theta_dot: 1.3, theta_ddot: -0.6}}}}
"""


@pytest.mark.parametrize("a, value", [("2", 2.0), ("1/3", 1 / 3), ("pi/7", math.pi / 7), ("2.0", 2.0)])
def test_a_fixed_exact_rotation_gives_the_pendulum_equation(a, value):
    problem = load_problem_text(PENDULUM.format(a=a), "p.yaml")
    ctx = solve_context(problem, RobotModel(problem), Budgets())
    answer = _solve_question(problem.questions[0], ctx, 120)
    assert answer.error is None, answer.error
    L, m, g, th, thdd = 0.7, 2.0, 9.81, 0.4, -0.6
    num = answer.numeric
    assert num["mass_matrix"][0][0] == pytest.approx(m * L ** 2, rel=1e-12)
    assert num["velocity_terms"][0] == pytest.approx(0.0, abs=1e-12)
    assert num["gravity_terms"][0] == pytest.approx(m * g * L * math.cos(th + value), rel=1e-10)
    assert num["actuators"]["C"] == pytest.approx(m * L ** 2 * thdd + m * g * L * math.cos(th + value), rel=1e-10)
