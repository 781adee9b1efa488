"""DH robots written with floats (twists like 0.7 rad, joint offsets, decimal lengths),
standard and modified, revolute and prismatic: pose and (2 joints) geometric Jacobian (Robotics Toolbox)
and equations of motion (a finite-difference Lagrange reference on the toolbox's forward
kinematics, tests/support/lagrange_fd.py).

A float twist once left rounding noise (cos²0.7 + sin²0.7 ≠ 1) in a joint axis' length and
the equations of motion ended in an internal error.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from robosolve.load.loader import load_problem_text
from robosolve.run.pipeline import solve_problem
from support.lagrange_fd import FiniteDifferenceLagrange

rtb = pytest.importorskip("roboticstoolbox")

# (kind, theta offset or d offset, d, a, alpha text, mass, com, inertia) per joint
ROBOTS = {
    "modified-RR-float-twist": ("modified", [
        ("R", 0.0, 0.0, 0.468, "0", 2.999, [0.055, 0.121, 0.144], [0.056, 0.043, 0.094, 0.0]),
        ("R", -0.153, 0.246, 0.0, "0.7", 1.5, [0.1, -0.05, 0.02], [0.03, 0.02, 0.05, 0.004]),
    ]),
    "modified-PPR": ("modified", [
        ("P", 0.2, 0.0, 0.3, "pi/2", 1.2, [0.0, 0.1, -0.05], [0.02, 0.03, 0.04, 0.0]),
        ("P", 0.0, 0.0, 0.0, "-pi/2", 0.8, [0.05, 0.0, 0.1], [0.01, 0.02, 0.015, 0.002]),
        ("R", 0.4, 0.15, 0.25, "0.7", 0.6, [0.12, 0.02, 0.0], [0.005, 0.008, 0.006, -0.001]),
    ]),
    "standard-RPR": ("standard", [
        ("R", 0.0, 0.35, 0.0, "pi/2", 2.0, [0.0, -0.1, 0.0], [0.04, 0.05, 0.03, 0.0]),
        ("P", 0.1, 0.0, 0.0, "-pi/2", 1.0, [0.0, 0.0, -0.2], [0.02, 0.02, 0.01, 0.003]),
        ("R", -0.3, 0.0, 0.2, "0.3", 0.5, [0.1, 0.0, 0.0], [0.001, 0.004, 0.004, 0.0]),
    ]),
}


def _problem(convention, joints, q, qd, qdd):
    rows, bodies, decl = [], [], []
    for i, (kind, offset, d, a, alpha, m, com, (ixx, iyy, izz, ixy)) in enumerate(joints, 1):
        name = f"q{i}"
        decl.append(f"  - {{name: {name}, type: {'revolute' if kind == 'R' else 'prismatic'}}}")
        theta, dd = (f"{name} + {offset}", d) if kind == "R" else (offset, f"{name} + {d}")
        rows.append(f"    - {{theta: '{theta}', d: '{dd}', a: {a}, alpha: '{alpha}'}}")
        bodies.append(f"  - {{name: b{i}, frame: '{i}', mass: {m}, com: {com}, "
                      f"inertia: [[{ixx}, {ixy}, 0], [{ixy}, {iyy}, 0], [0, 0, {izz}]]}}")
    n = len(joints)
    at = ", ".join(f"q{i + 1}: {q[i]}" for i in range(n))
    state = at + "".join(f", q{i + 1}_dot: {qd[i]}, q{i + 1}_ddot: {qdd[i]}" for i in range(n))
    return "\n".join([
        "robosolve: 1", "name: float-dh", "parameters: {g: 9.81}", "joints:", *decl,
        f"dh:\n  convention: {convention}\n  rows:", *rows, "bodies:", *bodies, "questions:",
        f"  - {{id: pose, type: position, frame: '{n}', at: {{{at}}}}}",
        # the geometric Jacobian of one robot only: its singularity analysis with float
        # coefficients takes tens of seconds for three joints
        *([f"  - {{id: jac, type: jacobian, geometric: true, frame: '{n}', at: {{{at}}}}}"] if n == 2 else []),
        f"  - {{id: eom, type: equations_of_motion, at: {{{state}}}}}",
    ]) + "\n"


def _toolbox(convention, joints):
    links = []
    for kind, offset, d, a, alpha, m, com, (ixx, iyy, izz, ixy) in joints:
        alpha_value = {"0": 0.0, "pi/2": math.pi / 2, "-pi/2": -math.pi / 2}.get(alpha) or float(alpha)
        inertia = np.array([[ixx, ixy, 0], [ixy, iyy, 0], [0, 0, izz]])
        common = dict(a=a, alpha=alpha_value, m=m, r=com, I=inertia)
        modified = convention == "modified"
        if kind == "R":
            cls = rtb.RevoluteMDH if modified else rtb.RevoluteDH
            links.append(cls(d=d, offset=offset, **common))
        else:
            cls = rtb.PrismaticMDH if modified else rtb.PrismaticDH
            links.append(cls(theta=offset, offset=d, **common))
    return rtb.DHRobot(links, gravity=[0, 0, -9.81])


@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_float_dh_robot_against_references(name):
    convention, joints = ROBOTS[name]
    n = len(joints)
    q, qd, qdd = np.linspace(-0.9, 1.1, n), np.linspace(0.6, -0.4, n), np.linspace(-0.5, 0.8, n)
    problem = load_problem_text(_problem(convention, joints, q, qd, qdd), f"{name}.yaml")
    answers = {a.id: a for a in solve_problem(problem).answers}
    assert all(a.error is None for a in answers.values()), {k: a.error for k, a in answers.items()}
    robot = _toolbox(convention, joints)
    assert np.allclose(np.array(answers["pose"].numeric["M"], dtype=float), robot.fkine(q).A, atol=1e-10)
    if "jac" in answers:
        assert np.allclose(np.array(answers["jac"].numeric["J"], dtype=float), robot.jacob0(q), atol=1e-10)
    reference = FiniteDifferenceLagrange(robot)
    eom = answers["eom"].numeric
    assert np.allclose(np.array(eom["mass_matrix"], dtype=float), reference.mass_matrix(q), atol=1e-7)
    tau = [eom["actuators"][k] for k in eom["actuators"]] if isinstance(eom["actuators"], dict) else eom["actuators"]
    assert np.allclose(np.array(tau, dtype=float), reference.torques(q, qd, qdd), atol=1e-5)
