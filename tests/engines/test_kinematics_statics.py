"""Statics engine: a 2R by hand, virtual work by finite differences, Robotics Toolbox
gravload and jacob0, and the course's potential energy U = −tr(Hg·⁰J)."""

import numpy as np
import pytest
import sympy as sp

from robosolve.core.matrices import gravity_matrix, pseudo_inertia_rod
from robosolve.core.transforms import rot_x
from robosolve.kinematics.jacobian_math import analytic_jacobian, com_jacobian, geometric_jacobian
from robosolve.kinematics.statics_math import balance_force, balance_weight, balance_wrench
from tests.support.robots import L1, L2, KinRobot as Robot, t1, t2
from tests.support.robots import kin_planar2r as planar2r, kin_scara as scara

RNG = np.random.default_rng(5)


def test_planar_2r_by_hand():
    r = planar2r()
    J = analytic_jacobian(r.E[:2, :], r.q)
    subs = {**r.params, t1: 0, t2: sp.pi / 2}
    Fq = balance_force(J, [1, 0]).subs(subs)
    # F = (1, 0) N at E = (1/2, 1/2): moment about joint 1 = -1/2, about joint 2 (at
    # (1/2, 0)) = -1/2, so both joints must exert +1/2 N·m.
    assert list(Fq) == [sp.Rational(1, 2), sp.Rational(1, 2)]
    Fx, Fy = sp.symbols("F_x F_y")
    Fq_sym = balance_force(J, [Fx, Fy])
    hand = sp.Matrix([Fx * (L1 * sp.sin(t1) + L2 * sp.sin(t1 + t2))
                      - Fy * (L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2)),
                      Fx * L2 * sp.sin(t1 + t2) - Fy * L2 * sp.cos(t1 + t2)])
    assert sp.simplify(Fq_sym - hand) == sp.zeros(2, 1)


def test_virtual_work_finite_differences():
    r = scara()
    J = analytic_jacobian(r.E, r.q)
    F = np.array([3.0, -2.0, 5.0])
    fk = sp.lambdify([r.q], r.E.subs(r.params), "numpy")
    Fq = sp.lambdify([r.q], balance_force(J.subs(r.params), list(F)), "numpy")
    for _ in range(5):
        q = RNG.uniform(-2, 2, 3)
        eps = 1e-6
        # δW = Fqᵀδq + Fᵀδs = 0 for every δq
        for k in range(3):
            dq = np.zeros(3)
            dq[k] = eps
            ds = (np.asarray(fk(q + dq), float) - np.asarray(fk(q - dq), float)).reshape(3)
            work = np.asarray(Fq(q), float).reshape(3)[k] * 2 * eps + F @ ds
            assert abs(work) < 1e-9


def test_wrench_vs_rtb_jacob0():
    rtb = pytest.importorskip("roboticstoolbox")
    r = scara()
    JG = geometric_jacobian([lm.subs(r.params) for lm in r.L0], r.E.subs(r.params))
    F, tau = [1.0, 2.0, -3.0], [0.5, -0.2, 0.7]
    f = sp.lambdify([r.q], balance_wrench(JG, F, tau), "numpy")
    e = rtb.ET.tz(1.0) * rtb.ET.Rz() * rtb.ET.tx(0.5) * rtb.ET.Rz() * rtb.ET.tx(0.4) \
        * rtb.ET.tz(flip=True)
    robot = rtb.Robot(e)
    for _ in range(5):
        q = RNG.uniform(-3, 3, 3)
        ref = -robot.jacob0(q).T @ np.array(F + tau)
        np.testing.assert_allclose(np.asarray(f(q), float).reshape(3), ref, atol=1e-12)


def _vertical_2r():
    """2R arm in the vertical x-z plane (base Rx(π/2)), uniform rods, masses m1, m2."""
    from robosolve.core.transforms import rot_z, trans_x
    return Robot([t1, t2], ["revolute", "revolute"],
                 [[rot_x(sp.pi / 2), rot_z(t1), trans_x(L1)], [rot_z(t2), trans_x(L2)]],
                 {L1: sp.Rational(1, 2), L2: sp.Rational(2, 5)})


def test_weight_vs_rtb_gravload_and_potential():
    r = _vertical_2r()
    m1, m2, g = 2.0, 1.5, 9.81
    rods = [pseudo_inertia_rod(m1, [-L1, 0, 0], [0, 0, 0]),
            pseudo_inertia_rod(m2, [-L2, 0, 0], [0, 0, 0])]
    jgs = [com_jacobian(rods[i], r.M0[i], r.q) for i in range(2)]
    Fq = balance_weight(jgs, [m1, m2], [0, 0, -g]).subs(r.params)
    f = sp.lambdify([r.q], Fq, "numpy")
    # course formula: U = −Σ tr(Hg·⁰Jᵢ), ⁰Jᵢ = M0i·Jᵢ·M0iᵀ; balancing Fq = ∂U/∂q
    hg = gravity_matrix([0, 0, -g])
    U = sum(-(hg * r.M0[i] * rods[i] * r.M0[i].T).trace() for i in range(2))
    u = sp.lambdify([r.q], U.subs(r.params), "numpy")
    rtb = pytest.importorskip("roboticstoolbox")
    from spatialmath import SE3
    robot = rtb.DHRobot([rtb.RevoluteDH(a=0.5, m=m1, r=[-0.25, 0, 0]),
                         rtb.RevoluteDH(a=0.4, m=m2, r=[-0.2, 0, 0])],
                        base=SE3.Rx(np.pi / 2), gravity=[0, 0, -g])
    for _ in range(5):
        q = RNG.uniform(-3, 3, 2)
        mine = np.asarray(f(q), float).reshape(2)
        np.testing.assert_allclose(mine, robot.gravload(q), atol=1e-10)
        eps = 1e-6
        du = [(u(q + eps * e) - u(q - eps * e)) / (2 * eps) for e in np.eye(2)]
        np.testing.assert_allclose(mine, du, atol=1e-7)


def test_force_dimension_mismatch():
    with pytest.raises(ValueError):
        balance_force(sp.eye(2), [1, 2, 3])
