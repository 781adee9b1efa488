"""Jacobians of task coordinates, geometric Jacobians, centre-of-mass Jacobians.

Conventions (spec §1 "Coordinates", docs/course-notes.md):

* analytic Jacobian J = dS/dQ of the coordinate vector S = F(Q): rows are the
  coordinates, columns the joints, in joint order (course-notes#note-jacobian-shape);
* geometric Jacobian (6 x m): column i = velocity of the point P and angular
  velocity of the moving frame produced by a unit rate of joint i alone. With
  ⁰Lᵢ = [[ω̂ᵢ], tᵢ; 0, 0] (∂M0i/∂qᵢ·M0i⁻¹), the column is (ω̂ᵢ·P + tᵢ, vex(ω̂ᵢ));
* centre-of-mass Jacobians are 3 x m: the derivative of the centre of mass,
  in frame 0, taken from the pseudo-inertia J (c = J[0:3, 3] / J[3, 3]).
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

from robosolve.core.simplify import jacobian_entry as tidy
from robosolve.core.transforms import vex

__all__ = [
    "analytic_jacobian", "geometric_jacobian", "com_position", "com_jacobian",
    "tidy", "tidy_matrix", "rank_measure", "numeric_manipulability",
]


def tidy_matrix(m: sp.Matrix) -> sp.Matrix:
    """Every entry through the policy's `jacobian_entry` variant."""
    return sp.Matrix(m).applyfunc(tidy)


def analytic_jacobian(coords: Sequence, q: Sequence[sp.Symbol]) -> sp.Matrix:
    """J = dS/dQ for S = coords (expressions in the joint symbols q)."""
    s = sp.Matrix(list(coords))
    return s.jacobian(list(q))


def geometric_jacobian(l_matrices: Sequence[sp.Matrix], point) -> sp.Matrix:
    """6 x m geometric Jacobian from the L matrices of the joints in frame 0.

    ``l_matrices[i]`` is ⁰Lᵢ (4x4, zero for joints that do not move the frame),
    ``point`` the 3-vector (frame 0) of the point whose linear velocity is wanted.
    """
    p = sp.Matrix([*list(point), 1])
    cols = []
    for lm in l_matrices:
        lm = sp.Matrix(lm)
        lin = (lm * p)[:3, 0]
        ang = vex(lm[:3, :3])
        cols.append(sp.Matrix.vstack(lin, ang))
    return sp.Matrix.hstack(*cols)


def com_position(pseudo_inertia: sp.Matrix, m0_frame: sp.Matrix) -> sp.Matrix:
    """Centre of mass in frame 0 from the body's pseudo-inertia (in its frame) and M0."""
    j = sp.Matrix(pseudo_inertia)
    c_local = j[:3, 3] / j[3, 3]
    return (sp.Matrix(m0_frame) * sp.Matrix([*c_local, 1]))[:3, 0]


def com_jacobian(pseudo_inertia: sp.Matrix, m0_frame: sp.Matrix, q: Sequence[sp.Symbol]) -> sp.Matrix:
    """3 x m Jacobian of the centre of mass (frame 0)."""
    return com_position(pseudo_inertia, m0_frame).jacobian(list(q))


def rank_measure(j: sp.Matrix):
    """The expression whose zeros are the singular configurations, and its name.

    Square J: ('det', det J). Otherwise ('gram', det(J Jᵀ)) for a wide J and
    det(Jᵀ J) for a tall one: the square of the manipulability, i.e. the sum of
    the squares of the maximal minors (Cauchy–Binet).
    """
    j = sp.Matrix(j)
    r, c = j.shape
    if r == c:
        return "det", j.det(method="berkowitz")
    g = j * j.T if r < c else j.T * j
    return "gram", g.det(method="berkowitz")


def numeric_manipulability(j) -> float:
    """Product of the singular values of a numeric J (0 at a singularity)."""
    import numpy as np

    a = np.asarray(j, dtype=float)
    if a.size == 0:
        return 0.0
    sv = np.linalg.svd(a, compute_uv=False)
    return float(np.prod(sv))
