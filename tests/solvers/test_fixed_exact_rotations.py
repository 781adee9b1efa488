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


TWO_LINKS = """robosolve: 1
name: tilted
parameters: {{L1: 0.45, L2: 0.3, m1: 1.5, m2: 0.8, g: 9.81}}
joints: [{{name: q1, type: revolute}}, {{name: q2, type: revolute}}]
frames:
  "1": {{parent: "0", pose: "Rx({a}) Rz(q1) Ty(L1)"}}
  "2": {{pose: "Ry({b}) Rz(q2) Tx(L2)"}}
bodies:
  - {{name: b1, frame: "1", mass: m1, point: [0, 0, 0]}}
  - {{name: b2, frame: "2", mass: m2, point: [0, 0, 0]}}
questions:
  - {{type: equations_of_motion, at: {{q1: 0.7, q2: -1.1, q1_dot: 0.4, q2_dot: -0.9, q1_ddot: 0.3, q2_ddot: 1.2}}}}
"""


def _rot(axis, t):
    import numpy as np

    c, s = math.cos(t), math.sin(t)
    i, j = {"x": (1, 2), "y": (2, 0), "z": (0, 1)}[axis]
    r = np.eye(4)
    r[i, i], r[i, j], r[j, i], r[j, j] = c, -s, s, c
    return r


def _tr(axis, d):
    import numpy as np

    t = np.eye(4)
    t["xyz".index(axis), 3] = d
    return t


@pytest.mark.parametrize("a, b, av, bv", [("1/3", "2", 1 / 3, 2.0), ("pi/7", "-1/5", math.pi / 7, -0.2)])
def test_a_fixed_exact_rotation_before_the_joint(a, b, av, bv):
    """The fixed rotation before the joint in the same pose (Rx(1/3) Rz(q1)): the ring did not know
    sin²(1/3) + cos²(1/3) = 1, so Rx(1/3)ᵀ·Rx(1/3) was not I, the joint's axis seemed to turn with
    the joint, and the equations of motion stopped with an internal error. Reference: Lagrange by
    finite differences on the point masses' positions (numpy, not robosolve)."""
    import numpy as np

    L1, L2, m1, m2, g = 0.45, 0.3, 1.5, 0.8, 9.81

    def points(q):
        f1 = _rot("x", av) @ _rot("z", q[0]) @ _tr("y", L1)
        f2 = f1 @ _rot("y", bv) @ _rot("z", q[1]) @ _tr("x", L2)
        return f1[:3, 3], f2[:3, 3]

    def jac(q, k, h=1e-6):
        return np.array([(points(q + h * e)[k] - points(q - h * e)[k]) / (2 * h) for e in np.eye(2)]).T

    def mass(q):
        return sum(m * jac(q, k).T @ jac(q, k) for k, m in enumerate((m1, m2)))

    def potential(q):
        return sum(m * g * points(q)[k][2] for k, m in enumerate((m1, m2)))

    q, qd, qdd = np.array([0.7, -1.1]), np.array([0.4, -0.9]), np.array([0.3, 1.2])
    h = 1e-5
    dm = [(mass(q + h * e) - mass(q - h * e)) / (2 * h) for e in np.eye(2)]
    mdot = sum(d * v for d, v in zip(dm, qd))
    c = mdot @ qd - 0.5 * np.array([qd @ d @ qd for d in dm])
    grav = np.array([(potential(q + h * e) - potential(q - h * e)) / (2 * h) for e in np.eye(2)])

    problem = load_problem_text(TWO_LINKS.format(a=a, b=b), "p.yaml")
    ctx = solve_context(problem, RobotModel(problem), Budgets())
    answer = _solve_question(problem.questions[0], ctx, 120)
    assert answer.error is None, answer.error
    num = answer.numeric
    assert np.allclose(num["mass_matrix"], mass(q), atol=1e-7)
    assert np.allclose(num["velocity_terms"], c, atol=1e-6)
    assert np.allclose(num["gravity_terms"], grav, atol=1e-6)
    assert np.allclose(list(num["actuators"].values()), mass(q) @ qdd + c + grav, atol=1e-6)
