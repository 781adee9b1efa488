"""Ellipsoid engine: ERRATA §B numbers, an SVD reference, the defining quadratic forms,
redundant and singular cases, q̇ for a desired velocity."""

import json

import numpy as np
import pytest
import sympy as sp

from robosolve.kinematics.ellipsoids_math import eig_sorted, ellipsoids, exact_values, joint_rates

S5, S2 = np.sqrt(5), np.sqrt(2)
J_ERRATA = np.array([[-0.5, -0.5], [0.5, 0.0]])          # planar 2R, L1 = L2 = 1/2, q = (0, π/2)


def _dirs_match(a, b):
    return np.allclose(a, b, atol=1e-4) or np.allclose(a, -np.asarray(b), atol=1e-4)


def test_errata_force_velocity_compliance_numbers():
    r = ellipsoids(J_ERRATA, kq=[1, 2])
    np.testing.assert_allclose(r.A, [[0.5, -0.25], [-0.25, 0.25]])
    np.testing.assert_allclose(r.eigenvalues, [(3 - S5) / 8, (3 + S5) / 8])
    np.testing.assert_allclose(r.force.lengths, [1 + S5, S5 - 1])
    assert _dirs_match(r.force.directions[0], [0.5257, 0.8507])
    assert _dirs_match(r.force.directions[1], [-0.8507, 0.5257])
    np.testing.assert_allclose(r.velocity.lengths, [(S5 + 1) / 4, (S5 - 1) / 4])
    assert r.condition_number == pytest.approx((7 + 3 * S5) / 2)
    np.testing.assert_allclose(r.Ks, [[0.75, -0.25], [-0.25, 0.25]])
    np.testing.assert_allclose(r.compliance.lengths, [0.5 + S2 / 4, 0.5 - S2 / 4])
    assert _dirs_match(r.compliance.directions[1], [0.3827, 0.9239])
    assert _dirs_match(r.compliance.directions[0], [-0.9239, 0.3827])


def test_errata_exact_values():
    J = sp.Matrix([[-sp.Rational(1, 2), -sp.Rational(1, 2)], [sp.Rational(1, 2), 0]])
    ex = exact_values(J, kq=[1, 2])
    assert [sp.simplify(a - b) for a, b in zip(ex["force"], [1 + sp.sqrt(5), sp.sqrt(5) - 1])] \
        == [0, 0]
    assert sp.simplify(ex["condition_number"] - (7 + 3 * sp.sqrt(5)) / 2) == 0
    assert [sp.simplify(a - b) for a, b in
            zip(ex["compliance"], [sp.Rational(1, 2) + sp.sqrt(2) / 4,
                                   sp.Rational(1, 2) - sp.sqrt(2) / 4])] == [0, 0]
    assert [sp.simplify(a - b) for a, b in
            zip(ex["velocity"], [(sp.sqrt(5) + 1) / 4, (sp.sqrt(5) - 1) / 4])] == [0, 0]


def test_sign_and_order_convention():
    r = ellipsoids(J_ERRATA, kf=2, kv=3, ka=5)
    for ax in (r.force, r.velocity, r.compliance):
        lens = ax.lengths
        assert lens == sorted(lens, reverse=True)
        for v in ax.directions:
            first = next(x for x in v if abs(x) > 1e-9 * max(map(abs, v)))
            assert first > 0
            assert np.linalg.norm(v) == pytest.approx(1.0)
    # budgets scale the lengths
    r1 = ellipsoids(J_ERRATA)
    np.testing.assert_allclose(r.force.lengths, 2 * np.array(r1.force.lengths))
    np.testing.assert_allclose(r.velocity.lengths, 3 * np.array(r1.velocity.lengths))
    np.testing.assert_allclose(r.compliance.lengths, 5 * np.array(r1.compliance.lengths))


