"""Helical axis of a displacement: exact cases, spatialmath, round trips, special cases."""

import math

import numpy as np
import pytest
import sympy as sp

from robosolve.core.transforms import rot_x, rot_y, rot_z, translation, trans_x
from robosolve.geometry.helical import (
    axis_l_matrix, displacement_matrix, express_in_frame, helical_matrix, helical_numeric,
    helical_symbolic,
)

RNG = np.random.default_rng(7)


def f(m):
    return np.array(sp.Matrix(m).evalf(30), dtype=float)


def random_pose():
    from scipy.spatial.transform import Rotation

    m = np.eye(4)
    m[:3, :3] = Rotation.from_rotvec(RNG.normal(size=3)).as_matrix()
    m[:3, 3] = RNG.normal(size=3) * 2
    return m


def check_axis(ax, u, alpha, h, p, tol=1e-10):
    np.testing.assert_allclose(ax.axis, u, atol=tol)
    assert ax.angle == pytest.approx(alpha, abs=tol)
    assert ax.h == pytest.approx(h, abs=tol)
    np.testing.assert_allclose(ax.point, p, atol=tol)


# ---------------------------------------------------------------- exact, by hand


def test_exact_quarter_turn_with_translation():
    # Rz(90 deg) about the vertical through (-1, 2, 0), advancing 3 along z.
    q = translation(1, 2, 3) * rot_z(sp.pi / 2) * trans_x(1)
    ax = helical_symbolic(q)
    assert ax.case == "general"
    assert ax.axis == [0, 0, 1] and ax.angle == sp.pi / 2 and ax.h == 3
    assert ax.point == [-1, 2, 0] and ax.pitch == 6 / sp.pi
    assert ax.cos_alpha == 0 and ax.sin_alpha == 1
    check_axis(helical_numeric(f(q)), [0, 0, 1], math.pi / 2, 3, [-1, 2, 0])


def test_exact_half_turn():
    q = rot_x(sp.pi) * translation(1, 2, 3)  # R = diag(1, -1, -1), dT = (1, -2, -3)
    ax = helical_symbolic(q)
    assert ax.case == "half_turn" and ax.axis == [1, 0, 0] and ax.angle == sp.pi
    assert ax.h == 1 and ax.point == [0, -1, sp.Rational(-3, 2)] and ax.pitch == 1 / sp.pi
    axn = helical_numeric(f(q))
    assert axn.case == "half_turn"
    check_axis(axn, [1, 0, 0], math.pi, 1, [0, -1, -1.5])


def test_exact_general_axis():
    # Rotation 2pi/3 about (1,1,1)/sqrt3 (cyclic permutation) through P, with h.
    u = sp.Matrix([1, 1, 1]) / sp.sqrt(3)
    p = sp.Matrix([1, -1, 0])
    q = helical_matrix(u, 2 * sp.pi / 3, sp.Rational(1, 2), p)
    assert q[:3, :3] == sp.Matrix([[0, 0, 1], [1, 0, 0], [0, 1, 0]])
    ax = helical_symbolic(q)
    assert ax.case == "general"
    assert [sp.simplify(a - b) for a, b in zip(ax.axis, u)] == [0, 0, 0]
    assert ax.angle == 2 * sp.pi / 3
    assert sp.simplify(ax.h - sp.Rational(1, 2)) == 0
    assert [sp.simplify(a - b) for a, b in zip(ax.point, p)] == [0, 0, 0]


def test_pure_translation_and_identity():
    ax = helical_symbolic(translation(1, 2, 2))
    assert ax.case == "translation" and ax.axis == [sp.Rational(1, 3), sp.Rational(2, 3), sp.Rational(2, 3)]
    assert ax.angle == 0 and ax.h == 3 and ax.point is None and ax.pitch is None
    axn = helical_numeric(f(translation(1, 2, 2)))
    assert axn.case == "translation" and axn.point is None and axn.pitch is None
    np.testing.assert_allclose(axn.axis, [1 / 3, 2 / 3, 2 / 3])
    assert helical_numeric(np.eye(4)).case == "identity"
    ax = helical_symbolic(sp.eye(4))
    assert ax.case == "identity" and ax.axis is None and ax.h == 0


# ---------------------------------------------------------------- references


