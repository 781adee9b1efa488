"""Numeric evaluation of the equations of motion (lambdify with cse, or numeric-only)."""

from __future__ import annotations

from typing import Mapping

import numpy as np
import sympy as sp

from robosolve.dynamics.api import Dynamics, NumericDynamics

__all__ = ["lambdify_dynamics", "numeric_from_engine", "free_symbols_left"]


def _subs(expr, rep):
    return expr.xreplace(rep) if rep else expr


def free_symbols_left(exprs, allowed) -> list[sp.Symbol]:
    """Symbols other than `allowed` still present (null parameters), sorted by name."""
    allowed = set(allowed)
    left = set()
    for e in exprs:
        left |= {s for s in e.free_symbols if s not in allowed}
    return sorted(left, key=lambda s: s.name)


def _lambdify(args, expr):
    # 'math' on scalars is the fastest for small matrices; the result is a nested list.
    return sp.lambdify(args, expr, modules=["math"], cse=True)


def lambdify_dynamics(dyn: Dynamics, subs: Mapping) -> NumericDynamics:
    """numpy callables for M, c, g, external and the actuators, parameters substituted."""
    rep = {sp.sympify(k): sp.sympify(v) for k, v in subs.items()}
    n = len(dyn.joints)
    q, qd, qdd = dyn.q, dyn.qd, dyn.qdd
    m = _subs(dyn.mass_matrix, rep)
    c = _subs(dyn.velocity_terms, rep)
    g = _subs(dyn.gravity_terms, rep)
    ext = _subs(dyn.external_forces, rep)
    left = free_symbols_left([*m, *c, *g, *ext], [*q, *qd])
    if left:
        raise ValueError("parameters without a value: " + ", ".join(s.name for s in left))
    tau = _subs(dyn.actuator_expressions(), rep)
    fm = _lambdify([q], m.tolist())
    fc = _lambdify([q, qd], list(c))
    fg = _lambdify([q], list(g))
    fe = _lambdify([q], list(ext))
    ft = _lambdify([q, qd, qdd], list(tau))
    def floats(v):
        # plain Python floats: the math module is much faster on them than on numpy scalars
        return v.tolist() if isinstance(v, np.ndarray) else [float(x) for x in v]

    return NumericDynamics(
        n=n,
        mass=lambda qv: np.array(fm(floats(qv)), dtype=float),
        velocity_terms=lambda qv, qdv: np.array(fc(floats(qv), floats(qdv)), dtype=float),
        gravity=lambda qv: np.array(fg(floats(qv)), dtype=float),
        external=lambda qv: np.array(fe(floats(qv)), dtype=float),
        actuators_fn=lambda qv, qdv, qddv: np.array(
            ft(floats(qv), floats(qdv), floats(qddv)), dtype=float),
    )


def numeric_from_engine(eng) -> NumericDynamics:
    """Numeric-only dynamics: only the small body-frame L matrices (and their derivatives)
    are symbolic; M, ∂M/∂q, c, g are assembled with numpy at each call.

    M_ik = Σ_b tr(ᵇLᵢ J_b ᵇLₖᵀ);  ∂M_ik/∂q_l = Σ_b tr(∂ᵇLᵢ J ᵇLₖᵀ) + tr(ᵇLᵢ J ∂ᵇLₖᵀ);
    c from the Christoffel symbols; g = ∂U/∂q with U = −Σ (g,0)·M₀ⱼ J[:,4].
    """
    n = eng.n
    q = eng.q
    frames = sorted({b.frame for b in eng.bodies} | {ld.frame for ld in eng.loads},
                    key=eng.order.index)
    # per frame: stack of L_b (n,4,4) and dL_b/dq (n,n,4,4) as one lambdified function
    lb_exprs = {f: [eng.Lb(i, f) if i in eng.moving(f) else sp.zeros(4, 4) for i in range(n)]
                for f in frames}
    dlb_exprs = {f: [[lb.diff(ql) for ql in q] for lb in lb_exprs[f]] for f in frames}
    f_lb = {f: _lambdify([q], [m.tolist() for m in lb_exprs[f]]) for f in frames}
    f_dlb = {f: _lambdify([q], [[m.tolist() for m in row] for row in dlb_exprs[f]])
             for f in frames}
    jb = []
    for b in eng.bodies:
        if b.J.free_symbols:
            raise ValueError("parameters without a value in the inertia of " + b.name)
        jb.append((b.frame, np.array(b.J.tolist(), dtype=float)))
    u = sp.Add(*eng.potential_energy().values())
    f_g = _lambdify([q], [u.diff(qi) for qi in q])
    f_ext = _lambdify([q], list(eng.external_forces()))

    def parts(qv):
        lbs = {f: np.array(f_lb[f](qv), dtype=float) for f in frames}
        return lbs

    def mass(qv):
        lbs = parts(qv)
        out = np.zeros((n, n))
        for f, j in jb:
            lb = lbs[f]
            out += np.einsum("irs,st,krt->ik", lb, j, lb)
        return out

    def velocity_terms(qv, qdv):
        qdv = np.asarray(qdv, dtype=float)
        dm = np.zeros((n, n, n))  # dm[i, k, l] = dM_ik/dq_l
        lbs = parts(qv)
        for f, j in jb:
            lb = lbs[f]
            dlb = np.array(f_dlb[f](qv), dtype=float)  # (i, l, 4, 4)
            t = np.einsum("ilrs,st,krt->ikl", dlb, j, lb)
            dm += t + t.transpose(1, 0, 2)
        # c_i = sum_jk (dM_ij/dq_k - 1/2 dM_jk/dq_i) qd_j qd_k
        return (np.einsum("ijk,j,k->i", dm, qdv, qdv)
                - 0.5 * np.einsum("jki,j,k->i", dm, qdv, qdv))

    return NumericDynamics(
        n=n, mass=mass, velocity_terms=velocity_terms,
        gravity=lambda qv: np.array(f_g(qv), dtype=float),
        external=lambda qv: np.array(f_ext(qv), dtype=float),
        note="numeric-only dynamics (mass matrix assembled numerically at each call)",
    )