@pytest.mark.parametrize("J", [
    np.array([[-0.65, -0.4, 0.0], [np.sqrt(3) / 4, 0.0, 0.0], [0.0, 0.0, -1.0]]),   # SCARA §B
    np.array([[-0.9, -0.4, -0.1], [0.3, 0.2, 0.25]]),                              # 2x3 redundant
])
def test_against_svd_and_quadratic_forms(J):
    kf, kv, ka = 2.0, 0.5, 3.0
    r = ellipsoids(J, kf=kf, kv=kv, ka=ka)
    U, sig, _ = np.linalg.svd(J)
    m = J.shape[0]
    # SVD reference: force Kf/σ along U (σ ascending), velocity Kv σ (σ descending)
    np.testing.assert_allclose(r.force.lengths, kf / np.sort(sig))
    np.testing.assert_allclose(r.velocity.lengths, kv * np.sort(sig)[::-1])
    assert r.condition_number == pytest.approx((sig.max() / sig.min()) ** 2)   # = cond(J)²
    for k in range(m):
        col = U[:, np.argsort(sig)[k]]
        assert _dirs_match(r.force.directions[k], col)
    A = J @ J.T
    for f in r.force.semi_axes:
        assert np.asarray(f) @ A @ np.asarray(f) == pytest.approx(kf**2)
    for v in r.velocity.semi_axes:
        qd = np.linalg.pinv(J) @ np.asarray(v)          # minimum-norm joint rates
        assert np.linalg.norm(qd) == pytest.approx(kv)
    Ks = J @ J.T
    for s in r.compliance.semi_axes:
        assert np.linalg.norm(np.linalg.solve(Ks, np.asarray(s))) == pytest.approx(ka)


def test_singular_configuration_is_degenerate_without_nan():
    J = np.array([[0.0, 0.0], [1.0, 0.5]])         # 2R at q = (0, 0): ERRATA item 112
    r = ellipsoids(J)
    assert r.singular and r.rank == 1
    assert r.force.lengths[0] is None and r.force.semi_axes[0] is None
    assert r.force.directions[0] == [1.0, 0.0]
    assert r.force.lengths[1] == pytest.approx(1 / np.sqrt(1.25))
    assert r.velocity.lengths == pytest.approx([np.sqrt(1.25), 0.0])
    assert r.condition_number is None
    assert r.notes and "Singular" in r.notes[0]
    json.dumps([r.force.as_dict(), r.velocity.as_dict(), r.compliance.as_dict(),
                r.condition_number], allow_nan=False)
    ex = exact_values(sp.Matrix([[0, 0], [1, sp.Rational(1, 2)]]))
    assert ex["force"][0] is None and ex["condition_number"] is None


def test_zero_jacobian():
    r = ellipsoids(np.zeros((2, 2)))
    assert r.force.lengths == [None, None]
    assert r.velocity.lengths == [0.0, 0.0]
    json.dumps(r.velocity.as_dict(), allow_nan=False)


def test_repeated_eigenvalues_canonical():
    w, vecs = eig_sorted(np.eye(3) * 2)
    assert [list(v) for v in vecs] == [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    # an isotropic 2R configuration: A = c I
    R = np.array([[np.cos(0.3), -np.sin(0.3)], [np.sin(0.3), np.cos(0.3)]])
    r = ellipsoids(R * 0.7)
    assert r.condition_number == pytest.approx(1.0)
    np.testing.assert_allclose(r.force.directions, [[1, 0], [0, 1]], atol=1e-12)


def test_joint_rates():
    qd, res, note = joint_rates(J_ERRATA, [0.1, 0.2])
    np.testing.assert_allclose(J_ERRATA @ qd, [0.1, 0.2])
    assert note is None
    J = np.array([[-0.9, -0.4, -0.1], [0.3, 0.2, 0.25]])
    qd, res, note = joint_rates(J, [0.1, 0.2])
    np.testing.assert_allclose(J @ qd, [0.1, 0.2], atol=1e-12)
    # minimum norm: orthogonal to the null space of J
    null = np.linalg.svd(J)[2][-1]
    assert abs(np.dot(qd, null)) < 1e-12
    assert "minimum norm" in note
    qd, res, note = joint_rates([[0.0, 0.0], [1.0, 0.5]], [1.0, 1.0])
    assert res == pytest.approx(1.0) and "singular" in note and "cannot be reached" in note
    assert all(np.isfinite(qd))
