"""Rotation representations: against spatialmath / scipy, round trips, singular cases."""

import math

import numpy as np
import pytest
import sympy as sp

from robosolve.geometry.rotations import (
    axis_angle_matrix, axis_angle_numeric, axis_angle_symbolic, canonical_sign,
    quaternion_matrix, quaternion_numeric, quaternion_symbolic, rpy_matrix, rpy_numeric,
    rpy_symbolic, wrap_angle, zyz_matrix, zyz_numeric, zyz_symbolic,
)

RNG = np.random.default_rng(20240612)


def f(m):
    return np.array(sp.Matrix(m).evalf(30), dtype=float)


def rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])


def ry(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0, s], [0, 1.0, 0], [-s, 0, c]])


def rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0, 0], [0, c, -s], [0, s, c]])


def random_quaternions(n):
    out = []
    for _ in range(n):
        q = RNG.normal(size=4)
        q /= np.linalg.norm(q)
        out.append(q if q[0] >= 0 else -q)
    return out


def random_rotations(n):
    return [f(quaternion_matrix(q.tolist())) for q in random_quaternions(n)]


def in_range(a):
    return -math.pi < a <= math.pi


# ---------------------------------------------------------------- numeric, generic


def test_zyz_numeric_matches_spatialmath_and_round_trips():
    smb = pytest.importorskip("spatialmath.base")
    for r in random_rotations(50):
        e = zyz_numeric(r)
        assert e.singular is False and len(e.solutions) == 2
        np.testing.assert_allclose(e.solutions[0], smb.tr2eul(r), atol=1e-12)
        np.testing.assert_allclose(e.solutions[1], smb.tr2eul(r, flip=True), atol=1e-12)
        assert 0 <= e.solutions[0][1] <= math.pi and e.solutions[1][1] <= 0
        for phi, th, psi in e.solutions:
            assert all(in_range(x) for x in (phi, th, psi))
            np.testing.assert_allclose(rz(phi) @ ry(th) @ rz(psi), r, atol=1e-12)


def test_rpy_numeric_matches_spatialmath_and_round_trips():
    smb = pytest.importorskip("spatialmath.base")
    for r in random_rotations(50):
        e = rpy_numeric(r)
        assert e.singular is False and len(e.solutions) == 2
        np.testing.assert_allclose(e.solutions[0], smb.tr2rpy(r, order="zyx"), atol=1e-12)
        assert abs(e.solutions[0][1]) <= math.pi / 2 <= abs(e.solutions[1][1])
        for roll, pitch, yaw in e.solutions:
            assert all(in_range(x) for x in (roll, pitch, yaw))
            np.testing.assert_allclose(rz(yaw) @ ry(pitch) @ rx(roll), r, atol=1e-12)


def test_axis_angle_and_quaternion_match_spatialmath():
    sm = pytest.importorskip("spatialmath")
    smb = pytest.importorskip("spatialmath.base")
    for q0 in random_quaternions(50):
        r = f(quaternion_matrix(q0.tolist()))
        aa = axis_angle_numeric(r)
        # exact reference: the quaternion the matrix was built from
        assert aa.angle == pytest.approx(2 * math.atan2(np.linalg.norm(q0[1:]), q0[0]), abs=1e-14)
        np.testing.assert_allclose(aa.axis, q0[1:] / np.linalg.norm(q0[1:]), atol=1e-13)
        theta, v = smb.tr2angvec(r)  # spatialmath loses ~1e-11 near pi
        assert aa.angle == pytest.approx(theta, abs=1e-9)
        np.testing.assert_allclose(aa.axis, v, atol=1e-9)
        q = quaternion_numeric(r)
        ref = sm.UnitQuaternion(r).vec
        ref = ref if ref[0] >= 0 else -ref
        assert q[0] >= 0
        np.testing.assert_allclose(q, ref, atol=1e-12)
        np.testing.assert_allclose(f(quaternion_matrix(q)), r, atol=1e-12)
        np.testing.assert_allclose(f(axis_angle_matrix(aa.axis, aa.angle)), r, atol=1e-12)


# ---------------------------------------------------------------- axis-angle special cases


def test_axis_angle_tiny_angle_keeps_precision():
    from scipy.spatial.transform import Rotation

    u = np.array([2.0, -1.0, 2.0]) / 3.0
    for alpha in (1e-9, 1e-11, 3e-8):
        r = Rotation.from_rotvec(alpha * u).as_matrix()
        aa = axis_angle_numeric(r)
        assert aa.case == "general"
        assert aa.angle == pytest.approx(alpha, rel=1e-9)
        np.testing.assert_allclose(aa.axis, u, atol=1e-6)
        q = quaternion_numeric(r)
        np.testing.assert_allclose(q[1:], math.sin(alpha / 2) * u, rtol=1e-6)


