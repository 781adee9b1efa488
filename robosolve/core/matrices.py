"""The course's 4x4 matrices beyond M: L, W, H, pseudo-inertia J, actions Phi.

Conventions are the spec's §3 and docs/course-notes.md:

* L of a joint = dM/dq * M^-1 (generated from M, never written by hand, §D.4);
* W = Mdot M^-1, H = Mddot M^-1 = Wdot + W^2, both expressed in the fixed frame;
* pseudo-inertia J = integral of p p^T dm with homogeneous p (§D.8);
* matrix of actions Phi = sum(F P^T - P F^T) + [C]  (§D.5);
* pseudo scalar product A (x) B over entries [3,2],[1,3],[2,1],[1,4],[2,4],[3,4]
  (1-based; course-notes#note-pseudo-scalar-product: [3,2], not [3,1]).
"""

from __future__ import annotations

import sympy as sp

from robosolve.core.simplify import tidy
from robosolve.core.transforms import rigid_inverse, skew

__all__ = [
    "l_matrix", "change_frame", "pseudo_inertia_point", "pseudo_inertia_rod",
    "pseudo_inertia_from_com", "pseudo_inertia_parts", "gravity_matrix",
    "action_matrix", "pseudo_scalar_product", "velocity_matrix",
]


def l_matrix(m: sp.Matrix, q: sp.Symbol) -> sp.Matrix:
    """L = dM/dq * M^-1 for a rototranslation M depending on joint variable q."""
    return (m.diff(q) * rigid_inverse(m)).applyfunc(lambda e: tidy(sp.expand(e)))


# dF/da F^-1 of each elementary motion F(a): constant twists (Rx: [e_x], Tx: e_x, ...).
_UNIT_TWIST = {
    "Rx": ((1, 0, 0), (0, 0, 0)), "Ry": ((0, 1, 0), (0, 0, 0)), "Rz": ((0, 0, 1), (0, 0, 0)),
    "Tx": ((0, 0, 0), (1, 0, 0)), "Ty": ((0, 0, 0), (0, 1, 0)), "Tz": ((0, 0, 0), (0, 0, 1)),
}


def l_matrix_of_factors(factors, q: sp.Symbol) -> sp.Matrix | None:
    """L = dM/dq M^-1 of M = F1 F2 ... (elementary motions `(op, arg)`) by structure,
    when q appears in one factor Fk only, linearly: L = P (c L_op) P^-1 with P = F1...Fk-1
    and c = d arg/dq (the same matrix as differentiating M, without simplifying products
    of sines). None when that shape does not apply (the caller differentiates M)."""
    from robosolve.core.transforms import ELEMENTARY

    hits = [k for k, (_, arg) in enumerate(factors) if sp.sympify(arg).has(q)]
    if len(hits) != 1:
        return None
    op, arg = factors[hits[0]]
    c = sp.diff(arg, q)
    if c.has(q) or op not in _UNIT_TWIST:
        return None
    prefix = sp.eye(4)
    for pop, parg in factors[:hits[0]]:
        prefix = prefix * ELEMENTARY[pop](parg)
    w, v = _UNIT_TWIST[op]
    r, t = prefix[:3, :3], prefix[:3, 3]
    omega = r * sp.Matrix(w) * c
    vel = r * sp.Matrix(v) * c - omega.cross(t)
    return velocity_matrix(omega.applyfunc(sp.expand), vel.applyfunc(sp.expand))


def change_frame(m: sp.Matrix, a: sp.Matrix) -> sp.Matrix:
    """Express a velocity-like 4x4 matrix (L, W, H) in another frame: M A M^-1."""
    return m * a * rigid_inverse(m)


def velocity_matrix(omega, v) -> sp.Matrix:
    """W = [[omega], v; 0 0 0 0] from an angular velocity and a velocity."""
    out = sp.zeros(4, 4)
    out[:3, :3] = skew(omega)
    out[:3, 3] = sp.Matrix(v)
    return out


def pseudo_inertia_point(mass, at) -> sp.Matrix:
    """J of a lumped mass at point `at`: m p p^T."""
    p = sp.Matrix([*at, 1])
    return mass * p * p.T


def pseudo_inertia_rod(mass, start, end) -> sp.Matrix:
    """J of a uniform thin rod from `start` to `end`.

    With p(s) = a + s (b - a), s in [0, 1]: integral p p^T m ds
    = m [a a^T + (a d^T + d a^T)/2 + d d^T/3], d = b - a (homogeneous, d[3] = 0).
    """
    a = sp.Matrix([*start, 1])
    d = sp.Matrix([*end, 1]) - a
    return mass * (a * a.T + (a * d.T + d * a.T) / 2 + d * d.T / 3)


def pseudo_inertia_from_com(mass, com, inertia=None) -> sp.Matrix:
    """J from the centre of mass c and the classical inertia tensor I_G about it.

    J3x3 = (tr I_G / 2) 1 - I_G + m c c^T, J[:3, 3] = m c, J[3, 3] = m (course-notes#note-pseudo-inertia).
    """
    c = sp.Matrix(com)
    ig = sp.zeros(3, 3) if inertia is None else sp.Matrix(inertia)
    out = sp.zeros(4, 4)
    out[:3, :3] = ig.trace() / 2 * sp.eye(3) - ig + mass * c * c.T
    out[:3, 3] = mass * c
    out[3, :3] = (mass * c).T
    out[3, 3] = mass
    return out


def pseudo_inertia_parts(j: sp.Matrix) -> dict:
    """Mass, centre of mass and classical inertia about the frame origin of a J."""
    m = j[3, 3]
    first = j[:3, 3]
    tr = j[0, 0] + j[1, 1] + j[2, 2]
    inertia_origin = tr * sp.eye(3) - j[:3, :3]
    return {"mass": m, "first_moment": first, "inertia_origin": inertia_origin}


def gravity_matrix(gravity) -> sp.Matrix:
    """H_g: zero but for the gravity vector in the last column (course-notes#note-gravity)."""
    out = sp.zeros(4, 4)
    out[:3, 3] = sp.Matrix(gravity)
    return out


def action_matrix(force=None, point=None, torque=None) -> sp.Matrix:
    """Phi = F P^T - P F^T + [C] for a force F at P and a pure torque C.

    The upper-left block is the skew matrix of the moment about the origin of the
    frame Phi is written in; the last column holds F, the last row -F^T.
    """
    out = sp.zeros(4, 4)
    if force is not None:
        f = sp.Matrix([*force, 0])
        p = sp.Matrix([*(point if point is not None else (0, 0, 0)), 1])
        out += f * p.T - p * f.T
    if torque is not None:
        out[:3, :3] += skew(torque)
    return out


# 0-based entries of the pseudo scalar product: [3,2],[1,3],[2,1],[1,4],[2,4],[3,4] (1-based).
_PSP_ENTRIES = ((2, 1), (0, 2), (1, 0), (0, 3), (1, 3), (2, 3))


def pseudo_scalar_product(a: sp.Matrix, b: sp.Matrix):
    """A (x) B = C.omega + F.v when A is an action matrix and B a velocity matrix."""
    return sp.Add(*[a[i, j] * b[i, j] for i, j in _PSP_ENTRIES])
