"""IK of a pose on arms robosolve has not seen (issue 26): cases kept from bench/ikprobe/probe.py.

The reference is independent of robosolve: a numpy forward kinematics of the DH table (standard or
modified) and, for the number of solutions, a batched Levenberg-Marquardt search on the 12 pose
equations from 300 random starts (deduplicated, wrapped). Each case also puts the configuration the
pose was computed from among the solutions.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from robosolve.core.angles import wrap_angle
from robosolve.core.transforms import dh_modified, dh_standard
from robosolve.ik.engine import IKJoint
from robosolve.ik.pose import solve_pose

PI = math.pi


# -- an independent reference -----------------------------------------------------------------

def _rx(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1, 0, 0, 0], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def _rz(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def _t(x, z):
    m = np.eye(4)
    m[0, 3], m[2, 3] = x, z
    return m


def fk(rows, conv, kinds, q):
    """rows: (theta, d, a, alpha) with the joint added to theta (R) or d (P)."""
    M = np.eye(4)
    for (th, d, a, al), k, v in zip(rows, kinds, q):
        th, d = (th + v, d) if k == "R" else (th, d + v)
        if conv == "standard":
            M = M @ _rz(th) @ _t(0, d) @ _t(a, 0) @ _rx(al)
        else:
            M = M @ _rx(al) @ _t(a, 0) @ _rz(th) @ _t(0, d)
    return M


def _fk_batch(rows, conv, kinds, Q):
    """The forward kinematics of many configurations at once (Q: starts × joints)."""
    S = Q.shape[0]
    M = np.broadcast_to(np.eye(4), (S, 4, 4)).copy()
    for k, ((th, d, a, al), kind) in enumerate(zip(rows, kinds)):
        th = th + Q[:, k] if kind == "R" else np.full(S, th)
        d = d + Q[:, k] if kind == "P" else np.full(S, d)
        c, s, ca, sa = np.cos(th), np.sin(th), math.cos(al), math.sin(al)
        A = np.zeros((S, 4, 4))
        A[:, 3, 3] = 1.0
        if conv == "standard":  # Rz(th) Tz(d) Tx(a) Rx(al)
            A[:, 0] = np.stack([c, -s * ca, s * sa, a * c], axis=1)
            A[:, 1] = np.stack([s, c * ca, -c * sa, a * s], axis=1)
            A[:, 2, 1], A[:, 2, 2], A[:, 2, 3] = sa, ca, d
        else:  # Rx(al) Tx(a) Rz(th) Tz(d)
            A[:, 0, 0], A[:, 0, 1], A[:, 0, 3] = c, -s, a
            A[:, 1] = np.stack([s * ca, c * ca, np.full(S, -sa), -sa * d], axis=1)
            A[:, 2] = np.stack([s * sa, c * sa, np.full(S, ca), ca * d], axis=1)
        M = M @ A
    return M


def reference_solutions(rows, conv, kinds, T, boxes, starts=300, seed=0):
    """Every solution a 300-start Levenberg-Marquardt search finds (wrapped, deduplicated to 1e-6).

    The starts run side by side (one numpy array); each keeps its own damping."""
    rng = np.random.default_rng(seed)
    n = len(rows)
    lo, hi = np.array([b[0] for b in boxes]), np.array([b[1] for b in boxes])
    tgt = T[:3, :4].reshape(12)
    assert np.allclose(_fk_batch(rows, conv, kinds, np.zeros((1, n)))[0],
                       fk(rows, conv, kinds, np.zeros(n)))

    def res(Q):
        return _fk_batch(rows, conv, kinds, Q)[:, :3, :4].reshape(len(Q), 12) - tgt

    def jac(Q, R):
        J = np.empty((len(Q), 12, n))
        for k in range(n):
            H = Q.copy()
            H[:, k] += 1e-7
            J[:, :, k] = (res(H) - R) / 1e-7
        return J

    Q = lo + rng.uniform(size=(starts, n)) * (hi - lo)
    lam, R = np.full(starts, 1e-2), res(Q)
    live = np.ones(starts, bool)
    for _ in range(150):
        idx = np.flatnonzero(live)
        if idx.size == 0:
            break
        q, r, la = Q[idx], R[idx], lam[idx]
        J = jac(q, r)
        JT = np.transpose(J, (0, 2, 1))
        A = JT @ J + la[:, None, None] * np.eye(n)
        step = -np.linalg.solve(A, (JT @ r[:, :, None]))[:, :, 0]
        norm = np.linalg.norm(step, axis=1)
        step *= np.minimum(1.0, 0.5 / np.maximum(norm, 1e-300))[:, None]
        rn = res(q + step)
        better = np.einsum("ij,ij->i", rn, rn) < np.einsum("ij,ij->i", r, r)
        Q[idx[better]] += step[better]
        R[idx[better]] = rn[better]
        lam[idx] = np.where(better, np.maximum(la / 3, 1e-12), np.minimum(la * 5, 1e8))
        live[idx] = np.einsum("ij,ij->i", R[idx], R[idx]) >= 1e-26
    sols = []
    for q, r in zip(Q, R):
        if np.max(np.abs(r)) > 1e-10:
            continue
        qw = np.array([wrap_angle(v) if k == "R" else v for v, k in zip(q, kinds)])
        if not any(_close(qw, s, kinds, 1e-6) for s in sols):
            sols.append(qw)
    return sols


def _close(a, b, kinds, tol):
    return all(abs(wrap_angle(x - y) if k == "R" else x - y) < tol for x, y, k in zip(a, b, kinds))


def _factors(rows, conv, kinds):
    qs = sp.symbols(f"q1:{len(rows) + 1}")
    out = []
    for (th, d, a, al), k, q in zip(rows, kinds, qs):
        th, d = (q + th, d) if k == "R" else (th, q + d)
        out.append(dh_standard(th, d, a, al) if conv == "standard" else dh_modified(al, a, th, d))
    return out, qs


def _solve(rows, conv, kinds, T, limits=None):
    F, qs = _factors(rows, conv, kinds)
    limits = limits or [None] * len(rows)
    joints = [IKJoint(q, k == "R", lim) for q, k, lim in zip(qs, kinds, limits)]
    return solve_pose(F, joints, T[:3, :3], T[:3, 3]), [str(q) for q in qs]


def _check(res, names, rows, conv, kinds, T, q0):
    assert res.status == "ok", res.reason
    for s in res.solutions:
        q = [s[n] for n in names]
        assert np.max(np.abs(fk(rows, conv, kinds, q)[:3, :4] - T[:3, :4])) < 1e-9
    q0w = [wrap_angle(v) if k == "R" else v for v, k in zip(q0, kinds)]
    assert any(_close([s[n] for n in names], q0w, kinds, 1e-9) for s in res.solutions)


# -- the UR family in modified DH: the closed form of the planar 3R at the first reachable branch --

UR_MDH = [(0.0, 0.12010218949650998, 0.0, 0.0), (0.0, 0.0, 0.0, PI / 2), (0.0, 0.0, -0.44259548721581754, 0.0),
          (0.0, 0.15871849111603006, -0.5846628774655147, 0.0), (0.0, 0.10412268555474341, 0.0, PI / 2),
          (0.0, 0.04153368060680562, 0.0, -PI / 2)]


def test_ur_family_closed_form_when_the_first_q1_branch_cannot_reach():
    """q1, q5, q6 have 4 branches here; for the first the planar arm of q2, q3, q4 cannot reach.
    The closed form must still be derived (it was taken from the first branch only: none)."""
    kinds = "RRRRRR"
    q0 = [0.717385422314309, -0.06200474158147351, 0.37616619062224466, -1.2133139237764157,
          -2.577903327242565, 1.4108495094364326]
    T = fk(UR_MDH, "modified", kinds, q0)
    res, names = _solve(UR_MDH, "modified", kinds, T)
    assert res.method == "three parallel axes"
    _check(res, names, UR_MDH, "modified", kinds, T, q0)
    assert res.closed_form, res.notes
    ref = reference_solutions(UR_MDH, "modified", kinds, T, [(-PI, PI)] * 6)
    assert len(res.solutions) == len(ref) == 4
    for r in ref:
        assert any(_close([s[n] for n in names], r, kinds, 1e-6) for s in res.solutions)


# -- the Stanford arm: a spherical wrist after a prismatic joint ------------------------------------

STANFORD = [(0.0, 0.412, 0.0, -PI / 2), (0.0, 0.154, 0.0, PI / 2), (0.0, 0.0, 0.0, 0.0),
            (0.0, 0.0, 0.0, -PI / 2), (0.0, 0.0, 0.0, PI / 2), (0.0, 0.263, 0.0, 0.0)]


@pytest.mark.parametrize("limits, count", [(None, 8), ((0.1, 1.2), 4)])
def test_stanford_arm_is_decoupled_at_its_wrist(limits, count):
    kinds = "RRPRRR"
    q0 = [0.4, -1.1, 0.7, 0.9, -0.6, 1.3]
    T = fk(STANFORD, "standard", kinds, q0)
    lims = [None, None, limits, None, None, None]
    res, names = _solve(STANFORD, "standard", kinds, T, lims)
    assert res.method == "decoupling" and res.closed_form
    _check(res, names, STANFORD, "standard", kinds, T, q0)
    assert len(res.solutions) == count
    ref = reference_solutions(STANFORD, "standard", kinds, T, [(-PI, PI)] * 2 + [(-1.5, 1.5)] + [(-PI, PI)] * 3)
    inside = [r for r in ref if limits is None or limits[0] <= r[2] <= limits[1]]
    assert len(inside) == count
    for r in inside:
        assert any(_close([s[n] for n in names], r, kinds, 1e-6) for s in res.solutions)


# -- fewer joints than a pose has coordinates: unreachable, with the reason, and fast ---------------

ARM5 = [(0.0, 0.3, 0.1, PI / 2), (0.0, 0.0, 0.45, 0.0), (0.0, 0.05, 0.0, PI / 2), (0.0, 0.4, 0.0, -PI / 2),
        (0.0, 0.0, 0.0, PI / 2)]


def test_five_joint_arm_reaches_the_pose_of_one_of_its_configurations():
    kinds = "RRRRR"
    q0 = [0.5, -0.7, 1.1, 0.3, -1.2]
    T = fk(ARM5, "standard", kinds, q0)
    res, names = _solve(ARM5, "standard", kinds, T)
    _check(res, names, ARM5, "standard", kinds, T, q0)


@pytest.mark.parametrize("scale, words", [(1.0, "not with this orientation"), (5.0, "beyond the reach")])
def test_five_joint_arm_unreachable_pose_says_why(scale, words):
    """A random orientation at a reachable position (or a position 5 times as far): no solution. The
    reason says the arm has too few joints for a pose, and whether the position itself is reachable
    (not the over-determined system's 'choose 5 of the 12 equations', which solved 20 subsets)."""
    kinds = "RRRRR"
    T = _rz(0.7) @ _rx(2.1) @ _rz(-1.3)
    T[:3, 3] = scale * fk(ARM5, "standard", kinds, [0.2, 0.4, -0.9, 1.0, 0.6])[:3, 3]
    ref = reference_solutions(ARM5, "standard", kinds, T, [(-PI, PI)] * 5, starts=100)
    assert ref == []
    res, _ = _solve(ARM5, "standard", kinds, T)
    assert res.status == "unreachable" and res.solutions == []
    assert "5 joints" in res.reason and words in res.reason, res.reason
    assert "Choose" not in res.reason


# -- the UR5 at its wrist singularity: the other branch of q1 has 4 isolated solutions ---------------

UR5 = [(0.0, 0.089159, 0.0, PI / 2), (0.0, 0.0, -0.425, 0.0), (0.0, 0.0, -0.39225, 0.0),
       (0.0, 0.10915, 0.0, PI / 2), (0.0, 0.09465, 0.0, -PI / 2), (0.0, 0.0823, 0.0, 0.0)]


@pytest.mark.parametrize("q5", [0.0, PI])
def test_ur5_wrist_singularity_keeps_the_isolated_solutions_of_the_other_q1(q5):
    """At q5 = 0 (or pi) on one branch of q1 the pose is reached along a continuum; on the other
    branch q5 is not 0 and there are 4 isolated solutions, which the reference finds too. They were
    lost (one point of the continuum only, from the numeric fallback)."""
    kinds = "RRRRRR"
    q0 = [0.4, -1.1, 1.3, -0.8, q5, 0.5]
    T = fk(UR5, "standard", kinds, q0)
    res, names = _solve(UR5, "standard", kinds, T)
    assert res.status == "ok" and res.method == "three parallel axes"
    for s in res.solutions:
        assert np.max(np.abs(fk(UR5, "standard", kinds, [s[n] for n in names])[:3] - T[:3])) < 1e-9
    ref = reference_solutions(UR5, "standard", kinds, T, [(-PI, PI)] * 6, starts=120)
    isolated = [r for r in ref if abs(wrap_angle(r[0] - 0.4)) > 1e-3]
    assert len(isolated) == 4
    for r in isolated:
        assert any(_close([s[n] for n in names], r, kinds, 1e-6) for s in res.solutions), r
    singular = [s for s, f in zip(res.all_solutions, res.wrist_singular) if f]
    assert len(singular) == 2 and all(s["q6"] == 0.0 and abs(s["q1"] - 0.4) < 1e-9 for s in singular)
    assert len(res.solutions) == 6 and any("continuum" in n for n in res.notes)


# -- the UR family: the planar 3R with its orientation angle, the course's way --------------------

UR_FLIPPED = [(0.0, 0.1625, 0.0, PI / 2), (0.0, 0.0, -0.425, PI), (0.0, 0.0, -0.3922, PI),
              (0.0, 0.1333, 0.0, PI / 2), (0.0, 0.0997, 0.0, -PI / 2), (0.0, 0.0996, 0.0, 0.0)]


@pytest.mark.parametrize("rows", [UR_FLIPPED, UR_MDH], ids=["flipped-axes", "modified-dh"])
def test_ur_family_planar_arm_solved_from_its_angle(rows):
    """The rotation of ¹M₄ about the parallel axes is one angle ±q2 ± q3 ± q4 (joint axes turned
    by π count with a minus sign): q4 comes from it linearly, then the planar 2R; every solution
    against the independent reference."""
    conv = "modified" if rows is UR_MDH else "standard"
    kinds = "RRRRRR"
    q0 = [0.5, -0.9, 1.2, -0.4, 0.8, -1.3]
    T = fk(rows, conv, kinds, q0)
    res, names = _solve(rows, conv, kinds, T)
    assert res.method == "three parallel axes"
    _check(res, names, rows, conv, kinds, T, q0)
    assert any("appears linearly" in s.title for s in res.steps), [s.title for s in res.steps]
    ref = reference_solutions(rows, conv, kinds, T, [(-PI, PI)] * 6)
    assert len(res.solutions) == len(ref)
    for r in ref:
        assert any(_close([s[n] for n in names], r, kinds, 1e-6) for s in res.solutions)


def test_angle_sum_is_read_with_its_signs_and_constant():
    from robosolve.ik.pose import _angle_sum

    q2, q3, q4 = sp.symbols("q2 q3 q4")
    theta = q2 - q3 + q4 + sp.pi / 2
    c, s = sp.expand(sp.expand_trig(sp.cos(theta))), sp.expand(sp.expand_trig(sp.sin(theta)))
    got = _angle_sum(c, s, [q2, q3, q4])
    assert got is not None and sp.simplify(got - theta) == 0
    # not one angle: cos(2 q2) and the cosine of a sum with a non-unit coefficient
    assert _angle_sum(sp.cos(2 * q2), sp.sin(2 * q2), [q2, q3, q4]) is None
    assert _angle_sum(sp.cos(q2) * sp.cos(q3), sp.sin(q2), [q2, q3, q4]) is None


def test_forward_kinematics_of_the_polish_against_the_reference_and_finite_differences():
    """The polish's ⁰M(q) (a numeric product of the local matrices) against the numpy reference
    of this file, and its Jacobian against central differences of it."""
    from robosolve.ik.pose import _FK, _Chain

    for rows, conv in ((UR_FLIPPED, "standard"), (UR_MDH, "modified"), (STANFORD, "standard")):
        kinds = "RRPRRR" if rows is STANFORD else "RRRRRR"
        F, qs = _factors(rows, conv, kinds)
        fk_ = _FK(_Chain([sp.Matrix(f) for f in F], [IKJoint(q, k == "R", None) for q, k in zip(qs, kinds)], list(qs)))
        q = np.array([0.3, -1.2, 0.8, 2.1, -0.4, 1.7])
        ref = fk(rows, conv, kinds, list(q))[:3, :].reshape(12)
        assert np.max(np.abs(fk_.residual(q, np.zeros(12)) - ref)) < 1e-12
        J = fk_.jac(*q)
        h = 1e-6
        for i in range(6):
            e = np.zeros(6)
            e[i] = h
            fd = (fk(rows, conv, kinds, list(q + e))[:3, :] - fk(rows, conv, kinds, list(q - e))[:3, :]).reshape(12) / (2 * h)
            assert np.max(np.abs(J[:, i] - fd)) < 1e-8, (conv, i)
