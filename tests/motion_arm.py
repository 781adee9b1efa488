"""A planar 2R arm in a vertical plane, built three independent ways for the motion tests.

* ``symbolic()``: Lagrange's equations written directly from the centre-of-mass
  positions (sympy), giving M(q), c(q, qd), g(q);
* ``rtb_robot()``: Robotics Toolbox DH robot (test-only reference, ``rne``);
* ``pin_model()``: pinocchio model built joint by joint (test-only reference, ``aba``).

Links along x of their frames, joints about z, gravity (0, -g, 0) in the base frame.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

VALUES = dict(L1=0.5, L2=0.4, m1=3.0, m2=2.0, I1=0.06, I2=0.03, g=9.81)
LC = dict(lc1=0.25, lc2=0.2)          # centres of mass from each joint, along the link


def symbolic():
    """(M, c, g_vec, q, qd, qdd, params) of the 2R arm, by Lagrange from the COM positions."""
    q1, q2, dq1, dq2 = sp.symbols("q1 q2 q1_dot q2_dot")
    ddq1, ddq2 = sp.symbols("q1_ddot q2_ddot")
    L1, m1, m2, I1, I2, g, lc1, lc2 = sp.symbols("L1 m1 m2 I1 I2 g lc1 lc2", positive=True)
    t = sp.Symbol("t")
    f1, f2 = sp.Function("f1")(t), sp.Function("f2")(t)
    p1 = sp.Matrix([lc1 * sp.cos(f1), lc1 * sp.sin(f1)])
    p2 = sp.Matrix([L1 * sp.cos(f1) + lc2 * sp.cos(f1 + f2), L1 * sp.sin(f1) + lc2 * sp.sin(f1 + f2)])
    v1, v2 = p1.diff(t), p2.diff(t)
    T = (m1 * v1.dot(v1) + m2 * v2.dot(v2) + I1 * f1.diff(t) ** 2 + I2 * (f1.diff(t) + f2.diff(t)) ** 2) / 2
    U = g * (m1 * p1[1] + m2 * p2[1])
    Lg = T - U
    eqs = []
    for f in (f1, f2):
        eqs.append(sp.diff(Lg.diff(f.diff(t)), t) - Lg.diff(f))
    rep = {f1.diff(t, 2): ddq1, f2.diff(t, 2): ddq2}
    rep2 = {f1.diff(t): dq1, f2.diff(t): dq2}
    rep3 = {f1: q1, f2: q2}
    eqs = [sp.expand(e.subs(rep).subs(rep2).subs(rep3)) for e in eqs]
    qdd = [ddq1, ddq2]
    M = sp.Matrix(2, 2, lambda i, j: eqs[i].coeff(qdd[j]))
    rest = [sp.expand(e - sum(M[i, j] * qdd[j] for j in range(2))) for i, e in enumerate(eqs)]
    gv = sp.Matrix([r.subs({dq1: 0, dq2: 0}) for r in rest])
    c = sp.Matrix([sp.expand(r - gr) for r, gr in zip(rest, gv)])
    params = {L1: VALUES["L1"], m1: VALUES["m1"], m2: VALUES["m2"], I1: VALUES["I1"], I2: VALUES["I2"],
              g: VALUES["g"], lc1: LC["lc1"], lc2: LC["lc2"]}
    return M, c, gv, [q1, q2], [dq1, dq2], qdd, params


def rtb_robot():
    import pytest
    rtb = pytest.importorskip("roboticstoolbox")
    v = VALUES
    l1 = rtb.RevoluteDH(a=v["L1"], m=v["m1"], r=[LC["lc1"] - v["L1"], 0, 0], I=[0, 0, v["I1"]], Jm=0, G=1, B=0, Tc=[0, 0])
    l2 = rtb.RevoluteDH(a=v["L2"], m=v["m2"], r=[LC["lc2"] - v["L2"], 0, 0], I=[0, 0, v["I2"]], Jm=0, G=1, B=0, Tc=[0, 0])
    robot = rtb.DHRobot([l1, l2], gravity=[0, -v["g"], 0])
    return robot


def pin_model():
    import pytest
    pin = pytest.importorskip("pinocchio")
    v = VALUES
    model = pin.Model()
    j1 = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "j1")
    model.appendBodyToJoint(j1, pin.Inertia(v["m1"], np.array([LC["lc1"], 0, 0]), np.diag([0, 0, v["I1"]])), pin.SE3.Identity())
    j2 = model.addJoint(j1, pin.JointModelRZ(), pin.SE3(np.eye(3), np.array([v["L1"], 0, 0])), "j2")
    model.appendBodyToJoint(j2, pin.Inertia(v["m2"], np.array([LC["lc2"], 0, 0]), np.diag([0, 0, v["I2"]])), pin.SE3.Identity())
    model.gravity.linear = np.array([0, -v["g"], 0])
    return model