def test_axis_angle_near_and_at_pi():
    from scipy.spatial.transform import Rotation

    u = np.array([1.0, -2.0, 2.0]) / 3.0
    for alpha in (math.pi - 1e-9, math.pi - 1e-6, 3.0, 2.0):
        r = Rotation.from_rotvec(alpha * u).as_matrix()
        aa = axis_angle_numeric(r)
        assert aa.case == "general"
        assert aa.angle == pytest.approx(alpha, abs=1e-9)
        np.testing.assert_allclose(aa.axis, u, atol=1e-7)  # sign follows sin(alpha) > 0
        r2 = Rotation.from_rotvec(alpha * -u).as_matrix()
        np.testing.assert_allclose(axis_angle_numeric(r2).axis, -u, atol=1e-7)
    for uu in (u, -u):  # exactly pi: +-u are the same rotation, canonical sign
        r = f(axis_angle_matrix(sp.Matrix([1, -2, 2]) / 3 * (1 if uu[0] > 0 else -1), sp.pi))
        aa = axis_angle_numeric(r)
        assert aa.case == "half_turn" and aa.angle == math.pi
        np.testing.assert_allclose(aa.axis, u, atol=1e-12)
        q = quaternion_numeric(r)
        np.testing.assert_allclose(q, [0.0, *u], atol=1e-12)


def test_axis_angle_zero():
    aa = axis_angle_numeric(np.eye(3))
    assert aa.case == "zero" and aa.axis is None and aa.angle == 0.0
    assert quaternion_numeric(np.eye(4)) == [1.0, 0.0, 0.0, 0.0]
    s = axis_angle_symbolic(sp.eye(3))
    assert s.case == "zero" and s.axis is None and s.angle == 0


def test_axis_angle_symbolic_exact():
    # Rodrigues with an exact axis and angle, then back.
    u = sp.Matrix([2, -1, 2]) / 3
    for alpha in (sp.pi / 3, 2 * sp.pi / 3, sp.pi / 7):
        r = axis_angle_matrix(u, alpha)
        aa = axis_angle_symbolic(r)
        assert aa.case == "general"
        assert sp.simplify(aa.angle - alpha) == 0
        assert all(sp.simplify(a - b) == 0 for a, b in zip(aa.axis, u))
    aa = axis_angle_symbolic(axis_angle_matrix(-u, sp.pi))
    assert aa.case == "half_turn" and aa.angle == sp.pi
    assert [sp.simplify(a - b) for a, b in zip(aa.axis, u)] == [0, 0, 0]
    # half turn about an axis with a zero first component: sign from the second one
    aa = axis_angle_symbolic(axis_angle_matrix(sp.Matrix([0, -3, 4]) / 5, sp.pi))
    assert aa.axis == [0, sp.Rational(3, 5), sp.Rational(-4, 5)]


def test_quaternion_symbolic_exact():
    r = axis_angle_matrix(sp.Matrix([0, 0, 1]), sp.pi / 3)
    q = quaternion_symbolic(r)
    assert [sp.simplify(a - b) for a, b in zip(q, [sp.sqrt(3) / 2, 0, 0, sp.Rational(1, 2)])] == [0] * 4
    q = quaternion_symbolic(axis_angle_matrix(sp.Matrix([1, 0, 0]), sp.pi))
    assert q == [0, 1, 0, 0]


# ---------------------------------------------------------------- Euler singular cases


@pytest.mark.parametrize("phi,psi", [(0.4, 0.9), (-2.0, 1.0), (3.0, 0.5)])
def test_zyz_singular_theta_zero_and_pi(phi, psi):
    r = rz(phi) @ rz(psi)
    e = zyz_numeric(r)
    assert e.singular and len(e.solutions) == 1 and e.solutions[0][2] == 0.0
    assert e.family[0] == "phi + psi"
    assert e.family[1] == pytest.approx(wrap_angle(phi + psi), abs=1e-12)
    a, b, c = e.solutions[0]
    np.testing.assert_allclose(rz(a) @ ry(b) @ rz(c), r, atol=1e-12)
    r = rz(phi) @ ry(math.pi) @ rz(psi)
    e = zyz_numeric(r)
    assert e.singular and e.solutions[0][1] == math.pi and e.family[0] == "phi - psi"
    assert e.family[1] == pytest.approx(wrap_angle(phi - psi), abs=1e-12)
    a, b, c = e.solutions[0]
    np.testing.assert_allclose(rz(a) @ ry(b) @ rz(c), r, atol=1e-12)


@pytest.mark.parametrize("roll,yaw", [(0.4, 0.9), (-2.0, 1.0), (3.0, 0.5)])
def test_rpy_singular_pitch_half_pi(roll, yaw):
    for pitch, combo, val in ((math.pi / 2, "roll - yaw", roll - yaw),
                              (-math.pi / 2, "roll + yaw", roll + yaw)):
        r = rz(yaw) @ ry(pitch) @ rx(roll)
        e = rpy_numeric(r)
        assert e.singular and len(e.solutions) == 1
        assert e.solutions[0][1] == pitch and e.solutions[0][2] == 0.0
        assert e.family[0] == combo
        assert e.family[1] == pytest.approx(wrap_angle(val), abs=1e-7)
        a, b, c = e.solutions[0]
        np.testing.assert_allclose(rz(c) @ ry(b) @ rx(a), r, atol=1e-7)


