"""The naming's geometry for many configurations at once against the same, row by row (a
self-check of robosolve: the row-by-row route is itself checked by the named conditions of the
singularity tests against Robotics Toolbox)."""

from __future__ import annotations

import numpy as np
import sympy as sp

from robosolve.core.transforms import dh_standard
from robosolve.kinematics.naming import _dist_point_line, _far_distances, _far_point, _Geometry


def _arm():
    q = sp.symbols("q1:5")
    rows = [(q[0], sp.Rational(1, 3), 0, sp.pi / 2), (q[1], 0, sp.Rational(1, 2), 0),
            (q[2], 0, sp.Rational(2, 5), 0), (q[3], sp.Rational(1, 10), 0, 0)]
    frames, m = [], sp.eye(4)
    for th, d, a, al in rows:
        m = m * dh_standard(th, d, a, al)
        frames.append(m)
    return q, frames


def test_many_configurations_equal_row_by_row_for_both_routes():
    q, frames = _arm()
    kinds = {s: "revolute" for s in q}
    point = list(frames[-1][:3, 3])
    ls = []
    for i, m in enumerate(frames):      # ⁰Lᵢ = ∂⁰Mᵢ/∂qᵢ · ⁰Mᵢ⁻¹ (exact), for the given-L route
        r, t = m[:3, :3], m[:3, 3]
        inverse = sp.Matrix(sp.BlockMatrix([[r.T, -r.T * t], [sp.zeros(1, 3), sp.eye(1)]]))
        ls.append(m.diff(q[i]) * inverse)
    rng = np.random.default_rng(7)
    Q = rng.uniform(-3, 3, size=(9, 4))
    for geo in (_Geometry(q, kinds, None, point, {}, frames), _Geometry(q, kinds, ls, point, {})):
        P = geo.point_many(Q)
        for i in range(4):
            U, A = geo.axis_many(Q, i)
            for r in range(len(Q)):
                u, a = geo.axis(list(Q[r]), i)
                assert np.allclose(U[r], u, atol=1e-9) and np.allclose(A[r], a, atol=1e-9)
                assert np.allclose(P[r], geo.point(list(Q[r])), atol=1e-12)
        prev_axis = geo.axis(list(Q[0]), 0)
        d = _far_distances(geo, Q, 1, prev_axis)
        for r in range(len(Q)):
            assert abs(d[r] - _dist_point_line(*_far_point(geo, list(Q[r]), 1, 0, prev_axis))) < 1e-9


def test_axes_by_central_differences_match_the_exact_l_matrices():
    """Every joint's axis from the stacked central differences against the axis read off the
    exact ⁰Lᵢ = ∂⁰Mᵢ/∂qᵢ·⁰Mᵢ⁻¹ (sympy, evaluated at the configuration): direction and the
    distance of its point from the exact line."""
    q, frames = _arm()
    kinds = {s: "revolute" for s in q}
    geo = _Geometry(q, kinds, None, list(frames[-1][:3, 3]), {}, frames)
    poses = sp.lambdify([q], frames)
    derivatives = sp.lambdify([q], [m.diff(q[i]) for i, m in enumerate(frames)])     # exact ∂⁰Mᵢ/∂qᵢ
    rng = np.random.default_rng(3)
    for _ in range(5):
        qv = rng.uniform(-3, 3, size=4)
        axes = geo.axes(list(qv))
        assert [i for i, _u, _a in axes] == [0, 1, 2, 3]
        m_at, dm_at = poses(qv), derivatives(qv)
        for i, u, a in axes:
            exact = np.asarray(dm_at[i], dtype=float) @ np.linalg.inv(np.asarray(m_at[i], dtype=float))
            w = np.array([exact[2, 1], exact[0, 2], exact[1, 0]])
            w_unit = w / np.linalg.norm(w)
            point = np.cross(w_unit, exact[:3, 3] / np.linalg.norm(w))
            assert abs(abs(np.dot(u, w_unit)) - 1) < 1e-9
            assert _dist_point_line(a, w_unit, point) < 1e-7
            single = geo.axis(list(qv), i)
            assert np.allclose(single[0], u, atol=1e-12) and np.allclose(single[1], a, atol=1e-12)