def test_against_spatialmath_trlog_and_twist():
    sm = pytest.importorskip("spatialmath")
    smb = pytest.importorskip("spatialmath.base")
    for _ in range(30):
        m01, m02 = random_pose(), random_pose()
        q = displacement_matrix(m01, m02)
        ax = helical_numeric(q)
        log = smb.trlog(q)  # = alpha * [[u], t; 0, 0], t = P x u + pitch u
        w = np.array([log[2, 1], log[0, 2], log[1, 0]])
        theta = np.linalg.norm(w)
        u, t = w / theta, log[:3, 3] / theta
        assert ax.angle == pytest.approx(theta, abs=1e-9)
        np.testing.assert_allclose(ax.axis, u, atol=1e-9)
        assert ax.pitch == pytest.approx(u @ t, abs=1e-8)
        np.testing.assert_allclose(ax.point, np.cross(u, t), atol=1e-8)
        tw = sm.Twist3(q)
        np.testing.assert_allclose(ax.point, tw.line().pp, atol=1e-8)
        assert ax.pitch == pytest.approx(tw.pitch, abs=1e-8)
        np.testing.assert_allclose(ax.point, tw.pole / tw.theta, atol=1e-8)  # .pole is off by theta


def test_l_matrix_exponential_gives_q():
    from scipy.linalg import expm

    for _ in range(10):
        q = displacement_matrix(random_pose(), random_pose())
        ax = helical_numeric(q)
        lm = f(axis_l_matrix(ax.axis, ax.point, ax.pitch))
        np.testing.assert_allclose(expm(ax.angle * lm), q, atol=1e-10)
    lm = f(axis_l_matrix([0, 0, 1], None, None))
    np.testing.assert_allclose(expm(2.0 * lm), f(translation(0, 0, 2)), atol=1e-14)


def test_round_trip_numeric():
    for _ in range(30):
        u = RNG.normal(size=3)
        u /= np.linalg.norm(u)
        alpha = RNG.uniform(0.01, math.pi - 0.01)
        h = RNG.normal()
        p = RNG.normal(size=3) * 3
        p -= (p @ u) * u
        q = f(helical_matrix(u.tolist(), alpha, h, p.tolist()))
        ax = helical_numeric(q)
        check_axis(ax, u, alpha, h, p, tol=1e-9)
        assert ax.pitch == pytest.approx(h / alpha)
        np.testing.assert_allclose(f(helical_matrix(ax.axis, ax.angle, ax.h, ax.point)), q, atol=1e-12)


def test_round_trip_symbolic():
    u = sp.Matrix([2, -1, 2]) / 3
    p = sp.Matrix([1, 2, 0])  # p . u = 0
    for alpha, h in ((sp.pi / 4, 2), (sp.pi / 2, -sp.Rational(1, 3)), (sp.pi, 5)):
        ax = helical_symbolic(helical_matrix(u, alpha, h, p))
        assert sp.simplify(ax.angle - alpha) == 0
        assert [sp.simplify(a - b) for a, b in zip(ax.axis, u)] == [0, 0, 0]
        assert sp.simplify(ax.h - h) == 0
        assert [sp.simplify(a - b) for a, b in zip(ax.point, p)] == [0, 0, 0]


# ---------------------------------------------------------------- special cases


@pytest.mark.parametrize("alpha", [1e-9, 1e-7])
def test_tiny_angle_no_cancellation(alpha):
    u = np.array([2.0, -1.0, 2.0]) / 3
    p = np.array([1.0, 2.0, 0.0])
    h = 0.3
    # exact Q built in high precision, then rounded once to floats
    q = f(helical_matrix(sp.Matrix([2, -1, 2]) / 3, sp.Float(alpha, 30), sp.Float(h, 30), [1, 2, 0]))
    ax = helical_numeric(q)
    assert ax.case == "general"
    assert ax.angle == pytest.approx(alpha, rel=1e-9)
    np.testing.assert_allclose(ax.axis, u, atol=1e-7)
    assert ax.h == pytest.approx(h, rel=1e-9)
    # the axis point is conditioned by 1/alpha: rounding of dT (1e-16) -> ~1e-16/alpha
    np.testing.assert_allclose(ax.point, p, atol=1e-5)
    assert ax.pitch == pytest.approx(h / alpha, rel=1e-8)


