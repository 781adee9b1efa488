"""Statics by virtual work: joint actions that balance external loads.

Spec §3 and docs/course-notes.md#note-statics-sign: Fq = −Jᵀ·Fs is what the joints must exert to
balance the load Fs applied at the point (the virtual work δQᵀFq + δSᵀFs = 0).

* a force in the task coordinates: Fq = −Jᵀ·F;
* a force F and a torque τ (frame 0) with the geometric Jacobian: Fq = −(J_Pᵀ·F + J_ωᵀ·τ);
* the bodies' own weight: Fq = −Σ J_Giᵀ·(mᵢ·g), with g the gravity vector and J_Gi the
  centre-of-mass Jacobians; this equals ∂U/∂q with U = Σ −mᵢ g·c_Gi.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp

__all__ = ["balance_force", "balance_wrench", "balance_weight"]


def balance_force(j: sp.Matrix, force) -> sp.Matrix:
    """Fq = −Jᵀ·F (F with one component per row of J)."""
    j = sp.Matrix(j)
    f = sp.Matrix(list(force))
    if f.shape[0] != j.shape[0]:
        raise ValueError(f"the force has {f.shape[0]} components, J has {j.shape[0]} rows")
    return -j.T * f


def balance_wrench(j_geometric: sp.Matrix, force=None, torque=None) -> sp.Matrix:
    """Fq = −(J_Pᵀ·F + J_ωᵀ·τ) with the 6 x n geometric Jacobian."""
    jg = sp.Matrix(j_geometric)
    out = sp.zeros(jg.shape[1], 1)
    if force is not None:
        out -= jg[:3, :].T * sp.Matrix(list(force))
    if torque is not None:
        out -= jg[3:, :].T * sp.Matrix(list(torque))
    return out


def balance_weight(com_jacobians: Sequence[sp.Matrix], masses: Sequence, gravity) -> sp.Matrix:
    """Fq = −Σ J_Giᵀ·mᵢ·g."""
    g = sp.Matrix(list(gravity))
    n = sp.Matrix(com_jacobians[0]).shape[1] if com_jacobians else 0
    out = sp.zeros(n, 1)
    for jg, m in zip(com_jacobians, masses):
        out -= sp.Matrix(jg).T * (m * g)
    return out
