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
        ls.append(sp.simplify(m.diff(q[i]) * m.inv()))
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
