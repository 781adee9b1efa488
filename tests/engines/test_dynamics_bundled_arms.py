"""The bundled six-axis arms (problems/ur5.yaml, problems/kuka-kr.yaml): their equations of motion
against Robotics Toolbox (`inertia`, `rne`) built from the same DH table and point masses."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

rtb = pytest.importorskip("roboticstoolbox")

from robosolve.dynamics.bridge import numeric_for  # noqa: E402
from robosolve.load.loader import load_problem  # noqa: E402
from robosolve.model import RobotModel  # noqa: E402
from robosolve.run.pipeline import solve_context  # noqa: E402

PROBLEMS = Path(__file__).resolve().parents[2] / "problems"


def _rtb_twin(problem, values):
    """The problem's standard DH chain and point masses as an RTB DHRobot."""
    links = []
    for name, frame in problem.frames.items():
        th, d, a, al = frame.factors
        body = next(b for b in problem.bodies if b.frame == name)
        r = [float(sp.N(v.xreplace(values))) for v in body.data["at"]]
        links.append(rtb.RevoluteDH(d=float(sp.N(d.xreplace(values))), a=float(sp.N(a.xreplace(values))),
                                    alpha=float(sp.N(al.xreplace(values))), m=float(body.mass), r=r,
                                    I=np.zeros(3), Jm=0.0, G=1.0))
    return rtb.DHRobot(links, gravity=[0, 0, -9.81])


@pytest.mark.parametrize("name", ["ur5", pytest.param("kuka-kr", marks=pytest.mark.slow)])
def test_bundled_arm_dynamics_against_rtb(name):
    problem = load_problem(PROBLEMS / f"{name}.yaml")
    model = RobotModel(problem)
    ctx = solve_context(problem, model)
    values = ctx.substitutions({})
    nd, note = numeric_for(model, values)
    robot = _rtb_twin(problem, values)
    rng = np.random.default_rng(5)
    for _ in range(4):
        q, qd, qdd = rng.uniform(-np.pi, np.pi, (3, 6))
        m_ref = robot.inertia(q)
        assert np.allclose(nd.mass(q), m_ref, rtol=1e-9, atol=1e-9 * np.abs(m_ref).max())
        tau_ref = robot.rne(q, qd, qdd)
        assert np.allclose(nd.actuators(q, qd, qdd), tau_ref, rtol=1e-9, atol=1e-9 * np.abs(tau_ref).max())
