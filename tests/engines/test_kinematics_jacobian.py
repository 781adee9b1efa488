"""Jacobian engines against ERRATA §B, Robotics Toolbox and finite differences."""

import numpy as np
import pytest
import sympy as sp

from robosolve.core.matrices import pseudo_inertia_rod
from robosolve.kinematics.jacobian_math import (
    analytic_jacobian, com_jacobian, com_position, geometric_jacobian, numeric_manipulability,
    rank_measure, tidy_matrix)
from tests.support.robots import L1, L2, h, t1, t2
from tests.support.robots import kin_anthropomorphic as anthropomorphic, kin_planar2r as planar2r, \
    kin_scara as scara

RNG = np.random.default_rng(7)


def _num(expr, subs):
    return np.array(sp.Matrix(expr).subs(subs).evalf(), dtype=float)


def test_scara_jacobian_errata_anchor():
    r = scara()
    J = tidy_matrix(analytic_jacobian(r.E, r.q))
    subs = {**r.params, r.q[0]: sp.pi / 6, r.q[1]: sp.pi / 3, r.q[2]: sp.Rational(1, 10)}
    exact = sp.Matrix([[-sp.Rational(13, 20), -sp.Rational(2, 5), 0],
                       [sp.sqrt(3) / 4, 0, 0], [0, 0, -1]])
    assert sp.simplify(J.subs(subs) - exact) == sp.zeros(3, 3)
    kind, det = rank_measure(J)
    assert kind == "det"
    assert sp.simplify(det.subs(subs) + sp.sqrt(3) / 10) == 0
    assert sp.simplify(det + L1 * L2 * sp.sin(t2)) == 0


def test_planar_2r_jacobian_by_hand():
    r = planar2r()
    J = analytic_jacobian(r.E[:2, :], r.q)
    hand = sp.Matrix([[-L1 * sp.sin(t1) - L2 * sp.sin(t1 + t2), -L2 * sp.sin(t1 + t2)],
                      [L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2), L2 * sp.cos(t1 + t2)]])
    assert sp.simplify(J - hand) == sp.zeros(2, 2)


def test_orientation_coordinate():
    r = planar2r()
    J = analytic_jacobian([r.E[0], r.E[1], t1 + t2], r.q)
    assert list(J[2, :]) == [1, 1]


def test_geometric_jacobian_vs_rtb_scara():
    rtb = pytest.importorskip("roboticstoolbox")
    r = scara()
    JG = geometric_jacobian([lm.subs(r.params) for lm in r.L0], r.E.subs(r.params))
    e = rtb.ET.tz(1.0) * rtb.ET.Rz() * rtb.ET.tx(0.5) * rtb.ET.Rz() * rtb.ET.tx(0.4) \
        * rtb.ET.tz(flip=True)
    robot = rtb.Robot(e)
    f = sp.lambdify([r.q], JG, "numpy")
    for _ in range(10):
        q = RNG.uniform(-np.pi, np.pi, 3)
        np.testing.assert_allclose(np.array(f(q), dtype=float), robot.jacob0(q), atol=1e-12)


@pytest.mark.slow
def test_geometric_jacobian_vs_rtb_anthropomorphic_dh():
    rtb = pytest.importorskip("roboticstoolbox")
    r = anthropomorphic()
    robot = rtb.DHRobot([rtb.RevoluteDH(d=0.5, a=0, alpha=np.pi / 2),
                         rtb.RevoluteDH(a=0.4), rtb.RevoluteDH(a=0.3)])
    JG = geometric_jacobian([lm.subs(r.params) for lm in r.L0], r.E.subs(r.params))
    f = sp.lambdify([r.q], JG, "numpy")
    for _ in range(10):
        q = RNG.uniform(-np.pi, np.pi, 3)
        np.testing.assert_allclose(np.array(f(q), dtype=float), robot.jacob0(q), atol=1e-12)


@pytest.mark.slow
def test_analytic_equals_geometric_linear_rows():
    r = anthropomorphic()
    JA = analytic_jacobian(r.E, r.q)
    JG = geometric_jacobian(r.L0, r.E)
    q = {s: v for s, v in zip(r.q, RNG.uniform(-3, 3, 3))}
    np.testing.assert_allclose(_num(JA, {**r.params, **q}), _num(JG[:3, :], {**r.params, **q}),
                               atol=1e-12)


def test_com_jacobian_finite_differences():
    r = planar2r()
    rod = pseudo_inertia_rod(3, [-L2, 0, 0], [0, 0, 0])
    c = com_position(rod, r.M0[1])
    assert sp.simplify(c[0] - (L1 * sp.cos(t1) + L2 * sp.cos(t1 + t2) / 2)) == 0
    JG = com_jacobian(rod, r.M0[1], r.q)
    f = sp.lambdify([r.q], c.subs(r.params), "numpy")
    q = RNG.uniform(-3, 3, 2)
    eps = 1e-6
    fd = np.column_stack([(np.array(f(q + eps * e), float) - np.array(f(q - eps * e), float))
                          .reshape(3) / (2 * eps) for e in np.eye(2)])
    np.testing.assert_allclose(_num(JG, {**r.params, t1: q[0], t2: q[1]}), fd, atol=1e-8)


def test_manipulability_is_product_of_singular_values():
    r = planar2r()
    J = analytic_jacobian(r.E[:2, :], r.q)
    kind, det = rank_measure(J)
    q = {t1: 0.3, t2: 1.1, **r.params}
    assert numeric_manipulability(_num(J, q)) == pytest.approx(abs(float(det.subs(q))))
    # redundant 2x3: manipulability = sqrt(det(J Jᵀ))
    J3 = np.array([[1.0, 2.0, 0.5], [0.0, 1.0, -1.0]])
    kind, gram = rank_measure(sp.Matrix(J3))
    assert kind == "gram"
    assert numeric_manipulability(J3) == pytest.approx(float(sp.sqrt(gram)))
    assert numeric_manipulability(np.zeros((2, 2))) == 0.0
    _ = h