def test_near_half_turn_sign_follows_sin():
    u = sp.Matrix([1, -2, 2]) / 3
    for alpha in (math.pi - 1e-9, math.pi - 1e-5):
        q = f(helical_matrix(u, sp.Float(alpha, 30), 1, [2, 1, 0]))
        ax = helical_numeric(q)
        assert ax.angle == pytest.approx(alpha, abs=1e-9)
        np.testing.assert_allclose(ax.axis, [1 / 3, -2 / 3, 2 / 3], atol=1e-7)
        np.testing.assert_allclose(ax.point, [2, 1, 0], atol=1e-7)
        assert ax.h == pytest.approx(1.0, abs=1e-9)
    # exactly pi about -u: same displacement as about +u with h -> -h; canonical +u
    q = helical_matrix(-u, sp.pi, 1, [2, 1, 0])
    ax = helical_numeric(f(q))
    assert ax.case == "half_turn"
    check_axis(ax, [1 / 3, -2 / 3, 2 / 3], math.pi, -1, [2, 1, 0])
    axs = helical_symbolic(q)
    assert axs.case == "half_turn" and axs.h == -1 and axs.axis == list(u)


# ---------------------------------------------------------------- poses and frames


def test_displacement_from_poses_moves_body_points():
    m01, m02 = random_pose(), random_pose()
    q = displacement_matrix(m01, m02)
    np.testing.assert_allclose(q @ m01, m02, atol=1e-12)
    body_point = np.array([0.3, -0.2, 0.5, 1.0])  # fixed in the body
    np.testing.assert_allclose(q @ (m01 @ body_point), m02 @ body_point, atol=1e-12)
    qs = displacement_matrix(sp.Matrix(m01), sp.Matrix(m02))
    np.testing.assert_allclose(f(qs), q, atol=1e-12)


def test_express_in_another_frame():
    m01, m02, m0k = random_pose(), random_pose(), random_pose()
    q0 = displacement_matrix(m01, m02)
    qk = express_in_frame(q0, m0k)
    # Qk is the displacement between the same poses written in frame k
    inv = np.linalg.inv(m0k)
    np.testing.assert_allclose(qk, displacement_matrix(inv @ m01, inv @ m02), atol=1e-12)
    a0, ak = helical_numeric(q0), helical_numeric(qk)
    assert ak.angle == pytest.approx(a0.angle) and ak.h == pytest.approx(a0.h)
    np.testing.assert_allclose(ak.axis, m0k[:3, :3].T @ np.array(a0.axis), atol=1e-10)
    # P*_k lies on the frame-0 axis (moved into frame k) and is perpendicular to u_k
    pk0 = (m0k @ np.array([*ak.point, 1.0]))[:3]
    d = pk0 - np.array(a0.point)
    np.testing.assert_allclose(np.cross(d, a0.axis), 0, atol=1e-9)
    assert np.dot(ak.point, ak.axis) == pytest.approx(0, abs=1e-9)


def test_symbolic_inputs():
    a, b, hh = sp.symbols("a b h", real=True)
    q = rot_z(a) * translation(b, 0, hh)
    ax = helical_symbolic(q)
    assert ax.case == "generic" and ax.notes
    vals = {a: 0.8, b: 1.5, hh: -0.4}
    axn = helical_numeric(f(q.subs(vals)))
    assert float(ax.angle.subs(vals)) == pytest.approx(axn.angle)
    np.testing.assert_allclose([float(x.subs(vals)) for x in ax.axis], axn.axis, atol=1e-12)
    np.testing.assert_allclose([float(x.subs(vals)) for x in ax.point], axn.point, atol=1e-12)
    assert float(ax.h.subs(vals)) == pytest.approx(axn.h)
    assert float(ax.pitch.subs(vals)) == pytest.approx(axn.pitch)
    # symbolic translation only
    ax = helical_symbolic(translation(b, 0, 0))
    assert ax.case == "translation" and ax.h == sp.Abs(b)
    # a rotation with exact numbers and a symbolic translation: exact case analysis
    ax = helical_symbolic(rot_y(sp.pi / 2) * translation(0, b, 0))
    assert ax.case == "general" and ax.axis == [0, 1, 0] and ax.h == b


def test_bad_shape():
    with pytest.raises(ValueError):
        helical_numeric(np.eye(3))
    with pytest.raises(ValueError):
        helical_symbolic(sp.eye(3))