def test_singular_symbolic_exact():
    e = zyz_symbolic(zyz_matrix(sp.pi / 3, 0, sp.pi / 6))
    assert e.singular and e.solutions == [[sp.pi / 2, 0, 0]] and e.family == ("phi + psi", sp.pi / 2)
    e = zyz_symbolic(zyz_matrix(sp.pi / 3, sp.pi, sp.pi / 6))
    assert e.singular and e.solutions == [[sp.pi / 6, sp.pi, 0]]
    e = zyz_symbolic(zyz_matrix(3 * sp.pi / 4, 0, sp.pi / 2))  # phi + psi = 5pi/4 -> -3pi/4
    assert e.solutions == [[-3 * sp.pi / 4, 0, 0]]
    e = rpy_symbolic(rpy_matrix(sp.pi / 3, sp.pi / 2, sp.pi / 6))
    assert e.singular and e.solutions == [[sp.pi / 6, sp.pi / 2, 0]] and e.family[0] == "roll - yaw"
    e = rpy_symbolic(rpy_matrix(sp.pi / 3, -sp.pi / 2, sp.pi / 6))
    assert e.singular and e.solutions == [[sp.pi / 2, -sp.pi / 2, 0]] and e.family[0] == "roll + yaw"
    # symbolic but identically singular: the family is a function of the symbols
    a, c = sp.symbols("a c", real=True)
    e = zyz_symbolic(zyz_matrix(a, 0, c))
    assert e.singular and e.family[0] == "phi + psi"
    assert sp.simplify(sp.cos(e.family[1]) - sp.cos(a + c)) == 0


def test_euler_symbolic_exact_generic():
    e = zyz_symbolic(zyz_matrix(sp.pi / 3, sp.pi / 4, -sp.pi / 6))
    assert e.singular is False
    assert e.solutions == [[sp.pi / 3, sp.pi / 4, -sp.pi / 6], [-2 * sp.pi / 3, -sp.pi / 4, 5 * sp.pi / 6]]
    e = rpy_symbolic(rpy_matrix(sp.pi / 6, -sp.pi / 3, 3 * sp.pi / 4))
    assert e.solutions[0] == [sp.pi / 6, -sp.pi / 3, 3 * sp.pi / 4]
    assert e.solutions[1] == [-5 * sp.pi / 6, -2 * sp.pi / 3, -sp.pi / 4]


def test_symbolic_matrix_agrees_with_numeric():
    a, b, c = sp.symbols("a b c", real=True)
    check_symbolic_against_numeric(zyz_matrix(a, b, c), {a: 0.7, b: -1.1, c: 2.5})


@pytest.mark.slow
def test_large_symbolic_matrix_agrees_with_numeric():
    a, b, c = sp.symbols("a b c", real=True)
    check_symbolic_against_numeric(zyz_matrix(a, b, c) * rpy_matrix(b, c, a), {a: 0.7, b: -1.1, c: 2.5})


def check_symbolic_against_numeric(r, vals):
    rn = f(r.subs(vals))
    for sym_fn, num_fn in ((zyz_symbolic, zyz_numeric), (rpy_symbolic, rpy_numeric)):
        es = sym_fn(r)
        assert es.singular is None and es.condition is not None and es.notes
        en = num_fn(rn)
        got = [[float(x.subs(vals)) for x in s] for s in es.solutions]
        np.testing.assert_allclose(got, en.solutions, atol=1e-10)
    aa = axis_angle_symbolic(r)
    assert aa.case == "generic"
    an = axis_angle_numeric(rn)
    assert float(aa.angle.subs(vals)) == pytest.approx(an.angle, abs=1e-10)
    np.testing.assert_allclose([float(x.subs(vals)) for x in aa.axis], an.axis, atol=1e-10)
    q = quaternion_symbolic(r)
    np.testing.assert_allclose([float(x.subs(vals)) for x in q], quaternion_numeric(rn), atol=1e-10)


def test_accepts_4x4_and_rejects_bad_shapes():
    r = random_rotations(1)[0]
    m = np.eye(4)
    m[:3, :3] = r
    m[:3, 3] = [1, 2, 3]
    assert zyz_numeric(m).solutions == zyz_numeric(r).solutions
    with pytest.raises(ValueError):
        zyz_numeric(np.eye(2))
    with pytest.raises(ValueError):
        rpy_symbolic(sp.eye(2))


def test_canonical_sign_and_wrap():
    np.testing.assert_allclose(canonical_sign([0.0, -1.0, 2.0]), [0.0, 1.0, -2.0])
    assert wrap_angle(math.pi) == math.pi
    assert wrap_angle(-math.pi) == math.pi
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
